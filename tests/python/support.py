"""What the Python tests share: paths, the shoal executable, temporary folders.

Run by ctest (tests/CMakeLists.txt) with /usr/bin/python3 and PYTHONPATH set to the build's
python folder; SHOAL_BINARY names the executable, SHOAL_SOURCE_DIR the repository.
"""
import json
import os
import subprocess
import tempfile

SOURCE = os.environ.get("SHOAL_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BINARY = os.environ.get("SHOAL_BINARY", os.path.join(SOURCE, "build", "cli", "shoal"))
HELSINKI = os.path.join(SOURCE, "examples", "data", "gof_helsinki_land.geojson")
AIS_CASES = os.path.join(SOURCE, "tests", "data", "tracks", "ais_cases")


def data(path):
    return os.path.join(SOURCE, "tests", "data", path)


def shoal(*args, ok=(0,)):
    """Runs the shoal executable; returns (status, stdout, stderr), failing on an unexpected status."""
    p = subprocess.run([BINARY, *map(str, args)], capture_output=True, text=True)
    if p.returncode not in ok:
        raise AssertionError("shoal %s: exit %d\n%s" % (" ".join(map(str, args)), p.returncode, p.stderr))
    return p.returncode, p.stdout, p.stderr


_tmp = tempfile.TemporaryDirectory(prefix="shoal-python-test-")


def tmp(name):
    return os.path.join(_tmp.name, name)


def grid_file(coast, name):
    """A grid built by `shoal import` (once per test process)."""
    out = tmp(name)
    if not os.path.exists(out):
        shoal("import", coast, "-o", out)
    return out


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)
