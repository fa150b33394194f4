#!/usr/bin/env python3
"""Writes berth.geojson, the made-up scene of berthing_sim.c: a straight quay and a pier off
Helsinki (reference point 60.15 N, 24.95 E), in the same local flat-earth frame as the
simulator (east x, north y in metres; WGS84 radii of curvature at the reference latitude).

  West Quay  land north of y = 0 (the parallel 60.15 N), x from -600 to 600 m, 300 m deep;
             its edge has a vertex every 50 m (a long straight lon/lat edge is curved in a
             local metric frame: ~5 cm of sagitta over 1.2 km here).
  Pier 7     10 m wide (x from 200 to 210 m), from the quay 150 m out (y = -150),
             overlapping the quay's land by 10 m; its sides have a vertex every 50 m.
  Little Skerry  a 30 m rock 700 m south of the quay: it stretches the chart's extent over
             the water where the runs start.
"""
import json, math, sys

LAT0, LON0 = 60.15, 24.95
A, F = 6378137.0, 1 / 298.257223563
E2 = F * (2 - F)
s = math.sin(math.radians(LAT0))
M = A * (1 - E2) / (1 - E2 * s * s) ** 1.5  # meridian radius of curvature
N = A / math.sqrt(1 - E2 * s * s)           # prime vertical radius of curvature


def lonlat(x, y):
    return [round(LON0 + math.degrees(x / (N * math.cos(math.radians(LAT0)))), 9),
            round(LAT0 + math.degrees(y / M), 9)]


def edge(p, q, step=50.0):
    """p to q (q excluded), a vertex at most every `step` metres."""
    n = max(1, math.ceil(math.hypot(q[0] - p[0], q[1] - p[1]) / step))
    return [(p[0] + (q[0] - p[0]) * i / n, p[1] + (q[1] - p[1]) * i / n) for i in range(n)]


def ring(corners):
    pts = []
    for i, p in enumerate(corners):
        pts += edge(p, corners[(i + 1) % len(corners)])
    pts.append(corners[0])
    return [lonlat(x, y) for x, y in pts]


def feature(name, corners):
    return {"type": "Feature", "properties": {"name": name},
            "geometry": {"type": "Polygon", "coordinates": [ring(corners)]}}


# Counter-clockwise rings (GeoJSON's right-hand rule).
quay = [(-600, 0), (600, 0), (600, 300), (-600, 300)]
pier = [(200, -150), (210, -150), (210, 10), (200, 10)]
skerry = [(-480, -700), (-450, -700), (-450, -670), (-480, -670)]
features = [feature("West Quay", quay), feature("Pier 7", pier), feature("Little Skerry", skerry)]
with open(sys.argv[1] if len(sys.argv) > 1 else "berth.geojson", "w") as out:
    out.write('{"type": "FeatureCollection", "name": "berth", "features": [\n')
    out.write(",\n".join(json.dumps(f) for f in features))
    out.write("\n]}\n")
