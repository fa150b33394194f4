#!/usr/bin/python3
"""Time per call of shoal.Detector.surroundings and of the C API's shoal_surroundings_at
(through ctypes) on the S-57 cut off Annapolis (tests/data), random poses afloat, a
150 x 29 m hull at a limiting depth of 8 m. A diagnosis figure for docs/surroundings-notes.md.

    PYTHONPATH=build/python /usr/bin/python3 bench/surroundings_python.py [BUILD_DIR]
"""
import ctypes
import math
import os
import sys
import tempfile
import time

import numpy as np

import shoal

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


class CSurroundings(ctypes.Structure):
    _fields_ = [("covered", ctypes.c_int)] + [
        (name, ctypes.c_double) for name in ("port_m", "starboard_m", "ahead_m", "astern_m", "least_depth_m")
    ]


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(SOURCE, "build")
    with tempfile.TemporaryDirectory() as tmp:
        grid_path = os.path.join(tmp, "cut.shoalgrid")
        g = shoal.Grid.build(os.path.join(SOURCE, "tests", "data", "coast", "US4MD81M_hazard_cut.000"))
        g.save(grid_path)
        det = shoal.Detector(g, dims=(150, 35, 14, 15), hazard_depth_m=8.0)
        lo_lon, lo_lat, hi_lon, hi_lat = g.bounds
        rng = np.random.default_rng(1)
        n = 3000
        lat, lon, hdg = rng.uniform(lo_lat, hi_lat, n), rng.uniform(lo_lon, hi_lon, n), rng.uniform(0, 360, n)
        contact = det.check(lat, lon, hdg)["contact"]
        afloat = [k for k in range(n) if not contact[k]]
        lib = ctypes.CDLL(os.path.join(build, "src", "libshoal_c.so"))
        lib.shoal_grid_load.restype = ctypes.c_void_p
        lib.shoal_grid_load.argtypes = [ctypes.c_char_p]
        lib.shoal_detector_new_at_depth.restype = ctypes.c_void_p
        lib.shoal_detector_new_at_depth.argtypes = [ctypes.c_void_p] + [ctypes.c_double] * 5
        lib.shoal_surroundings_at.argtypes = [ctypes.c_void_p] + [ctypes.c_double] * 4 + [ctypes.POINTER(CSurroundings)]
        lib.shoal_detector_free.argtypes = [ctypes.c_void_p]
        lib.shoal_grid_free.argtypes = [ctypes.c_void_p]
        cgrid = lib.shoal_grid_load(grid_path.encode())
        cdet = lib.shoal_detector_new_at_depth(cgrid, 150, 35, 14, 15, 8.0)
        out = CSurroundings()
        for max_m in (500.0, 2000.0, math.inf):
            t0 = time.perf_counter()
            for k in afloat:
                det.surroundings(lat[k], lon[k], hdg[k], max_m=max_m)
            t1 = time.perf_counter()
            for k in afloat:
                lib.shoal_surroundings_at(cdet, lat[k], lon[k], hdg[k], max_m, ctypes.byref(out))
            t2 = time.perf_counter()
            print("max_m %g: %d poses afloat; Detector.surroundings %.1f us per call; shoal_surroundings_at (ctypes) %.1f us per call"
                  % (max_m, len(afloat), (t1 - t0) / len(afloat) * 1e6, (t2 - t1) / len(afloat) * 1e6))
        lib.shoal_detector_free(cdet)
        lib.shoal_grid_free(cgrid)


if __name__ == "__main__":
    main()
