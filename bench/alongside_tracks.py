#!/usr/bin/python3
"""Vessels lying alongside with GPS jitter, for `shoal check` benchmarks: VESSELS vessels, each
moored for a day (8,640 fixes 10 s apart) beside a random coastline segment of at least 60 m,
heading along it, its side 0-4 m over the shore line (so most fixes touch), with 2 m of GPS
jitter and +-2 degrees of heading noise per fix; rows interleaved by time, MarineCadastre layout
(MMSI,BaseDateTime,LAT,LON,SOG,COG,Heading,Status: 5, moored).

usage: /usr/bin/python3 bench/alongside_tracks.py COAST.geojson OUT.csv [VESSELS] [SEED]
(needs Debian's python3-gdal, hence /usr/bin/python3)
"""
import datetime
import math
import random
import sys

from osgeo import ogr

src, dst = sys.argv[1], sys.argv[2]
vessels = int(sys.argv[3]) if len(sys.argv) > 3 else 50
random.seed(int(sys.argv[4]) if len(sys.argv) > 4 else 15)
segs = []


def walk(g):
    if g.GetGeometryCount():
        for k in range(g.GetGeometryCount()):
            walk(g.GetGeometryRef(k))
    else:
        p = g.GetPoints()
        segs.extend(zip(p, p[1:]))


ds = ogr.Open(src)  # kept alive while its layer is read
if ds is None:
    sys.exit(f"alongside_tracks.py: cannot open {src}")
for f in ds.GetLayer():
    walk(f.GetGeometryRef())
m_lat = 111320.0
long_segs = [s for s in segs if math.hypot((s[1][0] - s[0][0]) * m_lat * math.cos(math.radians(s[0][1])), (s[1][1] - s[0][1]) * m_lat) > 60]
ships = []
for v in range(vessels):
    (x0, y0), (x1, y1) = [p[:2] for p in random.choice(long_segs)]
    kx = m_lat * math.cos(math.radians(y0))
    dx, dy = (x1 - x0) * kx, (y1 - y0) * m_lat
    n = math.hypot(dx, dy)
    # Land is on the left of a GSHHG ring's edge (counter-clockwise): water to the right.
    off = 20 - random.uniform(0, 4)  # the hull's half-beam is 20 m (--dims 100,20,20,20 below)
    cx, cy = (x0 + x1) / 2 * kx + dy / n * off, (y0 + y1) / 2 * m_lat - dx / n * off
    hdg = math.degrees(math.atan2(dx, dy)) % 360
    ships.append((316000000 + v, cx / kx, cy / m_lat, kx, hdg))
t0 = datetime.datetime(2024, 5, 1)
with open(dst, 'w') as o:
    o.write('MMSI,BaseDateTime,LAT,LON,SOG,COG,Heading,Status\n')
    for k in range(8640):
        t = (t0 + datetime.timedelta(seconds=10 * k)).strftime('%Y-%m-%dT%H:%M:%S')
        for mmsi, lon, lat, kx, hdg in ships:
            jx, jy = random.gauss(0, 2), random.gauss(0, 2)
            h = (hdg + random.uniform(-2, 2)) % 360
            o.write('%d,%s,%.7f,%.7f,%.1f,%.1f,%.0f,5\n' % (mmsi, t, lat + jy / m_lat, lon + jx / kx, abs(random.gauss(0, 0.3)), h, h))
