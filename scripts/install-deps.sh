#!/usr/bin/env bash
# Installs every build and test dependency of shoal from Debian 12 packages.
# Nothing else is downloaded at build or test time.
set -euo pipefail
PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config
  libgdal-dev gdal-bin        # GDAL/OGR: every vector format, CRS, PROJ
  libgeos-dev                 # GEOS C API: clipping, validity, test oracle
  libproj-dev                 # geodesic.h (tests), PROJ through GDAL
  libeigen3-dev nlohmann-json3-dev libcli11-dev libxxhash-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-jsonschema python3-gdal   # report schema validation in tests (/usr/bin/python3)
  gpsd-clients python3-ais    # independent AIS decoders for tests/track/ais_test.cpp (gpsdecode, libais)
  clang libclang-rt-14-dev    # libFuzzer + sanitizers for scripts/fuzz.sh
  pybind11-dev python3-dev    # the Python module shoal (python/), built whenever both are found
  python3-numpy python3-pandas python3-geopandas   # its arrays and DataFrames, and its tests (/usr/bin/python3)
  zlib1g-dev                  # deflating the .qgz of the QGIS project stored in a GeoPackage report
  python3-qgis                # tests/report/qgis_report_test.py: the report opened and rendered in a real QGIS 3.22 (headless, offscreen)
  python3-distributed         # python3 -m shoal.dask: Dask/distributed 2022.12 (LocalCluster, scheduler) and its tests
  python3-dask                # the Dask core python3-distributed runs on
  chromium                    # tests/report/debrief_test.cpp: the debrief sheet opened in a real headless browser (skipped without it)
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
