"""docs/python.md, run: its `python` blocks in order (under this interpreter, and from a virtual
environment made by the page's own commands), its results checked against the AIS cases'
hand-derived answers (tests/data/tracks/ais_cases/expected.json), geodesic distances to the
ports, and the printed outputs the page shows. So the page cannot rot."""
import contextlib
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

import support

DOC = os.path.join(support.SOURCE, "docs", "python.md")


def blocks(language):
    with open(DOC, encoding="utf-8") as f:
        text = f.read()
    return re.findall(r"^```%s\n(.*?)^```$" % language, text, flags=re.S | re.M)


def shown_outputs(code):
    """The outputs the page shows: the comment lines right after a print(...) statement."""
    shown = []
    lines = code.splitlines()
    for k, line in enumerate(lines):
        if line.startswith("# ") and k > 0 and (lines[k - 1].startswith("print") or lines[k - 1].startswith("# ")
                                               or lines[k - 1].startswith("    print")):
            shown.append(line[2:])
    return shown


def work_folder():
    """A folder laid out as the repository's root for what the page reads (examples/data, the
    AIS cases), with its own examples/out: the page writes there, never into the sources."""
    root = tempfile.mkdtemp(prefix="shoal-docs-python-")
    os.makedirs(os.path.join(root, "examples"))
    os.symlink(os.path.join(support.SOURCE, "examples", "data"), os.path.join(root, "examples", "data"))
    os.makedirs(os.path.join(root, "tests", "data", "tracks"))
    os.symlink(support.AIS_CASES, os.path.join(root, "tests", "data", "tracks", "ais_cases"))
    return root


class DocsPythonPage(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.code = "\n".join(blocks("python"))
        cls.root = work_folder()
        cwd = os.getcwd()
        os.chdir(cls.root)
        cls.ns = {"__name__": "__docs_python__"}
        out = io.StringIO()
        try:
            with contextlib.redirect_stdout(out):
                exec(compile(cls.code, DOC, "exec"), cls.ns)
        finally:
            os.chdir(cwd)
        cls.stdout = out.getvalue()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.root, ignore_errors=True)

    def test_the_page_has_its_blocks(self):
        self.assertGreaterEqual(len(blocks("python")), 6)
        self.assertIn("gpd.sjoin(", self.code)

    def test_printed_outputs_are_the_pages(self):
        self.assertEqual(self.stdout.splitlines(), shown_outputs(self.code))

    def test_groundings_are_the_clis_and_the_cases_answers(self):
        import pandas as pd
        # The same files in one `shoal check` run (one run: the traffic that teaches berths is the same).
        files = sorted(os.path.join(support.AIS_CASES, f) for f in os.listdir(support.AIS_CASES) if f.endswith(".csv"))
        out = support.tmp("docs-cases.geojson")
        grid = support.grid_file(support.HELSINKI, "helsinki.shoalgrid")
        support.shoal("check", "--coast", grid, "--dims", "100,20,8,8", *files, "-o", out, "--no-progress", ok=(1,))
        cli = [f["properties"] for f in support.read_json(out)["features"] if f["properties"]["kind"] == "grounding"]
        groundings = self.ns["groundings"]
        self.assertEqual(groundings["track"].tolist(), [p["track"] for p in cli])
        self.assertEqual(list(groundings["start"]), [pd.Timestamp(p["start"]) for p in cli])
        # Each, where its case file gives the hand-derived time of contact, within its tolerance.
        with open(os.path.join(support.AIS_CASES, "expected.json"), encoding="utf-8") as f:
            cases = {c["mmsi"]: c["expect"] for c in json.load(f)["cases"].values()}
        for _, g in groundings.iterrows():
            e = cases[int(g["track"])]
            self.assertEqual(e["groundings"], 1)
            if "grounding_start" in e:
                error = abs((g["start"] - pd.Timestamp(e["grounding_start"])).total_seconds())
                self.assertLessEqual(error, e["start_tolerance_s"], g["track"])
            else:
                self.assertTrue(pd.Timestamp(e["start_earliest"]) <= g["start"] <= pd.Timestamp(e["start_latest"]), g["track"])
        # The two the page explains: groundings alone, alongside in the run that saw the others stay there.
        same = self.ns["same_spot"]
        self.assertEqual(set(same["kind"]), {"alongside"})
        self.assertEqual([cases[int(t)]["groundings"] for t in same["track"]], [1, 1])
        self.assertEqual(str(groundings["start"].dtype), "datetime64[ns, UTC]")
        self.assertEqual(groundings.crs.to_epsg(), 4326)
        self.assertEqual(self.ns["result"].tracks.crs.to_epsg(), 4326)

    def test_the_join_puts_each_grounding_in_its_ports_approach(self):
        from pyproj import Geod
        ports, near, groundings = self.ns["ports"], self.ns["near"], self.ns["groundings"]
        self.assertEqual(len(near), len(groundings))
        geod = Geod(ellps="GRS80")
        for index, g in groundings.iterrows():
            # Independent of the projection and of the join: geodesic distance on the ellipsoid.
            # The buffer is a polygon in a conformal projection (scale factor 0.9996-1.0004 here):
            # the answer is asked only of groundings clear of the 10 km edge by 50 m.
            dist = {p["port"]: geod.inv(g.geometry.x, g.geometry.y, p.geometry.x, p.geometry.y)[2] for _, p in ports.iterrows()}
            inside = [name for name, d in dist.items() if d < 10_000]
            self.assertTrue(all(abs(d - 10_000) > 50 for d in dist.values()))
            got = near.loc[[index], "port"].dropna().tolist()
            self.assertEqual(sorted(got), sorted(inside), g["track"])
        self.assertTrue(near["port"].notna().all())  # the example's groundings all lie in an approach

    def test_the_plot_is_written(self):
        path = os.path.join(self.root, "examples", "out", "groundings.png")
        with open(path, "rb") as f:
            head = f.read(24)
        self.assertEqual(head[:8], b"\x89PNG\r\n\x1a\n")
        self.assertEqual((int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")), (800, 600))


class DocsPythonFromAVenv(unittest.TestCase):
    """The page's venv commands, run as written (with this test's folders), then the page's
    code under the venv's interpreter: same outputs, no warning from pyproj."""

    def test_venv_route(self):
        sh = [b for b in blocks("sh") if "--system-site-packages" in b]
        self.assertEqual(len(sh), 1)
        root = work_folder()
        try:
            venv = os.path.join(root, "venv")
            package = os.environ.get("PYTHONPATH", "").split(os.pathsep)[0]
            self.assertTrue(os.path.isfile(os.path.join(package, "shoal", "__init__.py")), package)
            script = re.sub(r"^venv=.*$", "venv=%s" % venv, sh[0], count=1, flags=re.M)
            script = re.sub(r"^shoal_python=.*$", "shoal_python=%s" % package, script, count=1, flags=re.M)
            self.assertNotEqual(script, sh[0])
            env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PROJ_DATA", "PROJ_LIB")}
            p = subprocess.run(["bash", "-euo", "pipefail", "-c", script], capture_output=True, text=True, env=env, cwd=root)
            self.assertEqual(p.returncode, 0, p.stderr)
            import shoal
            self.assertEqual(p.stdout.strip(), shoal.__version__)
            code = "\n".join(blocks("python"))
            page = os.path.join(root, "page.py")
            with open(page, "w", encoding="utf-8") as f:
                f.write(code)
            # -W error: a warning outside the page's own `catch_warnings` (pyproj's missing data
            # folder above all) fails the run.
            run = subprocess.run([os.path.join(venv, "bin", "python"), "-W", "error", page], capture_output=True, text=True,
                                 env=env, cwd=root)
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertEqual(run.stdout.splitlines(), shown_outputs(code))
            where = subprocess.run([os.path.join(venv, "bin", "python"), "-c", "import sys, shoal; print(sys.prefix); print(shoal.__file__)"],
                                   capture_output=True, text=True, env=env, cwd=root)
            prefix, module = where.stdout.split()
            self.assertEqual(os.path.realpath(prefix), os.path.realpath(venv))
            self.assertTrue(module.startswith(package), module)
            self.assertNotEqual(os.path.realpath(sys.prefix), os.path.realpath(venv))
        finally:
            shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    unittest.main()
