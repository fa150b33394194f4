#!/usr/bin/python3
"""Writes the pathological inputs of docs/performance.md ("Bounded memory and time") into a folder:

    /usr/bin/python3 scripts/make-pathological.py OUT_DIR

- ring-1m.geojson   one island whose coastline is a single ring of 1,000,000 vertices
                    (radius about 20 km around 24.5E 59.9N, wavy at three scales)
- comb.geojson      a peninsula whose south shore zigzags 4,000 times within 400 m: one
                    500 m cell is crossed by thousands of segments
- comb-poses.csv    1,000 poses (lat,lon,heading) in and around the comb's busiest cell
- comb-track.csv    a vessel sailing along the comb's teeth, 50-250 m off them
- hull-1000.json    a ship file whose contour has 1,000 points (an ellipse with a bow)
- still-day.csv     two vessels standing still for a day, a fix every second (86,400 each):
                    one swinging at anchor 300 m off the ring island, one aground on it

Pure Python (no GDAL needed); deterministic.
"""
import json
import math
import os
import random
import sys

CENTRE = (24.5, 59.9)  # lon, lat
M_PER_DEG_LAT = 111_320.0


def to_lonlat(x, y, centre=CENTRE):
    """Local metres east/north of `centre` to lon/lat (small-area approximation)."""
    lon0, lat0 = centre
    return lon0 + x / (M_PER_DEG_LAT * math.cos(math.radians(lat0))), lat0 + y / M_PER_DEG_LAT


def polygon_feature(ring):
    if ring[0] != ring[-1]:
        ring = ring + [ring[0]]
    return {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [ring]}}


def write_geojson(path, features):
    with open(path, "w") as f:
        json.dump({"type": "FeatureCollection", "features": features}, f, separators=(",", ":"))


def ring_1m(out):
    n = 1_000_000
    r0 = 20_000.0
    ring = []
    for k in range(n):
        t = 2 * math.pi * k / n
        r = r0 * (1 + 0.05 * math.sin(37 * t) + 0.004 * math.sin(1009 * t) + 0.0002 * math.sin(50021 * t))
        lon, lat = to_lonlat(r * math.sin(t), r * math.cos(t))
        ring.append([round(lon, 8), round(lat, 8)])
    ring.reverse()  # counter-clockwise, as GeoJSON wants an outer ring
    write_geojson(os.path.join(out, "ring-1m.geojson"), [polygon_feature(ring)])


def comb(out):
    # A 2 km x 1 km block of land whose south shore, between x = 0 and x = 400 m, is a zigzag of
    # 2,000 teeth (4,000 segments) reaching 400 m down: all of it within one 500 m cell.
    teeth, width, depth = 2000, 400.0, 400.0
    ring = [(-800.0, 1000.0), (-800.0, 0.0)]
    for k in range(teeth):
        x0 = width * k / teeth
        ring.append((x0, 0.0))
        ring.append((x0 + width / teeth / 2, -depth))
    ring += [(width, 0.0), (1200.0, 0.0), (1200.0, 1000.0)]
    ll = [list(map(lambda v: round(v, 9), to_lonlat(x, y))) for x, y in ring]
    ll.reverse()
    # A frame of sea around it: a second island far away so that the grid's extent holds water.
    far = [to_lonlat(x, y) for x, y in [(-3000, -3000), (-2900, -3000), (-2900, -2900), (-3000, -2900)]]
    write_geojson(os.path.join(out, "comb.geojson"), [polygon_feature(ll), polygon_feature([list(p) for p in far][::-1])])
    rnd = random.Random(7)
    with open(os.path.join(out, "comb-poses.csv"), "w") as f:
        f.write("lat,lon,heading\n")
        for _ in range(1000):
            lon, lat = to_lonlat(-100 + 600 * rnd.random(), -700 + 600 * rnd.random())
            f.write(f"{lat:.7f},{lon:.7f},{360 * rnd.random():.1f}\n")
    with open(os.path.join(out, "comb-track.csv"), "w") as f:
        f.write("mmsi,timestamp,lat,lon,sog,cog,heading\n")
        for k in range(600):  # west to east below the teeth, 50-250 m off them, 1 s apart
            x = -600 + 3.0 * k
            y = -depth - 150 + 100 * math.sin(k / 40)
            lon, lat = to_lonlat(x, y)
            f.write(f"230999000,{1714557600 + k},{lat:.7f},{lon:.7f},5.8,90.0,90\n")


def hull_1000(out):
    n, a, b, half_beam = 1000, 150.0, 30.0, 14.0
    pts = []
    for k in range(n):
        t = 2 * math.pi * k / n
        x = (a + b) / 2 * math.cos(t) + (a - b) / 2
        y = half_beam * math.sin(t) * (1 - 0.3 * max(0.0, math.cos(t)) ** 4)
        pts.append([round(x, 6), round(y, 6)])
    ship = {"name": "Thousand-point hull", "a": a, "b": b, "c": half_beam, "d": half_beam, "contour": pts}
    with open(os.path.join(out, "hull-1000.json"), "w") as f:
        json.dump(ship, f)


def still_day(out):
    rnd = random.Random(11)
    # Anchored 300 m off the ring island's north shore (its radius there is about 20.3 km), and aground 1 km inside it.
    anchor = to_lonlat(0, 20_000 * (1 + 0.05 * math.sin(0)) + 700)
    aground = to_lonlat(0, 19_000)
    with open(os.path.join(out, "still-day.csv"), "w") as f:
        f.write("mmsi,timestamp,lat,lon,sog,cog,heading\n")
        heading = 0.0
        for s in range(86_400):
            heading = (heading + rnd.uniform(-0.2, 0.2)) % 360  # swinging slowly at anchor
            t = 1714521600 + s
            f.write(f"230888001,{t},{anchor[1]:.7f},{anchor[0]:.7f},0.0,,{heading:.1f}\n")
            f.write(f"230888002,{t},{aground[1]:.7f},{aground[0]:.7f},0.0,,45\n")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for make in (ring_1m, comb, hull_1000, still_day):
        make(out)
        print(f"make-pathological: {make.__name__} written")


if __name__ == "__main__":
    main()
