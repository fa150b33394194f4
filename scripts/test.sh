#!/usr/bin/env bash
# The whole test suite: installs the Debian packages it needs, configures, builds, runs ctest.
#   scripts/test.sh              RelWithDebInfo build in build/
#   scripts/test.sh --sanitize   AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/,
#                                without the tests labelled `external` (they drive QGIS, Dask,
#                                headless Chromium, the installed package: programs built without
#                                the sanitizers, which the plain suite runs; tests/CMakeLists.txt)
set -euo pipefail
cd "$(dirname "$0")/.."
"./scripts/install-deps.sh"
build=build
ctest_args=()
# Line tables only (-g1), not full debug information: the suite's builds compile in about 60 % of
# the time, and sanitizer reports and backtraces still name files and lines.
flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG")
if [ "${1:-}" = "--sanitize" ]; then
  build=build-asan
  flags=(-DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-g1" -DSHOAL_SANITIZE=ON -DSHOAL_BUILD_BENCH=OFF)
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  export LSAN_OPTIONS=suppressions="$PWD/.ci/lsan.supp"
  ctest_args=(-LE external)
fi
cmake -S . -B "$build" -G Ninja -DSHOAL_WERROR=ON "${flags[@]}"
cmake --build "$build" -j "$(nproc)"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "${ctest_args[@]}"
