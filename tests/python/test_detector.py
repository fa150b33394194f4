"""shoal.Detector against `shoal probe` on the same poses, and the GIL released while it checks."""
import csv
import io
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


if __name__ == "__main__":
    unittest.main()
