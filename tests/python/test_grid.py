"""shoal.Grid: built and loaded as `shoal import` and `shoal info` see it; saved atomically."""
import os
import re
import unittest

import shoal
import support

SOLENT = support.data("coast/uk_solent_land.geojson")


def info(path):
    _, out, _ = support.shoal("info", path)
    return out


class GridAgainstCli(unittest.TestCase):
    def test_build_equals_import(self):
        cli_path = support.tmp("solent-cli-200.shoalgrid")
        support.shoal("import", SOLENT, "-o", cli_path, "--cell", "200")
        g = shoal.Grid.build([SOLENT], cell_m=200)
        text = info(cli_path)
        self.assertIn("fingerprint:    %s\n" % g.fingerprint, text)
        self.assertIn("frame:          %s\n" % g.frame, text)
        self.assertIn("cell size:      200.0 m", text)
        nx, ny = map(int, re.search(r"grid:\s+(\d+) x (\d+) cells", text).groups())
        self.assertEqual(g.shape, (nx, ny))
        self.assertIsNone(g.limiting_depth_m)
        self.assertEqual(g.sources, [SOLENT])
        # Saved by Python, the file is the one `shoal import` wrote, byte for byte.
        py_path = support.tmp("solent-py-200.shoalgrid")
        g.save(py_path)
        with open(py_path, "rb") as a, open(cli_path, "rb") as b:
            self.assertEqual(a.read(), b.read())
        back = shoal.Grid.load(py_path)
        self.assertEqual(back.fingerprint, g.fingerprint)
        self.assertEqual(back.bounds, g.bounds)

    def test_bounds_hold_the_coast(self):
        g = shoal.Grid.build(SOLENT)  # a str is one source
        lo_lon, lo_lat, hi_lon, hi_lat = g.bounds
        # The Solent land (GSHHG) lies within about -1.96..-0.9 E, 50.5..50.95 N.
        self.assertLess(lo_lon, -1.5)
        self.assertGreater(hi_lon, -1.2)
        self.assertTrue(50.3 < lo_lat < 50.7 < hi_lat < 51.2, g.bounds)
        self.assertEqual(g.cell_m, 500.0)

    def test_hazard_depth(self):
        chart = support.data("coast/US4MD81M_hazard_cut.000")
        g = shoal.Grid.build([chart], hazard_depth_m=4.0)
        self.assertEqual(g.limiting_depth_m, 4.0)
        cli_path = support.tmp("hazard-4.shoalgrid")
        support.shoal("import", chart, "-o", cli_path, "--hazard-depth", "4")
        self.assertIn("fingerprint:    %s\n" % g.fingerprint, info(cli_path))

    def test_cache(self):
        cache = support.tmp("cache")
        a = shoal.Grid.build([SOLENT], cache_dir=cache)
        self.assertTrue(any(f.endswith(".shoalgrid") for f in os.listdir(cache)))
        b = shoal.Grid.build([SOLENT], cache_dir=cache)
        self.assertEqual(a.fingerprint, b.fingerprint)

    def test_errors_name_the_file(self):
        with self.assertRaises(shoal.InputError) as e:
            shoal.Grid.load(support.data("coast/not_a_dataset.txt"))
        self.assertIsInstance(e.exception, ValueError)
        self.assertIn("not_a_dataset.txt", str(e.exception))
        with self.assertRaisesRegex(shoal.InputError, "no_such_coast.geojson"):
            shoal.Grid.build([support.data("coast/no_such_coast.geojson")])
        with self.assertRaisesRegex(ValueError, "cell_m must be a finite number > 0"):
            shoal.Grid.build([SOLENT], cell_m=-5)
        with self.assertRaisesRegex(shoal.UsageError, "CRS 'EPSG:999999' is not one GDAL understands"):
            shoal.Grid.build([SOLENT], crs="EPSG:999999")
        g = shoal.Grid.build([SOLENT])
        # The grid never overwrites its own source.
        with self.assertRaisesRegex(shoal.UsageError, "is the input"):
            g.save(SOLENT)


class WithoutTheExtension(unittest.TestCase):
    def test_the_package_imports_and_says_what_is_missing(self):
        # shoal.dask drives the executable and must import where the extension is not built.
        import subprocess
        import sys
        env = dict(os.environ, PYTHONPATH=os.path.join(support.SOURCE, "python"))
        p = subprocess.run([sys.executable, "-c", "import shoal\ntry:\n    shoal.Grid\nexcept ImportError as e:\n    print(e)"],
                           capture_output=True, text=True, env=env)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("shoal.Grid needs the extension shoal._shoal", p.stdout)


if __name__ == "__main__":
    unittest.main()
