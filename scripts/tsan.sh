#!/usr/bin/env bash
# The parallel audit under ThreadSanitizer (GCC, -fsanitize=thread), in build-tsan/:
#   1. `shoal check --jobs 2` on the example's 96 AIS vessels, plain and in exercise mode
#      (--encounters), GeoJSON and GeoPackage, with the grid built (and cached) by the run; the
#      GeoJSON run's layer files (a pose at every fix) compared with those of --jobs 1;
#   2. the tests that run the audit on several threads (audit_test, cli_test, bad_input_test;
#      cli_test also runs `shoal probe --jobs 2` and 3), those that read a CSV file on two
#      threads (track_test), poses placed in blocks on threads (check_test), and the report's
#      events and the chart layer's tiles made on threads (report_test), and the threads' pool
#      itself (util_test Parallel*). The module loads GDAL, GEOS and PROJ from whichever thread
#      first needs them (src/util/lazy_libraries.hpp): the runs above do it from the chart's.
# Any data race or other report from ThreadSanitizer makes it fail (halt_on_error).
# GDAL, GEOS and PROJ are not instrumented: races inside them are not seen, only ours.
#
#   scripts/tsan.sh
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
build=build-tsan
# -O1 -g1: ThreadSanitizer's advice (-O1 or more), with line tables for its stack traces. The
# module `shoal` loads for its commands (libshoal_cli_full.so) is linked with the runtime too.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHOAL_BUILD_BENCH=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS="-fsanitize=thread -fno-omit-frame-pointer" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" \
  -DCMAKE_MODULE_LINKER_FLAGS="-fsanitize=thread" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=thread" >/dev/null
cmake --build "$build" -j "$(nproc)" --target shoal_cli audit_test cli_test bad_input_test track_test check_test report_test util_test
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 history_size=4 suppressions=$PWD/.ci/tsan.supp"
shoal="$build/cli/shoal"
out="$build/tsan-out"
rm -rf "$out"
mkdir -p "$out"
export SHOAL_CACHE_DIR="$out/cache"
ex=examples
run() {  # exit status 1 (groundings found) is a result, not a failure
  "$shoal" "$@" || { s=$?; [ $s -eq 1 ] || { echo "tsan: shoal $* failed with status $s" >&2; exit $s; }; }
}
echo "== shoal check --jobs 2 under ThreadSanitizer =="
run check --coast "$ex/data/gof_helsinki_land.geojson" --ship "$ex/ship.json" "$ex/data/aava_n2k_fixes.csv" \
  -o "$out/traffic.geojson" --jobs 2 --margin 50 --poses-interval 0
run check --coast "$ex/data/gof_helsinki_land.geojson" --ship "$ex/ship.json" "$ex/data/aava_n2k_fixes.csv" \
  "$ex/data/plaka_first_hour.nmea" -o "$out/traffic.gpkg" --jobs 2 --encounters --plot "$out/traffic.svg"
run check --coast "$ex/data/gof_helsinki_land.geojson" --ship "$ex/ship.json" "$ex/data/aava_n2k_fixes.csv" \
  -o "$out/traffic-1.geojson" --jobs 1 --margin 50 --poses-interval 0
cmp "$out/traffic.geojson" "$out/traffic-1.geojson"
# The QGIS project's layer files, written in blocks on two threads while the report is written
# on a third (a pose at every fix: many blocks).
for layer in hulls poses tracks coast; do
  cmp "$out/traffic.$layer.geojson" "$out/traffic-1.$layer.geojson"
done
echo "reports of --jobs 1 and --jobs 2 (and their layer files) are byte-identical"
echo "== tests that run the audit on several threads, under ThreadSanitizer =="
# Each test program in two halves at once (GoogleTest's sharding): the machine's two cores,
# where one program at a time left one idle (the six programs took 363 s of wall time that way).
# bad_input_test without the option-parsing table (every value is refused or taken before a
# thread starts; the ASan suite runs it) and the two million-line AIS logs (one file is read by
# one thread; the ASan suite runs them).
halves() {
  local pids=() s
  for i in 0 1; do
    GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=$i "$@" --gtest_brief=1 & pids+=($!)
  done
  for p in "${pids[@]}"; do wait "$p" || s=$?; done
  return "${s:-0}"
}
halves "$build/tests/audit_test"
halves "$build/tests/cli_test"
halves "$build/tests/bad_input_test" --gtest_filter='-BadInput.EveryNumericOption*:BadInput.*CostNoMemoryPerLine*'
"$build/tests/track_test" --gtest_brief=1 --gtest_filter='Input.ACsvReadByTwoThreads*:PackedTrack.TracksNormalisedOnThreads*'
"$build/tests/check_test" --gtest_brief=1 --gtest_filter='Placement.InBlocks*'
"$build/tests/util_test" --gtest_brief=1 --gtest_filter='Parallel*'
"$build/tests/report_test" --gtest_brief=1 --gtest_filter='ReportFields.TheStreamedGeoJsonIsTheDocumentsDump:ChartLayer.*'
echo "ThreadSanitizer: no report"
