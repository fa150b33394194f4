#!/usr/bin/env bash
# The example audit, end to end on a fresh Debian 12 machine: installs the packages, builds
# shoal (Release), imports the Helsinki coastline into a grid, shows what it holds and checks
# a few poses. Outputs go to examples/out/.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here/.."
./scripts/install-deps.sh
cmake -S . -B build-release -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHOAL_BUILD_TESTS=OFF -DSHOAL_BUILD_BENCH=OFF > /dev/null
cmake --build build-release --target shoal_cli
shoal=build-release/cli/shoal
out="$here/out"
mkdir -p "$out"

echo "== shoal import: Helsinki coastline (GSHHG full resolution) into a grid =="
"$shoal" import "$here/data/gof_helsinki_land.geojson" --ship-length 185 -o "$out/helsinki.shoalgrid"
echo
echo "== shoal info =="
"$shoal" info "$out/helsinki.shoalgrid"
echo
echo "== shoal probe: single poses of the example ship =="
"$shoal" probe --coast "$out/helsinki.shoalgrid" --ship "$here/ship.json" "$here/poses.csv" -o "$out/poses-checked.csv"
cat "$out/poses-checked.csv"
