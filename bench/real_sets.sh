#!/usr/bin/env bash
# The six real track sets of ../shared/data/tracks, each against its GSHHG coast, every hull
# --dims 100,20,8,8, as a new user would run them; prints the events of each kind per set and
# every grounding with its evidence. Reads ../shared/data (or SHOAL_DATA); not part of the tests.
#   bench/real_sets.sh [SHOAL_BINARY] [OUT_DIR]
# The Danish coast is not in ../shared/data: it is cut from Debian's GSHHG 2.3.7 full resolution
# (packages gmt, gmt-gshhg-full) over the Danish waters of the data's README
# (10.5-13.2 E, 54.8-56.8 N) and polygonised with OGR; the script does it once into OUT_DIR.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shoal="${1:-$here/build-release/cli/shoal}"
out="${2:-/tmp/shoal-real-sets}"
data="${SHOAL_DATA:-$here/../shared/data}"
[ -d "$data/tracks" ] || { echo "real_sets: no data at $data (set SHOAL_DATA)"; exit 0; }
mkdir -p "$out"
g="$data/coast/gshhg"
dk="$out/dk_land.geojson"
if [ ! -f "$dk" ]; then
  command -v gmt > /dev/null || { echo "real_sets: the Danish coast needs Debian's gmt and gmt-gshhg-full (apt-get install gmt gmt-gshhg-full)"; exit 1; }
  (cd "$out" && gmt coast -R10.5/13.2/54.8/56.8 -Df -M -W -A0/1/1 > dk_shore.gmt)  # GMT leaves gmt.history in its folder
  /usr/bin/python3 - "$out" <<'PY'
import subprocess, sys
from osgeo import ogr, osr
out = sys.argv[1]
ds = ogr.Open(out + '/dk_shore.gmt')
ml = ogr.Geometry(ogr.wkbMultiLineString)
for f in ds.GetLayer():
    ml.AddGeometry(f.GetGeometryRef())
ml.AddGeometry(ogr.CreateGeometryFromWkt('LINESTRING(10.5 54.8,13.2 54.8,13.2 56.8,10.5 56.8,10.5 54.8)'))
faces = ml.Union(ogr.CreateGeometryFromWkt('POINT(10.5 54.8)')).Polygonize()  # node the lines, then faces
pts = ''.join('%r %r %d\n' % (faces.GetGeometryRef(i).PointOnSurface().GetX(), faces.GetGeometryRef(i).PointOnSurface().GetY(), i)
              for i in range(faces.GetGeometryCount()))
open(out + '/dk_faces.txt', 'w').write(pts)
sel = subprocess.run(['gmt', 'select', out + '/dk_faces.txt', '-R10.5/13.2/54.8/56.8', '-Df', '-Ns/k'], capture_output=True, text=True, check=True, cwd=out)
land = sorted(int(l.split()[2]) for l in sel.stdout.splitlines() if l.strip() and not l.startswith('>'))
srs = osr.SpatialReference(); srs.ImportFromEPSG(4326)
o = ogr.GetDriverByName('GeoJSON').CreateDataSource(out + '/dk_land.geojson')
lay = o.CreateLayer('land', srs, ogr.wkbPolygon)
for i in land:
    f = ogr.Feature(lay.GetLayerDefn()); f.SetGeometry(faces.GetGeometryRef(i)); lay.CreateFeature(f)
o = None
print('Danish coast: %d land polygons of %d faces' % (len(land), faces.GetGeometryCount()))
PY
fi
run() {
  local name=$1 coast=$2 tracks=$3
  set +e
  "$shoal" check --coast "$coast" --dims 100,20,8,8 "$tracks" -o "$out/$name.geojson" --no-progress > "$out/$name.txt" 2> "$out/$name.err"
  echo "$name: exit status $?"
  set -e
}
t="$data/tracks"
run helsinki_aava "$g/gof_helsinki_land.geojson" "$t/signalk/signalk_fi_aava_n2k_fixes.csv"
run nl_merrimac "$g/nl_wadden_ijssel_land.geojson" "$t/signalk/signalk_nl_merrimac_fixes.csv"
run nl_gpsd "$g/nl_wadden_ijssel_land.geojson" "$t/gpsd/gpsd_nl_fixes.csv"
run nl_canboat "$g/nl_wadden_ijssel_land.geojson" "$t/canboat/canboat_nl_susteranna_fixes.csv"
run gr_saronic "$g/gr_saronic_piraeus_land.geojson" "$t/gpsd/gpsd_gr_saronic_fixes.csv"
run dk_aislib "$dk" "$t/dma/dma_aislib_dk_fixes.csv"
/usr/bin/python3 - "$out" <<'PY'
import collections, glob, json, sys
kinds = ['grounding', 'alongside', 'in_contact_at_start', 'expected_contact', 'chart_disagrees', 'close_pass']
print('| set | ' + ' | '.join(kinds) + ' | wild fixes | jumps | fixes with no heading |')
print('|---' * (len(kinds) + 4) + '|')
total = collections.Counter()
grounds = []
for f in ['helsinki_aava', 'nl_merrimac', 'nl_gpsd', 'nl_canboat', 'gr_saronic', 'dk_aislib']:
    d = json.load(open(f'{sys.argv[1]}/{f}.geojson'))
    c = collections.Counter(x['properties']['kind'] for x in d['features'])
    s = d['shoal']['summary']
    total += c
    print(f'| {f} | ' + ' | '.join(str(c[k]) for k in kinds) + f" | {s['wild_fixes']} | {s['jumps']} | {s['unknown_heading_fixes']} |")
    grounds += [(f, x['properties']) for x in d['features'] if x['properties']['kind'] == 'grounding']
print('| all | ' + ' | '.join(str(total[k]) for k in kinds) + ' | | | |')
for f, p in grounds:
    print(f"grounding: {f} {p['track']} {p['start']} {p['speed_kn']} kn ({p['speed_source']}), {p['duration_s']} s, "
          f"heading {p['heading']} ({p['heading_source']}), penetration {p['penetration_m']} m, reference point {p['reference_inside_m']} m inside")
PY
