#!/usr/bin/python3
"""A synthetic fleet over the S-57 cell US4MD81M for docs/performance.md (issue 19 part 4):
N vessels, each a straight-legged random walk of F fixes every 10 s at 8-14 kn inside the
cell's box (-76.6223,38.3468,-75.9975,39.0532), each with its own draught drawn from 2-12 m
(a `draught` column), written as one CSV sorted by time. Fixed seed: the same file every run.

    /usr/bin/python3 bench/depth_fleet.py OUT.csv [N] [F]
"""
import datetime
import math
import random
import sys

W, S, E, N = -76.55, 38.40, -76.05, 39.00  # a little inside the cell's box


def main():
    out = sys.argv[1]
    vessels = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    fixes = int(sys.argv[3]) if len(sys.argv) > 3 else 300
    rng = random.Random(19)
    rows = []
    t0 = 1714557600  # 2024-05-01T10:00:00Z
    for v in range(vessels):
        lon, lat = rng.uniform(W, E), rng.uniform(S, N)
        cog = rng.uniform(0, 360)
        sog = rng.uniform(8, 14)
        draught = round(rng.uniform(2, 12), 1)
        for k in range(fixes):
            if k % 30 == 0:
                cog = (cog + rng.uniform(-60, 60)) % 360
            rows.append((t0 + 10 * k, 300000000 + v, lat, lon, sog, cog, draught))
            step = sog * 1852 / 3600 * 10
            lat += step * math.cos(math.radians(cog)) / 111320
            lon += step * math.sin(math.radians(cog)) / (111320 * math.cos(math.radians(lat)))
            if not (W < lon < E and S < lat < N):
                cog = (cog + 180) % 360
    rows.sort()
    with open(out, "w") as f:
        f.write("mmsi,timestamp,lat,lon,sog,cog,heading,draught\n")
        for t, m, lat, lon, sog, cog, d in rows:
            ts = datetime.datetime.fromtimestamp(t, datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
            f.write(f"{m},{ts},{lat:.6f},{lon:.6f},{sog:.1f},{cog:.1f},{cog:.0f},{d}\n")


if __name__ == "__main__":
    main()
