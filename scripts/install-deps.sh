#!/usr/bin/env bash
# Installs shoal's dependencies from Debian 12 packages; nothing else is downloaded at build or
# test time. What it installs is what it is asked for:
#   scripts/install-deps.sh --build    the library, the CLI and the example (examples/run-example.sh):
#                                      compiler, CMake, Ninja, GDAL/GEOS/PROJ, Eigen, nlohmann-json,
#                                      CLI11, xxHash, zlib; for a build configured with
#                                      -DSHOAL_BUILD_TESTS=OFF -DSHOAL_BUILD_BENCH=OFF -DSHOAL_BUILD_PYTHON=OFF
#   scripts/install-deps.sh [--tests]  everything the test suite needs (scripts/test.sh): the above,
#                                      GoogleTest, Benchmark, clang, the Python module's pybind11 and
#                                      its pandas/geopandas, QGIS, Dask, Chromium, ...
#   --list                             with either: print the package names, install nothing
# README.md ("First commands") gives what each set pulls on a bare Debian 12 and how it was counted.
set -euo pipefail
BUILD=(
  build-essential cmake ninja-build pkg-config
  libgdal-dev                 # GDAL/OGR: every vector format, CRS, PROJ (find_package(GDAL CONFIG))
  libgeos-dev                 # GEOS C API: clipping, validity
  libproj-dev                 # PROJ (find_package(PROJ CONFIG)), geodesic.h
  libeigen3-dev nlohmann-json3-dev libcli11-dev libxxhash-dev
  zlib1g-dev                  # deflating the .qgz of the QGIS project stored in a GeoPackage report
  libexpat1-dev               # expat: where each point of a GPX file is written (GDAL reads the points)
)
TESTS=(
  ccache                      # compiler cache, used by CMakeLists.txt when found
  gdal-bin                    # ogr2ogr/ogrinfo, used by tests
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-jsonschema python3-gdal   # report schema validation in tests (/usr/bin/python3)
  gpsd-clients python3-ais    # independent AIS decoders for tests/track/ais_test.cpp (gpsdecode, libais)
  clang libclang-rt-14-dev    # libFuzzer + sanitizers for scripts/fuzz.sh
  pybind11-dev python3-dev    # the Python module shoal (python/), built whenever both are found
  python3-numpy python3-pandas python3-geopandas   # its arrays and DataFrames, and its tests (/usr/bin/python3)
  python3-rtree               # geopandas' spatial index: gpd.sjoin in docs/python.md (a Recommends, not a Depends, of python3-geopandas)
  python3-matplotlib          # GeoDataFrame.plot in docs/python.md (a Recommends too)
  python3-venv                # docs/python.md's virtual environment, made by tests/python/test_docs_python.py
  python3-qgis                # tests/report/qgis/qgis_report_test.py: the report opened and rendered in a real QGIS 3.22 (headless, offscreen)
  python3-distributed         # python3 -m shoal.dask: Dask/distributed 2022.12 (LocalCluster, scheduler) and its tests
  python3-dask                # the Dask core python3-distributed runs on
  chromium                    # tests/picture/debrief_test.cpp: the debrief sheet opened in a real headless browser (skipped without it)
)
set_name=tests
list=0
for arg in "$@"; do
  case "$arg" in
    --build) set_name=build ;;
    --tests) set_name=tests ;;
    --list) list=1 ;;
    -h|--help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "install-deps.sh: unknown option '$arg' (use --build, --tests, --list)" >&2; exit 2 ;;
  esac
done
PACKAGES=("${BUILD[@]}")
[ "$set_name" = tests ] && PACKAGES+=("${TESTS[@]}")
if [ $list -eq 1 ]; then
  printf '%s\n' "${PACKAGES[@]}"
  exit 0
fi
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
