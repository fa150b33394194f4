#!/usr/bin/env bash
# The example audit, end to end on a fresh Debian 12 machine: installs the build's packages, builds
# shoal (Release), imports the Helsinki coastline into a grid, audits ten minutes of real AIS
# traffic off Helsinki and an hour of a sailing yacht's NMEA log, and checks a few single
# poses. Outputs go to examples/out/: open helsinki-traffic.gpkg, or plaka.geojson (styled by
# the plaka.qml beside it), in QGIS.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here/.."
# Only what the library and the CLI need (scripts/install-deps.sh --build: no test framework,
# no Python module, no QGIS/Dask/Chromium); ./scripts/test.sh installs everything.
./scripts/install-deps.sh --build
# SHOAL_BUILD_DIR: an existing build to use instead (CI uses the test suite's, not a second
# compile of the library); by default a Release build in build-release/, at -O2 as Debian builds
# its packages (12 % less compile time than CMake's -O3, the same speed and the same report
# bytes) and with the CLI's commands compiled as one unit (SHOAL_CLI_UNITY_BUILD: CLI11 parsed
# once, not in every command's file): 2 min 3 s against 2 min 55 s for this target on 2 cores
# (docs/performance.md).
build="${SHOAL_BUILD_DIR:-build-release}"
if [ -z "${SHOAL_BUILD_DIR:-}" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" -DSHOAL_CLI_UNITY_BUILD=ON \
    -DSHOAL_BUILD_TESTS=OFF -DSHOAL_BUILD_BENCH=OFF -DSHOAL_BUILD_PYTHON=OFF > /dev/null
fi
cmake --build "$build" --target shoal_cli
shoal="$build/cli/shoal"
out="$here/out"
mkdir -p "$out"

echo "== shoal import: Helsinki coastline (GSHHG full resolution) into a grid =="
"$shoal" import "$here/data/gof_helsinki_land.geojson" --ship-length 185 -o "$out/helsinki.shoalgrid"
echo
echo "== shoal info =="
"$shoal" info "$out/helsinki.shoalgrid"

# shoal check exits 1 when it finds a grounding: that is a result here, not a failure.
audit() { "$shoal" "$@" || { status=$?; [ $status -eq 1 ] || exit $status; echo "(exit status 1: groundings found)"; }; }
echo
echo "== shoal check: 10 minutes of AIS traffic (96 vessels), each as the example ferry =="
audit check --coast "$out/helsinki.shoalgrid" --ship "$here/ship.json" "$here/data/aava_n2k_fixes.csv" \
  -o "$out/helsinki-traffic.gpkg" --margin 50 --plot "$out/helsinki-traffic.svg"
echo
echo "== shoal check: a sailing yacht's NMEA 0183 log (the log has no date: times of day) =="
audit check --coast "$out/helsinki.shoalgrid" --ship "$here/yacht.json" "$here/data/plaka_first_hour.nmea" \
  -o "$out/plaka.geojson" --margin 50 --plot "$out/plaka.svg"
echo
echo "== shoal probe: single poses of the example ferry =="
"$shoal" probe --coast "$out/helsinki.shoalgrid" --ship "$here/ship.json" "$here/poses.csv" -o "$out/poses-checked.csv"
cat "$out/poses-checked.csv"
echo
echo "Reports for QGIS: $out/helsinki-traffic.gpkg (layers events, tracks, hulls, styled) and $out/plaka.geojson (+ plaka.qml); pictures: $out/*.svg"
