#!/usr/bin/python3
"""Writes a synthetic daily AIS export in the MarineCadastre layout, for the bounded-memory
figures in docs/performance.md (section "Bounded memory and time").

    /usr/bin/python3 scripts/make-ais.py -o /tmp/ais-10m.csv              # 5,000 vessels x 2,000 fixes
    /usr/bin/python3 scripts/make-ais.py --vessels 50 --fixes 100 -o small.csv

Rows are interleaved by time across the vessels, as a daily export is: every vessel reports
every --interval seconds at its own offset, and the file is in time order. The vessels sail
random walks (8-20 kn, course drifting) in the water of a coastline file, turning away when
their next position would come within about 300 m of land (a raster mask of the land
polygons, made with GDAL); one in ten lies still all day. Heading is the course rounded, or
511 (not available) for one vessel in five. Deterministic for a given --seed. Needs Debian's
python3-gdal and python3-numpy (/usr/bin/python3).
"""
import argparse
import datetime
import math
import os
import sys

import numpy as np
from osgeo import gdal, ogr

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_COAST = os.path.join(HERE, "..", "..", "shared", "data", "coast", "gshhg", "gof_helsinki_land.geojson")
HEADER = "MMSI,BaseDateTime,LAT,LON,SOG,COG,Heading,VesselName,IMO,CallSign,VesselType,Status,Length,Width,Draft,Cargo,TransceiverClass\n"


def land_mask(coast, cell_deg):
    """Land raster (True = within ~300 m of land) over the coastline's extent, and its geotransform."""
    gdal.UseExceptions()
    src = ogr.Open(coast)
    if src is None:
        sys.exit(f"make-ais: cannot open {coast}")
    layer = src.GetLayer(0)
    minx, maxx, miny, maxy = layer.GetExtent()
    nx = int(math.ceil((maxx - minx) / (2 * cell_deg)))  # lon cells twice as wide: ~square at 60N
    ny = int(math.ceil((maxy - miny) / cell_deg))
    ds = gdal.GetDriverByName("MEM").Create("", nx, ny, 1, gdal.GDT_Byte)
    ds.SetGeoTransform((minx, 2 * cell_deg, 0, maxy, 0, -cell_deg))
    gdal.RasterizeLayer(ds, [1], layer, burn_values=[1], options=["ALL_TOUCHED=TRUE"])
    land = ds.GetRasterBand(1).ReadAsArray().astype(bool)
    near = land.copy()
    for dy in (-3, -2, -1, 0, 1, 2, 3):  # grow by 3 cells (~300 m)
        for dx in (-3, -2, -1, 0, 1, 2, 3):
            near |= np.roll(np.roll(land, dy, axis=0), dx, axis=1)
    return near, (minx, maxy, 2 * cell_deg, cell_deg, nx, ny)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--coast", default=DEFAULT_COAST)
    ap.add_argument("--vessels", type=int, default=5000)
    ap.add_argument("--fixes", type=int, default=2000, help="fixes per vessel")
    ap.add_argument("--interval", type=int, default=10, help="seconds between a vessel's fixes")
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()

    near, (x0, y0, dx, dy, nx, ny) = land_mask(a.coast, 0.001)
    rng = np.random.default_rng(a.seed)
    n = a.vessels

    def blocked(lon, lat):
        i = np.floor((lon - x0) / dx).astype(np.int64)
        j = np.floor((y0 - lat) / dy).astype(np.int64)
        out = (i < 5) | (j < 5) | (i >= nx - 5) | (j >= ny - 5)
        ok = ~out
        res = out.copy()
        res[ok] = near[j[ok], i[ok]]
        return res

    lon = np.empty(n)
    lat = np.empty(n)
    todo = np.arange(n)
    while todo.size:  # starting points in open water
        lon[todo] = x0 + rng.random(todo.size) * dx * nx
        lat[todo] = y0 - rng.random(todo.size) * dy * ny
        todo = todo[blocked(lon[todo], lat[todo])]
    moored = rng.random(n) < 0.1
    sog = np.where(moored, 0.0, 8 + 12 * rng.random(n))
    cog = 360 * rng.random(n)
    no_heading = rng.random(n) < 0.2
    offset = rng.integers(0, a.interval, n)
    order = np.argsort(offset, kind="stable")  # within one round, rows in time order
    mmsi = 230000000 + np.arange(n)
    static = [f"VESSEL {v},IMO{9000000 + v},OH{v:04d},{70 if v % 3 else 80},{0 if sog[v] else 5},"
              f"{80 + v % 200},{12 + v % 30},{4 + v % 8}.{v % 10},,A" for v in range(n)]

    t0 = datetime.datetime(2024, 5, 1, tzinfo=datetime.timezone.utc)
    metres_per_deg_lat = 111_320.0
    with open(a.output, "w", buffering=1 << 22) as out:
        out.write(HEADER)
        for k in range(a.fixes):
            base = t0 + datetime.timedelta(seconds=k * a.interval)
            rows = []
            for v in order:
                t = base + datetime.timedelta(seconds=int(offset[v]))
                hdg = 511 if no_heading[v] else int(round(cog[v])) % 360
                rows.append(f"{mmsi[v]},{t:%Y-%m-%dT%H:%M:%S},{lat[v]:.5f},{lon[v]:.5f},{sog[v]:.1f},{cog[v]:.1f},{hdg},{static[v]}\n")
            out.write("".join(rows))
            # Move every vessel one interval; one about to come near land turns away and waits.
            step_m = sog * 0.514444 * a.interval
            h = np.radians(cog)
            nlat = lat + step_m * np.cos(h) / metres_per_deg_lat
            nlon = lon + step_m * np.sin(h) / (metres_per_deg_lat * np.cos(np.radians(lat)))
            stop = blocked(nlon, nlat) & ~moored
            go = ~stop
            lat[go], lon[go] = nlat[go], nlon[go]
            cog[stop] = (cog[stop] + 60 + 120 * rng.random(int(stop.sum()))) % 360
            cog[go & ~moored] = (cog[go & ~moored] + (rng.random(int((go & ~moored).sum())) - 0.5) * 4) % 360
    print(f"make-ais: {a.output}: {a.vessels} vessels x {a.fixes} fixes = {a.vessels * a.fixes} rows, "
          f"{os.path.getsize(a.output) / 1e6:.0f} MB")


if __name__ == "__main__":
    main()
