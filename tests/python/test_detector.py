"""shoal.Detector against `shoal probe` on the same poses, and the GIL released while it checks."""
import csv
import ctypes
import io
import math
import os
import threading
import unittest
import warnings

import numpy as np

import shoal
import support


def probe(grid_path, poses_csv, *ship):
    out = support.tmp("probe.csv")
    support.shoal("probe", "--coast", grid_path, *ship, poses_csv, "-o", out)
    with open(out) as f:
        return list(csv.DictReader(f))


def random_poses(grid, n, seed):
    """Poses over the grid's area and a little beyond it, written as probe reads them and read back."""
    lo_lon, lo_lat, hi_lon, hi_lat = grid.bounds
    rng = np.random.default_rng(seed)
    pad_lon, pad_lat = 0.05 * (hi_lon - lo_lon), 0.05 * (hi_lat - lo_lat)
    lat = rng.uniform(lo_lat - pad_lat, hi_lat + pad_lat, n)
    lon = rng.uniform(lo_lon - pad_lon, hi_lon + pad_lon, n)
    heading = rng.uniform(0, 360, n)
    text = "".join("%.7f,%.7f,%.1f\n" % p for p in zip(lat, lon, heading))
    path = support.tmp("poses-%d.csv" % seed)
    with open(path, "w") as f:
        f.write(text)
    back = np.loadtxt(io.StringIO(text), delimiter=",", ndmin=2)
    return path, back[:, 0], back[:, 1], back[:, 2]


class DetectorAgainstProbe(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.grid_path = support.grid_file(support.data("coast/uk_solent_land.geojson"), "solent.shoalgrid")
        cls.grid = shoal.Grid.load(cls.grid_path)

    def compare(self, rows, r, lat, lon, heading):
        self.assertEqual(len(rows), len(lat))
        for k, row in enumerate(rows):
            where = "pose %d (%s, %s, %s)" % (k, lat[k], lon[k], heading[k])
            self.assertAlmostEqual(float(row["lat"]), lat[k], places=7, msg=where)
            self.assertEqual(row["covered"] == "1", bool(r["covered"][k]), where)
            if row["collision"] == "":
                self.assertFalse(r["contact"][k], where)
                self.assertTrue(np.isnan(r["clearance_m"][k]), where)
                continue
            self.assertEqual(row["collision"] == "1", bool(r["contact"][k]), where)
            want = float(row["clearance_m"])
            if np.isinf(want):
                self.assertTrue(np.isinf(r["clearance_m"][k]), where)
            else:
                self.assertLessEqual(abs(want - r["clearance_m"][k]), 0.0005 + 1e-9, where)
            if r["contact"][k]:
                self.assertEqual(r["clearance_m"][k], 0.0, where)
                self.assertGreaterEqual(r["penetration_m"][k], 0.0, where)

    def test_dims_hundreds_of_random_poses(self):
        path, lat, lon, heading = random_poses(self.grid, 800, seed=16)
        rows = probe(self.grid_path, path, "--dims", "150,35,14,15")
        det = shoal.Detector(self.grid, dims=(150, 35, 14, 15))
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            r = det.check(lat, lon, heading)
        self.assertEqual(r["contact"].dtype, np.bool_)
        self.assertEqual(r["clearance_m"].shape, lat.shape)
        self.compare(rows, r, lat, lon, heading)
        # Both answers occur many times: the comparison is not of one kind only.
        contacts = int(np.sum(r["contact"]))
        clear = int(np.sum(r["covered"] & ~r["contact"]))
        self.assertGreater(contacts, 50)
        self.assertGreater(clear, 50)
        self.assertGreater(int(np.sum(~r["covered"])), 10)

    def test_ship_file_and_contour(self):
        for ship in ("tanker.json", "ferry-contour.json"):
            path, lat, lon, heading = random_poses(self.grid, 300, seed=len(ship))
            rows = probe(self.grid_path, path, "--ship", support.data("ships/" + ship))
            r = shoal.Detector(self.grid, ship=support.data("ships/" + ship)).check(lat, lon, heading)
            self.compare(rows, r, lat, lon, heading)

    def test_broadcast_and_shape(self):
        det = shoal.Detector(self.grid, dims=(150, 35, 14, 15))
        headings = np.arange(0, 360, 10.0).reshape(6, 6)
        r = det.check(50.75, -1.3, headings)
        self.assertEqual(r["contact"].shape, (6, 6))
        one = det.check(50.75, -1.3, 120.0)
        self.assertEqual(one["clearance_m"].shape, ())
        self.assertEqual(float(one["clearance_m"]), float(r["clearance_m"][2, 0]))

    def test_huge_finite_headings_as_probe_answers_them(self):
        # A heading of 5.72e307 or more was "no contact" on land, where probe said collision.
        headings = [5.72e307, 1e308, -1e308, 1.7976931348623157e308, -1.7976931348623157e308, 3.6e12 + 45, -90.0, 720.5]
        places = [(50.67, -1.30), (50.76, -1.30)]  # inland on the Isle of Wight, open water
        lat = np.array([p[0] for p in places for _ in headings])
        lon = np.array([p[1] for p in places for _ in headings])
        heading = np.array(headings * len(places))
        path = support.tmp("huge-headings.csv")
        with open(path, "w") as f:
            f.write("lat,lon,heading\n" + "".join("%.7f,%.7f,%r\n" % p for p in zip(lat, lon, heading)))
        rows = probe(self.grid_path, path, "--dims", "150,35,14,15")
        r = shoal.Detector(self.grid, dims=(150, 35, 14, 15)).check(lat, lon, heading)
        self.compare(rows, r, lat, lon, heading)
        self.assertTrue(all(r["contact"][: len(headings)]), "inland, every heading is a contact")

    def test_invalid_poses_cost_their_pose(self):
        det = shoal.Detector(self.grid, dims=(150, 35, 14, 15))
        lat = np.array([50.75, np.nan, 91.0, 50.75, 50.75])
        lon = np.array([-1.3, -1.3, -1.3, 200.0, -1.3])
        heading = np.array([0.0, 0.0, 0.0, 0.0, np.nan])
        with self.assertWarnsRegex(UserWarning, r"4 of 5 poses are not valid \(first: pose 1: latitude nan is not a number\)"):
            r = det.check(lat, lon, heading)
        self.assertTrue(r["covered"][0])
        self.assertEqual(list(r["covered"][1:]), [False] * 4)
        self.assertTrue(np.all(np.isnan(r["clearance_m"][1:])))

    def test_gil_released_while_checking(self):
        det = shoal.Detector(self.grid, dims=(150, 35, 14, 15))
        n = 20_000  # a few seconds of checking (inland poses cost their penetration search)
        rng = np.random.default_rng(3)
        lo_lon, lo_lat, hi_lon, hi_lat = self.grid.bounds
        lat, lon, heading = rng.uniform(lo_lat, hi_lat, n), rng.uniform(lo_lon, hi_lon, n), rng.uniform(0, 360, n)
        started, result = threading.Event(), {}

        def work():
            started.set()
            result["r"] = det.check(lat, lon, heading)

        t = threading.Thread(target=work)
        t.start()
        started.wait()
        # A little Python on this thread. Were the GIL held through the check, none of it could
        # run before the check returned; released, it runs while the check goes on.
        squares = [i * i for i in range(2000)]
        still_checking = "r" not in result
        t.join()
        self.assertEqual(len(squares), 2000)
        self.assertTrue(still_checking, "the main thread ran only after the check of %d poses had returned: the GIL was held" % n)
        self.assertEqual(result["r"]["contact"].shape, (n,))
        self.assertTrue(np.any(result["r"]["contact"]))

    def test_threads_share_a_detector(self):
        det = shoal.Detector(self.grid, dims=(150, 35, 14, 15))
        _, lat, lon, heading = random_poses(self.grid, 3000, seed=77)
        serial = det.check(lat, lon, heading)
        parts = np.array_split(np.arange(len(lat)), 4)
        out = [None] * len(parts)

        def work(i):
            idx = parts[i]
            out[i] = det.check(lat[idx], lon[idx], heading[idx])

        threads = [threading.Thread(target=work, args=(i,)) for i in range(len(parts))]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for key in ("contact", "covered", "clearance_m", "penetration_m"):
            np.testing.assert_array_equal(np.concatenate([o[key] for o in out]), serial[key], err_msg=key)

    def test_bad_input_is_input_error(self):
        with self.assertRaises(shoal.InputError) as e:
            shoal.Detector(self.grid, dims=(150, 0, 14, 15))
        self.assertIsInstance(e.exception, ValueError)
        self.assertIn("dims: b must be a finite number > 0 (got 0)", str(e.exception))
        with self.assertRaisesRegex(shoal.InputError, "bad-missing-d.json"):
            shoal.Detector(self.grid, ship=support.data("ships/bad-missing-d.json"))
        with self.assertRaisesRegex(ValueError, r"ship=PATH \(a ship file\) or dims"):
            shoal.Detector(self.grid)

    def test_depth_fit_warned(self):
        # tanker.json has a draught: a land-only grid does not see shallow water for it.
        with self.assertWarnsRegex(UserWarning, "holds land only"):
            shoal.Detector(self.grid, ship=support.data("ships/tanker.json"), ukc=1.0)


class CSurroundings(ctypes.Structure):
    _fields_ = [("covered", ctypes.c_int)] + [
        (name, ctypes.c_double) for name in ("port_m", "starboard_m", "ahead_m", "astern_m", "least_depth_m")
    ]


FIELDS = ("port_m", "starboard_m", "ahead_m", "astern_m", "least_depth_m")


def c_api():
    """libshoal_c of the build that made SHOAL_BINARY, through ctypes; None when it is not there."""
    path = os.path.join(os.path.dirname(os.path.dirname(support.BINARY)), "src", "libshoal_c.so")
    if not os.path.exists(path):
        return None
    lib = ctypes.CDLL(path)
    lib.shoal_grid_load.restype = ctypes.c_void_p
    lib.shoal_grid_load.argtypes = [ctypes.c_char_p]
    lib.shoal_grid_free.argtypes = [ctypes.c_void_p]
    lib.shoal_detector_new_at_depth.restype = ctypes.c_void_p
    lib.shoal_detector_new_at_depth.argtypes = [ctypes.c_void_p] + [ctypes.c_double] * 5
    lib.shoal_detector_free.argtypes = [ctypes.c_void_p]
    lib.shoal_surroundings_at.restype = ctypes.c_int
    lib.shoal_surroundings_at.argtypes = [ctypes.c_void_p] + [ctypes.c_double] * 4 + [ctypes.POINTER(CSurroundings)]
    lib.shoal_last_error.restype = ctypes.c_char_p
    return lib


def same(a, b):
    return a == b or (math.isnan(a) and math.isnan(b))


class DetectorSurroundings(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.solent = shoal.Grid.load(support.grid_file(support.data("coast/uk_solent_land.geojson"), "solent.shoalgrid"))
        cls.cut_path = support.grid_file(support.data("coast/US4MD81M_hazard_cut.000"), "cut.shoalgrid")
        cls.cut = shoal.Grid.load(cls.cut_path)

    def test_against_the_pose_check(self):
        # Travel along any axis is at least the clearance (local metres there; the frame's
        # scale is within 1e-3 of 1); in contact every distance is 0 and the depth 0 (land).
        det = shoal.Detector(self.solent, dims=(150, 35, 14, 15))
        rng = np.random.default_rng(37)
        lo_lon, lo_lat, hi_lon, hi_lat = self.solent.bounds
        contacts = clear = 0
        for k in range(300):
            lat, lon, hdg = rng.uniform(lo_lat, hi_lat), rng.uniform(lo_lon, hi_lon), rng.uniform(0, 360)
            max_m = math.inf if k % 2 else 800.0
            r = det.surroundings(lat, lon, hdg, max_m=max_m)
            self.assertEqual(sorted(r), sorted(FIELDS + ("covered",)))
            c = det.check(lat, lon, hdg)
            where = "pose %d (%r, %r, %r)" % (k, lat, lon, hdg)
            if c["contact"]:
                contacts += 1
                self.assertEqual([r[f] for f in FIELDS], [0.0] * 5, where)
                continue
            self.assertTrue(math.isnan(r["least_depth_m"]), where)  # land only: no depth charted
            least = min(r[f] for f in FIELDS[:4])
            self.assertLessEqual(max(r[f] for f in FIELDS[:4]), max_m, where)
            if r["covered"]:
                clear += 1
                self.assertTrue(math.isfinite(least), where)
                self.assertGreaterEqual(least, min(float(c["clearance_m"]) * (1 - 1e-3) - 1e-6, max_m), where)
        self.assertGreater(contacts, 20)
        self.assertGreater(clear, 20)

    def test_the_same_numbers_as_the_c_api(self):
        lib = c_api()
        if lib is None:
            self.skipTest("libshoal_c.so is not built beside %s" % support.BINARY)
        grid = lib.shoal_grid_load(self.cut_path.encode())
        self.assertTrue(grid, lib.shoal_last_error())
        cdet = lib.shoal_detector_new_at_depth(grid, 45, 15, 5, 5, 4.5)
        self.assertTrue(cdet, lib.shoal_last_error())
        det = shoal.Detector(self.cut, dims=(45, 15, 5, 5), hazard_depth_m=4.5)
        rng = np.random.default_rng(5)
        lo_lon, lo_lat, hi_lon, hi_lat = self.cut.bounds
        depths = set()
        try:
            for k in range(400):
                lat, lon, hdg = rng.uniform(lo_lat, hi_lat), rng.uniform(lo_lon, hi_lon), rng.uniform(0, 360)
                max_m = math.inf if k % 3 == 0 else 500.0
                r = det.surroundings(lat, lon, hdg, max_m=max_m)
                out = CSurroundings()
                self.assertEqual(lib.shoal_surroundings_at(cdet, lat, lon, hdg, max_m, ctypes.byref(out)), 0, lib.shoal_last_error())
                self.assertEqual(bool(out.covered), r["covered"])
                for f in FIELDS:
                    self.assertTrue(same(getattr(out, f), r[f]), "pose %d %s: %r vs %r" % (k, f, getattr(out, f), r[f]))
                depths.add(r["least_depth_m"] if not math.isnan(r["least_depth_m"]) else "nan")
        finally:
            lib.shoal_detector_free(cdet)
            lib.shoal_grid_free(grid)
        self.assertIn(0.0, depths)  # land, known depths and none all occur
        self.assertIn("nan", depths)
        self.assertGreater(len(depths), 3)

    def test_threads_share_a_detector(self):
        # Each call leases a frame of its own: four threads at once give what one gives alone.
        det = shoal.Detector(self.cut, dims=(45, 15, 5, 5), hazard_depth_m=4.5)
        rng = np.random.default_rng(8)
        lo_lon, lo_lat, hi_lon, hi_lat = self.cut.bounds
        poses = [(rng.uniform(lo_lat, hi_lat), rng.uniform(lo_lon, hi_lon), rng.uniform(0, 360)) for _ in range(800)]
        alone = [det.surroundings(*p, max_m=2000.0) for p in poses]
        results = [None] * 4

        def work(t):
            results[t] = [det.surroundings(*p, max_m=2000.0) for p in poses[t::4]]

        threads = [threading.Thread(target=work, args=(t,)) for t in range(4)]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        for t in range(4):
            for got, want in zip(results[t], alone[t::4]):
                self.assertEqual(got["covered"], want["covered"])
                for f in FIELDS:
                    self.assertTrue(same(got[f], want[f]), (f, got[f], want[f]))

    def test_bad_arguments_are_value_errors(self):
        det = shoal.Detector(self.solent, dims=(150, 35, 14, 15))
        with self.assertRaisesRegex(ValueError, "max_m must be > 0"):
            det.surroundings(50.75, -1.3, 0.0, max_m=0)
        with self.assertRaisesRegex(ValueError, "max_m must be > 0"):
            det.surroundings(50.75, -1.3, 0.0, max_m=math.nan)
        with self.assertRaisesRegex(ValueError, "latitude"):
            det.surroundings(91.0, -1.3, 0.0)
        with self.assertRaisesRegex(ValueError, "heading nan is not a number"):
            det.surroundings(50.75, -1.3, math.nan)


if __name__ == "__main__":
    unittest.main()


class CContactPoint(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("x_m", "y_m", "nx", "ny", "depth_m", "lat", "lon", "coast_lat", "coast_lon")] + [
        ("hazard", ctypes.c_int), ("charted_depth_m", ctypes.c_double), ("name", ctypes.c_char_p)]


class DetectorContacts(unittest.TestCase):
    """Detector.contacts: the regions shoal_contacts gives, on the Solent and the Annapolis cut."""

    @classmethod
    def setUpClass(cls):
        cls.solent_path = support.grid_file(support.data("coast/uk_solent_land.geojson"), "solent.shoalgrid")
        cls.solent = shoal.Grid.load(cls.solent_path)

    def test_contacts_are_the_c_apis_and_only_where_the_check_finds_contact(self):
        det = shoal.Detector(self.solent, dims=(150, 35, 14, 15))
        lib = c_api()
        cdet = cgrid = None
        if lib is not None:
            lib.shoal_contacts.restype = ctypes.c_int
            lib.shoal_contacts.argtypes = [ctypes.c_void_p] + [ctypes.c_double] * 3 + [ctypes.POINTER(CContactPoint), ctypes.c_int]
            cgrid = lib.shoal_grid_load(self.solent_path.encode())
            cdet = lib.shoal_detector_new_at_depth(cgrid, 150, 35, 14, 15, math.nan)
        rng = np.random.default_rng(11)
        lo_lon, lo_lat, hi_lon, hi_lat = self.solent.bounds
        hits = 0
        for k in range(400):
            lat, lon, hdg = rng.uniform(lo_lat, hi_lat), rng.uniform(lo_lon, hi_lon), rng.uniform(0, 360)
            regions = det.contacts(lat, lon, hdg)
            self.assertEqual(bool(regions), bool(det.check(lat, lon, hdg)["contact"]), "pose %d" % k)
            depths = [r["depth_m"] for r in regions]
            self.assertEqual(depths, sorted(depths, reverse=True))
            for r in regions:
                self.assertAlmostEqual(math.hypot(r["nx"], r["ny"]), 1.0, places=9)
                self.assertEqual(r["hazard"], "land")
            hits += bool(regions)
            if cdet:
                out = (CContactPoint * 8)()
                n = lib.shoal_contacts(cdet, lat, lon, hdg, out, 8)
                self.assertEqual(n, len(regions), lib.shoal_last_error())
                for a, b in zip(out, regions):
                    for f in ("x_m", "y_m", "nx", "ny", "depth_m", "lat", "lon", "coast_lat", "coast_lon"):
                        self.assertEqual(getattr(a, f), b[f], "pose %d %s" % (k, f))
        self.assertGreater(hits, 40)
        if cdet:
            lib.shoal_detector_free(cdet)
            lib.shoal_grid_free(cgrid)

    def test_bad_poses_are_value_errors(self):
        det = shoal.Detector(self.solent, dims=(150, 35, 14, 15))
        with self.assertRaises(ValueError):
            det.contacts(91, 0, 0)
        with self.assertRaises(ValueError):
            det.contacts(50.8, -1.2, math.nan)
