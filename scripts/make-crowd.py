#!/usr/bin/python3
"""Writes a crowd of vessels as one CSV track file, for the scaling cases of
docs/performance.md ("Bounded memory and time": --encounters and --plot with many vessels):

    /usr/bin/python3 scripts/make-crowd.py OUT.csv VESSELS [--area-km K] [--fixes F] [--every S]
                                           [--lon LON] [--lat LAT] [--seed N]

VESSELS vessels (MMSI 200000000 + k) start at random in a K x K km square centred on LON, LAT
(default 1 km, off the east end of the Isle of Wight in tests/data/coast/uk_solent_land.geojson:
open water), and steam at 2-8 kn on a random course, a fix every S seconds (default 10), F fixes
each (default 6), bouncing off the square's edges. Columns: mmsi,time,lat,lon,sog,cog,heading.
Pure Python; deterministic for a seed.
"""
import argparse
import math
import random

M_PER_DEG_LAT = 111_320.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("vessels", type=int)
    ap.add_argument("--area-km", type=float, default=1.0)
    ap.add_argument("--fixes", type=int, default=6)
    ap.add_argument("--every", type=float, default=10.0)
    ap.add_argument("--lon", type=float, default=-0.98)
    ap.add_argument("--lat", type=float, default=50.66)
    ap.add_argument("--seed", type=int, default=14)
    a = ap.parse_args()
    rnd = random.Random(a.seed)
    half = a.area_km * 500.0
    m_per_deg_lon = M_PER_DEG_LAT * math.cos(math.radians(a.lat))
    t0 = 1_700_000_000
    with open(a.out, "w") as f:
        f.write("mmsi,time,lat,lon,sog,cog,heading\n")
        for k in range(a.vessels):
            x, y = rnd.uniform(-half, half), rnd.uniform(-half, half)
            course = rnd.uniform(0, 360)
            kn = rnd.uniform(2, 8)
            for i in range(a.fixes):
                lat = a.lat + y / M_PER_DEG_LAT
                lon = a.lon + x / m_per_deg_lon
                f.write(f"{200000000 + k},{t0 + i * a.every:.0f},{lat:.7f},{lon:.7f},{kn:.1f},{course:.1f},{course:.0f}\n")
                d = kn * 0.514444 * a.every
                x += d * math.sin(math.radians(course))
                y += d * math.cos(math.radians(course))
                if abs(x) > half:
                    x = math.copysign(2 * half - abs(x), x)
                    course = (360 - course) % 360
                if abs(y) > half:
                    y = math.copysign(2 * half - abs(y), y)
                    course = (180 - course) % 360


if __name__ == "__main__":
    main()
