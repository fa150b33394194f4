#!/usr/bin/env bash
# Fuzzes shoal's parsers of untrusted input with libFuzzer under AddressSanitizer +
# UndefinedBehaviorSanitizer (clang from Debian: clang, libclang-rt-14-dev).
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     default: 60 s for each of the eleven targets
#
# Targets: csv_tracks nmea aivdm geojson_tracks gpx_tracks vessels ship grid_cache roles assessment poses merge_parts zip_members debrief_record partitions (fuzz/fuzz_<target>.cpp). Builds in build-fuzz/,
# then for each target replays fuzz/corpus/<target>/ and fuzz/regressions/<target>/ (any
# failure there is a regression) and fuzzes for SECONDS. New inputs go to
# build-fuzz/corpus/<target>/ (not committed); a crash is saved under
# build-fuzz/artifacts/<target>/ and the script fails: fix it, then keep the input in
# fuzz/regressions/<target>/ so tests/fuzz_replay_test.cpp replays it in every build.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(csv_tracks nmea aivdm geojson_tracks gpx_tracks vessels ship grid_cache roles assessment poses merge_parts zip_members debrief_record partitions)

./scripts/install-deps.sh
build=build-fuzz
sanitize="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHOAL_FUZZ=ON \
  -DSHOAL_BUILD_TESTS=OFF -DSHOAL_BUILD_BENCH=OFF -DCMAKE_C_FLAGS="$sanitize" -DCMAKE_CXX_FLAGS="$sanitize" >/dev/null
cmake --build "$build" -j "$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}")

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions="$PWD/.ci/lsan.supp"
for t in "${targets[@]}"; do
  bin="$build/fuzz/fuzz_$t"
  work="$build/corpus/$t"
  artifacts="$build/artifacts/$t/"
  mkdir -p "$work" "$artifacts" "fuzz/regressions/$t"
  dict=()
  [ -f "fuzz/$t.dict" ] && dict=(-dict="fuzz/$t.dict")
  echo "== fuzz_$t: replay fuzz/corpus/$t and fuzz/regressions/$t =="
  # -runs=0: run every saved input once, fuzz nothing.
  status=0
  "$bin" -runs=0 -timeout=10 -rss_limit_mb=2048 "fuzz/corpus/$t" "fuzz/regressions/$t" >"$build/replay-$t.log" 2>&1 || status=$?
  if [ $status -ne 0 ]; then
    tail -n 40 "$build/replay-$t.log" >&2
    echo "fuzz_$t: a saved input fails (status $status): a regression" >&2
    exit 1
  fi
  grep -E '^#[0-9]+[[:space:]]+(INITED|DONE)' "$build/replay-$t.log" | tail -n 1
  echo "== fuzz_$t: $secs s =="
  # Each line of the log is prefixed with the seconds since the start, so the plateau shows:
  # the time of the last line that found new coverage.
  start=$SECONDS
  "$bin" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=16384 -print_final_stats=1 \
    -artifact_prefix="$artifacts" "${dict[@]}" "$work" "fuzz/corpus/$t" "fuzz/regressions/$t" 2>&1 |
    while IFS= read -r line; do printf '%s\t%s\n' "$((SECONDS - start))" "$line"; done >"$build/fuzz-$t.log" || status=$?
  grep -E '#[0-9]+[[:space:]]+(INITED|DONE)|stat::(number_of_executed_units|peak_rss_mb|new_units_added)|==[0-9]+== ?ERROR|SUMMARY|runtime error|Test unit written' \
    "$build/fuzz-$t.log" || true
  awk -v t="fuzz_$t" '
    function cov(s) { return match(s, /cov: [0-9]+/) ? substr(s, RSTART + 5, RLENGTH - 5) : "" }
    { at = $1; s = substr($0, index($0, "\t") + 1) }
    s ~ /^#[0-9]+[ \t]+INITED/ { c0 = cov(s) }
    s ~ /^#[0-9]+[ \t]+NEW/ { c = cov(s); if (c + 0 > best + 0) { best = c; when = at } }
    s ~ /^#[0-9]+[ \t]+DONE/ { cend = cov(s); end = at }
    s ~ /^stat::number_of_executed_units/ { runs = $NF }
    END { printf "%s: %s runs in %s s; edges covered: %s after the saved inputs, %s at the end, the last new one at %s s\n",
                 t, runs, end, c0, cend, (when == "" ? "-" : when) }
  ' "$build/fuzz-$t.log"
  if [ $status -ne 0 ] || [ -n "$(ls -A "$artifacts" 2>/dev/null)" ]; then
    tail -n 60 "$build/fuzz-$t.log" >&2
    echo "fuzz_$t found a failing input (status $status): $(ls "$artifacts")" >&2
    echo "reproduce with: $bin $artifacts<file>; after the fix keep it in fuzz/regressions/$t/" >&2
    exit 1
  fi
done
echo "fuzzing passed"
