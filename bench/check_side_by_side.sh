#!/usr/bin/env bash
# Two shoal binaries' `check` as whole processes, runs interleaved, best of N; then whether
# their reports (REPORT.geojson, the events) are the same bytes. Not part of the tests.
#   bench/check_side_by_side.sh N DIMS TRACKS BEFORE_SHOAL BEFORE_GRID AFTER_SHOAL AFTER_GRID [AFTER_OPTION...]
# Each binary reads its own grid (a grid file's format may differ between versions: make each
# with its own `shoal import`). AFTER_OPTION (e.g. --no-project) goes to the second only, so
# that both write the same outputs. Reports go to a temporary folder, removed at the end.
set -euo pipefail
[ $# -ge 7 ] || { sed -n '2,7p' "$0"; exit 2; }
n="$1" dims="$2" tracks="$3" before="$4" before_grid="$5" after="$6" after_grid="$7"
shift 7
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
now() { date +%s%N; }
best_b="" best_a=""
for ((i = 0; i < n; ++i)); do
  s=$(now); "$before" check --coast "$before_grid" --dims "$dims" "$tracks" -o "$out/before.geojson" --jobs 2 > /dev/null 2>&1 || [ $? -eq 1 ]; e=$(now)
  t=$((e - s)); [ -z "$best_b" ] || [ "$t" -lt "$best_b" ] && best_b=$t
  s=$(now); "$after" check --coast "$after_grid" --dims "$dims" "$tracks" -o "$out/after.geojson" --jobs 2 "$@" > /dev/null 2>&1 || [ $? -eq 1 ]; e=$(now)
  t=$((e - s)); [ -z "$best_a" ] || [ "$t" -lt "$best_a" ] && best_a=$t
done
same=different; cmp -s "$out/before.geojson" "$out/after.geojson" && same=identical
awk -v b="$best_b" -v a="$best_a" -v f="$(basename "$tracks")" -v s="$same" -v n="$n" \
  'BEGIN { printf "%s: before %.2f s, after %.2f s (best of %d): %.2fx; reports %s\n", f, b / 1e9, a / 1e9, n, b / a, s }'
