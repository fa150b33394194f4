#!/usr/bin/env bash
# `shoal probe` against the GEOS-only probe (bench_geos_probe), whole processes, side by side in
# one run: the same coastline, the same poses, the same hull; runs interleaved, best of N; the
# answers compared row by row (collision equal, clearance within 1 mm of each other).
#
#   bench/probe_vs_geos.sh BUILD_DIR COAST.geojson POSES.csv [RUNS] [DIMS] [JOBS] [CHECKER]
#
# CHECKER (default pieces): bench_geos_probe's --checker: `pieces` (coastline pieces in an
# STRtree, nearest first, early exit) or `polygons` (prepared land polygons in an STRtree,
# PreparedIntersects then PreparedDistance in a growing box: issue 40's peer).
#
# JOBS (default 1): threads for both, `shoal probe --jobs` and the GEOS probe's `--jobs` (one
# STRtree and GEOS context a thread).
#
# Both are timed on the whole POSES.csv and on its first pose alone: the difference, divided by
# the number of poses, is the cost of a pose without the start-up (reading the coast, building
# the index). shoal reads the grid `shoal import` made of the coast (a user imports once);
# the GEOS probe builds its trees from the coastline file, which is its import.
set -euo pipefail
build=$1 coast=$2 poses=$3 runs=${4:-5} dims=${5:-150,40,14,18} jobs=${6:-1} checker=${7:-pieces}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
"$build/cli/shoal" import "$coast" -o "$work/coast.shoalgrid" > /dev/null
head -2 "$poses" > "$work/one.csv"
n=$(($(wc -l < "$poses") - 1))
now() { date +%s%N; }  # nanoseconds
best() { printf '%s\n' "$@" | sort -n | head -1; }
declare -a s_all s_one g_all g_one
for ((r = 0; r < runs; ++r)); do
  t=$(now); "$build/cli/shoal" probe --coast "$work/coast.shoalgrid" --dims "$dims" --jobs "$jobs" "$poses" -o "$work/shoal.csv"; s_all+=($(($(now) - t)))
  t=$(now); "$build/bench/bench_geos_probe" --coast "$coast" --dims "$dims" --jobs "$jobs" --checker "$checker" "$poses" -o "$work/geos.csv"; g_all+=($(($(now) - t)))
  t=$(now); "$build/cli/shoal" probe --coast "$work/coast.shoalgrid" --dims "$dims" --jobs "$jobs" "$work/one.csv" -o "$work/s1.csv"; s_one+=($(($(now) - t)))
  t=$(now); "$build/bench/bench_geos_probe" --coast "$coast" --dims "$dims" --jobs "$jobs" --checker "$checker" "$work/one.csv" -o "$work/g1.csv"; g_one+=($(($(now) - t)))
done
sa=$(best "${s_all[@]}") so=$(best "${s_one[@]}") ga=$(best "${g_all[@]}") go=$(best "${g_one[@]}")
/usr/bin/python3 - "$work/shoal.csv" "$work/geos.csv" "$n" "$sa" "$so" "$ga" "$go" "$jobs" <<'PY'
import csv, sys
a, b = list(csv.DictReader(open(sys.argv[1]))), list(csv.DictReader(open(sys.argv[2])))
n = int(sys.argv[3]); sa, so, ga, go = (int(v) / 1e9 for v in sys.argv[4:8])  # ns -> s
assert len(a) == len(b) == n, (len(a), len(b), n)
bad = touching = 0
for x, y in zip(a, b):
    if x['covered'] != '1':
        continue
    touching += x['collision'] == '1'
    if x['collision'] != y['collision'] or abs(float(x['clearance_m']) - float(y['clearance_m'])) > 0.0015:
        bad += 1
ps, pg = (sa - so) / n * 1e6, (ga - go) / n * 1e6
print(f"poses {n} (touching {touching}), disagreements {bad}, threads {sys.argv[8]}")
print(f"shoal probe: {sa:.3f} s all, {so:.3f} s one pose, {ps:.2f} us/pose")
print(f"GEOS probe:  {ga:.3f} s all, {go:.3f} s one pose, {pg:.2f} us/pose")
print(f"whole process: GEOS / shoal = {ga / sa:.1f}; per pose: {pg / ps:.1f}")
sys.exit(1 if bad else 0)
PY
