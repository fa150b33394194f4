#!/usr/bin/python3
"""Near-coast poses for `shoal probe` benchmarks: 100,000 rows lat,lon,heading, each a random
vertex of the coastline moved up to 400 m in a random direction, with a random heading.

usage: /usr/bin/python3 bench/near_poses.py COAST.geojson OUT.csv [SEED] [COUNT]
(needs Debian's python3-gdal, hence /usr/bin/python3)
"""
import math
import random
import sys

from osgeo import ogr

src, dst = sys.argv[1], sys.argv[2]
seed = int(sys.argv[3]) if len(sys.argv) > 3 else 15
count = int(sys.argv[4]) if len(sys.argv) > 4 else 100000
random.seed(seed)
pts = []


def walk(g):
    if g.GetGeometryCount():
        for k in range(g.GetGeometryCount()):
            walk(g.GetGeometryRef(k))
    else:
        pts.extend(g.GetPoints())


ds = ogr.Open(src)  # kept alive while its layer is read (GDAL's Python crashes otherwise)
if ds is None:
    sys.exit(f"near_poses.py: cannot open {src}")
for f in ds.GetLayer():
    walk(f.GetGeometryRef())
with open(dst, 'w') as o:
    o.write('lat,lon,heading\n')
    for _ in range(count):
        x, y = random.choice(pts)[:2]
        d = random.uniform(0, 400)
        a = random.uniform(0, 2 * math.pi)
        o.write('%.7f,%.7f,%.1f\n' % (y + d * math.cos(a) / 111320,
                                      x + d * math.sin(a) / (111320 * math.cos(math.radians(y))),
                                      random.uniform(0, 360)))
