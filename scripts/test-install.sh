#!/usr/bin/env bash
# The installed package as a simulator developer uses it (run by ctest as `install_test`):
# `cmake --install BUILD --prefix P`, then the per-frame examples of examples/simulator built
# against P: the C++ one with find_package(Shoal CONFIG) and the C one both with CMake and with
# `pkg-config --cflags --libs shoal_c`; the C program's answers must equal `shoal probe`'s; the
# berthing simulation's contact log must give hand-derived answers.
# The C programs run with no LD_LIBRARY_PATH (shoal_c.pc's rpath, CMake's own), and neither
# they nor libshoal_c.so.1 may need GDAL (the C API's lean runtime: PROJ and GEOS only).
#   scripts/test-install.sh BUILD_DIR [WORK_DIR]
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "$1" && pwd)"
work="${2:-$(mktemp -d)}"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work"
prefix="$work/prefix"
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for f in include/shoal/shoal.h include/shoal/version.hpp include/shoal/check/detector.hpp lib/libshoal.a lib/libshoal_c.so.1 \
         bin/shoal lib/shoal/libshoal_cli_full.so \
         lib/cmake/Shoal/ShoalConfig.cmake lib/cmake/Shoal/ShoalConfigVersion.cmake lib/pkgconfig/shoal.pc lib/pkgconfig/shoal_c.pc; do
  [ -e "$prefix/$f" ] || { echo "test-install: $f was not installed"; exit 1; }
done
if find "$prefix/include" -path '*detail*' | grep -q .; then echo "test-install: internal headers were installed"; exit 1; fi
# Only the C API is exported from libshoal_c.
if nm -D --defined-only "$prefix/lib/libshoal_c.so.1" | awk '$2 ~ /[TDB]/ {print $3}' | grep -v '^shoal_' | grep -q .; then
  echo "test-install: libshoal_c exports more than shoal_*:"; nm -D --defined-only "$prefix/lib/libshoal_c.so.1" | grep -v ' shoal_' | head; exit 1
fi
# A separate project with find_package(Shoal 0.2 CONFIG REQUIRED).
cmake -S "$src/examples/simulator" -B "$work/sim" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" > "$work/sim-configure.log"
cmake --build "$work/sim" > "$work/sim-build.log"
# The C program with pkg-config only.
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
cc -std=c11 -Wall -Wextra -Werror "$src/examples/simulator/frame_check.c" $(pkg-config --cflags --libs shoal_c) -lm -o "$work/frame_check_pc"
# No GDAL in the C API's runtime, and libshoal_c found in the prefix without LD_LIBRARY_PATH.
unset LD_LIBRARY_PATH
if readelf -d "$prefix/lib/libshoal_c.so.1" | grep NEEDED | grep -qi gdal; then
  echo "test-install: libshoal_c.so.1 needs GDAL:"; readelf -d "$prefix/lib/libshoal_c.so.1" | grep NEEDED; exit 1
fi
for exe in "$work/frame_check_pc" "$work/sim/frame_check_c"; do
  ldd "$exe" > "$work/ldd.txt"
  if grep -qi 'libgdal' "$work/ldd.txt"; then echo "test-install: $exe loads GDAL:"; grep -i gdal "$work/ldd.txt"; exit 1; fi
  # PROJ and GEOS only where used: PROJ by the module libshoal_crs.so for a grid in a user's CRS
  # (below), GEOS never (the C API builds no grid).
  if grep -Eqi 'libproj|libgeos' "$work/ldd.txt"; then echo "test-install: $exe loads PROJ or GEOS at start:"; grep -Ei 'proj|geos' "$work/ldd.txt"; exit 1; fi
  if grep -q 'not found' "$work/ldd.txt"; then echo "test-install: $exe cannot start without LD_LIBRARY_PATH:"; grep 'not found' "$work/ldd.txt"; exit 1; fi
  loaded="$(awk '$1 == "libshoal_c.so.1" {print $3}' "$work/ldd.txt")"
  if [ -z "$loaded" ] || [ "$(realpath "$loaded")" != "$(realpath "$prefix/lib/libshoal_c.so.1")" ]; then
    echo "test-install: $exe does not load the installed libshoal_c.so.1:"; grep shoal_c "$work/ldd.txt"; exit 1
  fi
  echo "test-install: $(basename "$exe"): $(grep -c '=>' "$work/ldd.txt") shared libraries, no GDAL"
done
# The installed `shoal` links no GDAL (a probe of a grid runs in it); its other commands run in
# the module it finds in ../lib/shoal (import, below, is one).
if ldd "$prefix/bin/shoal" | grep -qi 'libgdal'; then echo "test-install: bin/shoal loads GDAL:"; ldd "$prefix/bin/shoal" | grep -i gdal; exit 1; fi
"$prefix/bin/shoal" import "$src/examples/data/gof_helsinki_land.geojson" -o "$work/helsinki.shoalgrid" > /dev/null
# Poses: the example's, and a few hundred around Helsinki (some outside the chart).
{
  cat "$src/examples/poses.csv"
  awk 'BEGIN { srand(7); for (i = 0; i < 400; i++) printf "%.6f,%.6f,%.1f\n", 59.35 + rand() * 1.0, 23.1 + rand() * 2.8, rand() * 360 }'
} > "$work/poses.csv"
"$prefix/bin/shoal" probe --coast "$work/helsinki.shoalgrid" --dims 150,35,14,15 "$work/poses.csv" -o "$work/probe.csv"
if LD_DEBUG=libs "$prefix/bin/shoal" probe --coast "$work/helsinki.shoalgrid" --dims 150,35,14,15 "$work/poses.csv" 2>&1 >/dev/null | grep -qi 'libgdal'; then
  echo "test-install: a probe of a grid loaded GDAL"; exit 1
fi
for exe in "$work/frame_check_pc" "$work/sim/frame_check_c"; do
  "$exe" "$work/helsinki.shoalgrid" "$work/poses.csv" > "$work/c.csv" 2> "$work/c.err"
  if ! cmp -s "$work/probe.csv" "$work/c.csv"; then
    echo "test-install: $exe disagrees with shoal probe:"; diff "$work/probe.csv" "$work/c.csv" | head; exit 1
  fi
  cat "$work/c.err"
done
"$work/sim/frame_check_cpp" "$work/helsinki.shoalgrid" 3000
# A grid in a user's CRS (UTM 35N): libshoal_c loads PROJ for it, through the installed module
# lib/shoal/libshoal_crs.so, and gives shoal probe's answers; for the grid in shoal's own frame
# above it loaded no PROJ.
"$prefix/bin/shoal" import "$src/examples/data/gof_helsinki_land.geojson" --crs EPSG:32635 -o "$work/helsinki-utm.shoalgrid" > /dev/null 2>&1
"$prefix/bin/shoal" probe --coast "$work/helsinki-utm.shoalgrid" --dims 150,35,14,15 "$work/poses.csv" -o "$work/probe-utm.csv"
LD_DEBUG=libs "$work/frame_check_pc" "$work/helsinki-utm.shoalgrid" "$work/poses.csv" > "$work/c-utm.csv" 2> "$work/c-utm.err"
cmp -s "$work/probe-utm.csv" "$work/c-utm.csv" || { echo "test-install: frame_check disagrees with shoal probe on a UTM grid:"; diff "$work/probe-utm.csv" "$work/c-utm.csv" | head; exit 1; }
crs_module="$(sed -n 's/.*calling init: \(.*libshoal_crs\.so\)$/\1/p' "$work/c-utm.err" | head -1)"
[ -n "$crs_module" ] && [ "$(realpath "$crs_module")" = "$(realpath "$prefix/lib/shoal/libshoal_crs.so")" ] ||
  { echo "test-install: the UTM grid did not load the installed PROJ module"; grep -i crs "$work/c-utm.err" | head; exit 1; }
grep -q 'calling init: .*libproj' "$work/c-utm.err" || { echo "test-install: the UTM grid did not load PROJ"; exit 1; }
if LD_DEBUG=libs "$work/frame_check_pc" "$work/helsinki.shoalgrid" "$work/poses.csv" 2>&1 >/dev/null | grep -qi 'libproj'; then
  echo "test-install: a grid in shoal's own frame loaded PROJ"; exit 1
fi
# The Python module, when this build has it: importable by Debian's python3 from the prefix, and
# its Detector gives shoal probe's answers on the same poses.
if [ -e "$build/python/shoal/__init__.py" ]; then
  pydir="$prefix/lib/python3/dist-packages"
  [ -e "$pydir/shoal/__init__.py" ] && ls "$pydir"/shoal/_shoal*.so > /dev/null || { echo "test-install: the Python module was not installed in $pydir"; exit 1; }
  PYTHONPATH="$pydir" /usr/bin/python3 -c '
import csv, sys, numpy as np, shoal
assert shoal.__file__.startswith(sys.argv[1]), shoal.__file__
grid = shoal.Grid.load(sys.argv[2])
rows = list(csv.DictReader(open(sys.argv[4])))
p = np.loadtxt(sys.argv[3], delimiter=",", ndmin=2, skiprows=1)
r = shoal.Detector(grid, dims=(150, 35, 14, 15)).check(p[:, 0], p[:, 1], p[:, 2])
for k, row in enumerate(rows):
    assert (row["covered"] == "1") == bool(r["covered"][k]), k
    if row["collision"]:
        assert (row["collision"] == "1") == bool(r["contact"][k]), k
        assert abs(float(row["clearance_m"]) - r["clearance_m"][k]) <= 0.0005 or np.isinf(r["clearance_m"][k]), k
print("test-install: shoal %s imported from %s, %d poses agree with shoal probe" % (shoal.__version__, sys.argv[1], len(rows)))
' "$pydir" "$work/helsinki.shoalgrid" "$work/poses.csv" "$work/probe.csv"
fi
# The berthing simulation (examples/simulator/berthing_sim.c, also with pkg-config only) on the
# made-up quay and pier of berth.geojson: it asserts its own limits (no contact deepens more than
# 5 cm a frame, none goes through), and its contact log must give the hand-derived answers of
# check_berthing.awk (first contact frames, normals, hazard kinds and names, the resting depth).
cc -std=c11 -Wall -Wextra -Werror "$src/examples/simulator/berthing_sim.c" $(pkg-config --cflags --libs shoal_c) -lm -o "$work/berthing_sim_pc"
"$prefix/bin/shoal" import "$src/examples/simulator/berth.geojson" --ship-length 185 -o "$work/berth.shoalgrid" > /dev/null
for exe in "$work/berthing_sim_pc" "$work/sim/berthing_sim"; do
  "$exe" "$work/berth.shoalgrid" > "$work/berthing.log" || { echo "test-install: $exe failed"; tail -5 "$work/berthing.log"; exit 1; }
  awk -f "$src/examples/simulator/check_berthing.awk" "$work/berthing.log" || { echo "test-install: $exe: its contact log is wrong"; exit 1; }
done
echo "test-install: installed package OK ($(wc -l < "$work/probe.csv") poses agree with shoal probe)"
