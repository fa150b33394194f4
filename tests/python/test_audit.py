"""shoal.audit on DataFrames against `shoal check` on the same CSV files: every field of the
report's events, tracks, problems and summary; bad rows; GeoDataFrames; errors."""
import glob
import math
import os
import unittest
import warnings

import numpy as np
import pandas as pd

import shoal
import support

DIMS = (100, 20, 8, 8)
COLUMNS = {"id": "MMSI", "time": "BaseDateTime", "lat": "LAT", "lon": "LON", "sog": "SOG", "cog": "COG", "heading": "Heading",
           "name": "VesselName", "draught": "Draft", "nav_status": "Status", "line": "line"}


def plain(v):
    """A DataFrame cell as the report's JSON has it: null for missing, Python numbers."""
    if v is None or v is pd.NA or v is pd.NaT or (isinstance(v, float) and math.isnan(v)):
        return None
    if isinstance(v, pd.Timestamp):
        # The report's ISO 8601 text (milliseconds when not 0, Z), written here from the Timestamp's fields:
        # anything else (not UTC, a finer part) cannot equal the CLI's text.
        if str(v.tz) != "UTC" or v.microsecond % 1000 or v.nanosecond:
            return repr(v)
        ms = v.microsecond // 1000
        return v.strftime("%Y-%m-%dT%H:%M:%S") + (".%03d" % ms if ms else "") + "Z"
    if isinstance(v, (np.bool_, bool)):
        return bool(v)
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.floating):
        return float(v)
    return v


def rows(df, names):
    return [{n: plain(df[n].iloc[k]) for n in names} for k in range(len(df))]


def read_fixes(path):
    # round_trip: numbers parsed as the CLI parses them (correctly rounded), to the last bit.
    df = pd.read_csv(path, float_precision="round_trip")
    df["line"] = df.index + 2  # the header is line 1
    return df


class AuditAgainstCheck(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.grid_path = support.grid_file(support.HELSINKI, "helsinki.shoalgrid")
        cls.grid = shoal.Grid.load(cls.grid_path)

    def check_cli(self, track, *options):
        out = support.tmp("report.geojson")
        support.shoal("check", "--coast", self.grid_path, "--dims", ",".join(map(str, DIMS)), track, "-o", out, "--no-progress",
                      *options, ok=(0, 1))
        return support.read_json(out)

    def assert_same(self, report, result, track):
        names = list(result.events.columns.drop("geometry"))
        features = report["features"]
        self.assertEqual([list(f["properties"]) for f in features], [names] * len(features))
        self.assertEqual([f["properties"] for f in features], rows(result.events, names), track)
        self.assertEqual([f["geometry"]["coordinates"] for f in features],
                         [[p.x, p.y] for p in result.events.geometry], track)
        tnames = list(result.tracks.columns.drop("geometry"))
        self.assertEqual(report["shoal"]["tracks"], rows(result.tracks, tnames), track)
        problems = [{k: v for k, v in p.items() if v is not None} for p in rows(result.problems, list(result.problems.columns))]
        self.assertEqual(report["shoal"]["problems"], problems, track)
        self.assertEqual(report["shoal"]["summary"], {k: plain(v) for k, v in result.summary.items()}, track)
        run = {k: v for k, v in report["shoal"].items() if k not in ("summary", "tracks", "problems", "closest_approaches")}
        self.assertEqual(run, {k: plain(v) for k, v in result.run.items()}, track)

    def test_every_ais_case_equals_the_cli(self):
        files = sorted(glob.glob(os.path.join(support.AIS_CASES, "*.csv")))
        self.assertEqual(len(files), 14)  # the seven first cases and the seven of the real world (README)
        kinds = set()
        for track in files:
            report = self.check_cli(track)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # wild fixes, as the CLI's stderr says them
                result = shoal.audit(read_fixes(track), self.grid, dims=DIMS, columns=COLUMNS, file=track)
            self.assert_same(report, result, track)
            kinds.update(result.events["kind"])
            # Each case's VesselType column (70 cargo; the ferry 60 passenger, the pilot boat 50):
            # the tracks carry it, with its meaning.
            with open(track) as f:
                f.readline()
                vtype = int(f.readline().split(",")[10])
            self.assertEqual(result.tracks["ship_type"].tolist(), [vtype] * len(result.tracks), track)
            self.assertEqual(set(result.tracks["ship_type_source"]), {"ship type column"}, track)
            if vtype == 70:
                self.assertEqual(set(result.tracks["ship_type_text"]), {"Cargo, all ships of this type"}, track)
        # The cases hold groundings and other contacts: the comparison covers them.
        self.assertIn("grounding", kinds)
        self.assertGreater(len(kinds), 1)

    def test_datetime_and_epoch_times_and_default_names(self):
        track = os.path.join(support.AIS_CASES, "aground_at_speed.csv")
        report = self.check_cli(track, "--margin", "80", "--step", "2")
        df = read_fixes(track)
        df["BaseDateTime"] = pd.to_datetime(df["BaseDateTime"], utc=True)
        # Default column names (the CSV reader's): only the line column is named.
        result = shoal.audit(df, self.grid, dims=DIMS, columns={"line": "line"}, file=track, margin_m=80, step_m=2)
        self.assert_same(report, result, track)
        self.assertEqual(list(result.events["kind"]).count("grounding"), 1)
        df["BaseDateTime"] = df["BaseDateTime"].astype("int64") / 1e9
        epoch = shoal.audit(df, self.grid, dims=DIMS, columns={"line": "line"}, file=track, margin_m=80, step_m=2)
        self.assert_same(report, epoch, track)

    def test_columns_are_found_as_the_csv_reader_finds_them(self):
        # One table of names for the CSV reader and shoal.audit: a time column the CSV reader takes
        # by its spelling (TIMESTAMP_UTC, not among the listed names) is taken here too.
        self.assertEqual(shoal.DEFAULT_COLUMNS["time"][:3], ["time", "timestamp", "basedatetime"])
        self.assertEqual(shoal.DEFAULT_COLUMNS["line"], [])
        track = os.path.join(support.AIS_CASES, "aground_at_speed.csv")
        report = self.check_cli(track, "--margin", "80", "--step", "2")
        df = read_fixes(track).rename(columns={"BaseDateTime": "TIMESTAMP_UTC", "LAT": "# Latitude "})
        result = shoal.audit(df, self.grid, dims=DIMS, columns={"line": "line"}, file=track, margin_m=80, step_m=2)
        self.assert_same(report, result, track)
        df = df.rename(columns={"TIMESTAMP_UTC": "local_time"})  # not a UTC time: not taken, and said
        with self.assertRaisesRegex(ValueError, "no time column"):
            shoal.audit(df, self.grid, dims=DIMS, columns={"line": "line"})

    def test_options_reach_the_audit(self):
        track = os.path.join(support.AIS_CASES, "berthing_sideways.csv")
        report = self.check_cli(track, "--berthing-speed", "0.1", "--stop-time", "60", "--stop-diameter", "30",
                                "--max-gap", "300", "--max-speed", "40", "--jobs", "1")
        result = shoal.audit(read_fixes(track), self.grid, dims=DIMS, columns=COLUMNS, file=track, berthing_speed_kn=0.1,
                             stop_time_s=60, stop_diameter_m=30, max_gap_s=300, max_speed_kn=40, jobs=1)
        self.assert_same(report, result, track)

    def test_bad_rows_cost_the_row(self):
        track = support.data("tracks/bad_coordinates.csv")
        report = self.check_cli(track)
        df = read_fixes(track)
        with self.assertWarnsRegex(UserWarning, "8 bad rows skipped"):
            result = shoal.audit(df, self.grid, dims=DIMS, columns={"line": "line"}, file=track)
        self.assertEqual(result.summary["skipped_rows"], report["shoal"]["summary"]["skipped_rows"])
        self.assertEqual(result.summary["fixes"], report["shoal"]["summary"]["fixes"])
        self.assertEqual(result.tracks["skipped_rows"].tolist(), [t["skipped_rows"] for t in report["shoal"]["tracks"]])
        lines = lambda ms: [int(m.split(" line ")[1].split(":")[0]) for m in ms]
        cli = [p["message"] for p in report["shoal"]["problems"]]
        self.assertEqual(lines(result.problems["message"]), lines(cli))
        # Where the DataFrame holds what the file held, the message is the CLI's word for word.
        for m in ("line 3: latitude nan is not a number; row skipped", "line 5: latitude 91 (AIS: not available); row skipped",
                  "line 8: longitude -180.2 is outside [-180, 180]; row skipped"):
            self.assertIn(track + " " + m, list(result.problems["message"]))
            self.assertIn(track + " " + m, cli)

    def test_bad_values_in_a_dataframe(self):
        t0 = pd.Timestamp("2024-05-01T10:00:00Z")
        df = pd.DataFrame({
            "mmsi": [230990001, 230990001, None, 230990001, 230990001, 230990001],
            "time": [t0, t0 + pd.Timedelta(seconds=10), t0 + pd.Timedelta(seconds=20), pd.NaT, pd.Timestamp("1970-01-02T00:00:00Z"),
                     t0 + pd.Timedelta(seconds=30)],
            "lat": [60.158306, np.nan, 60.16, 60.16, 60.16, 60.1590],
            "lon": [25.327977, 25.33, 25.33, 25.33, 25.33, 25.3279],
        })
        with self.assertWarnsRegex(UserWarning, "DataFrame: 4 bad rows skipped"):
            result = shoal.audit(df, self.grid, dims=DIMS)
        self.assertEqual(result.summary["fixes"], 2)
        self.assertEqual(result.tracks["track"].tolist(), ["230990001"])  # an MMSI with NaN beside it, not "230990001.0"
        self.assertEqual(list(result.problems["message"]), [
            "DataFrame line 2: latitude nan is not a number; row skipped",
            "DataFrame line 3: no vessel id; row skipped",
            "DataFrame line 4: no time; row skipped",
            "DataFrame line 5: time 86400 (seconds since 1970) is outside the years 1980-2099 (a wrong unit, or a corrupt field?); row skipped",
        ])

    def test_dma_export_as_text_equals_the_cli(self):
        # The Danish Maritime Authority's layout: "# Timestamp" day-first text, "Navigational
        # status" as text, A,B,C,D columns, "Type of mobile"; found by the default names.
        track = support.data("tracks/dma_export_dk_head200.csv")
        out = support.tmp("dma.geojson")
        support.shoal("check", "--coast", self.grid_path, "--dims", "100,20,8,8", track, "-o", out, "--no-progress")
        report = support.read_json(out)
        df = pd.read_csv(track, float_precision="round_trip", dtype={"# Timestamp": str})
        df["line"] = df.index + 2
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the fixes lie outside the Helsinki grid, as the CLI warns too
            result = shoal.audit(df, self.grid, dims=DIMS, columns={"line": "line"}, file=track)
        self.assertEqual(len(report["shoal"]["tracks"]), len(result.tracks))
        self.assertGreater(len(result.tracks), 10)
        self.assert_same(report, result, track)
        # A base station row is not a vessel, as the CLI's reader says.
        df.loc[3, "Type of mobile"] = "Base Station"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            fewer = shoal.audit(df, self.grid, dims=DIMS, columns={"line": "line"}, file=track)
        self.assertEqual(list(fewer.problems["message"])[:1], [track + " line 5: not a vessel (Type of mobile 'Base Station'); row skipped"])

    def test_geodataframes(self):
        import geopandas as gpd
        track = os.path.join(support.AIS_CASES, "aground_at_speed.csv")
        result = shoal.audit(read_fixes(track), self.grid, dims=DIMS, columns=COLUMNS, file=track)
        self.assertIsInstance(result.events, gpd.GeoDataFrame)
        self.assertEqual(result.events.crs.to_epsg(), 4326)
        self.assertEqual(set(result.events.geom_type), {"Point"})
        self.assertIsInstance(result.tracks, gpd.GeoDataFrame)
        self.assertEqual(set(result.tracks.geom_type), {"MultiLineString"})
        self.assertGreater(result.tracks.geometry.iloc[0].length, 0)
        self.assertEqual(str(result.events["nav_status"].dtype), "Int64")
        self.assertEqual(result.events.attrs["units"]["min_clearance_m"], "m")
        flat = shoal.audit(read_fixes(track), self.grid, dims=DIMS, columns=COLUMNS, file=track, geo=False)
        self.assertNotIsInstance(flat.events, gpd.GeoDataFrame)
        self.assertEqual(flat.events["lon"].tolist(), [p.x for p in result.events.geometry])

    def test_errors(self):
        df = read_fixes(os.path.join(support.AIS_CASES, "passes_clear.csv"))
        with self.assertRaisesRegex(shoal.UsageError, "step_m 0.001 is under the smallest step"):
            shoal.audit(df, self.grid, dims=DIMS, step_m=0.001)
        with self.assertRaisesRegex(ValueError, "margin_m must be a finite number >= 0"):
            shoal.audit(df, self.grid, dims=DIMS, margin_m=float("nan"))
        # As the CLI's --berthing-speed: at most SweepOptions::max_berthing_speed_kn (5 kn);
        # 1e300 called every grounding alongside.
        with self.assertRaisesRegex(ValueError, r"berthing_speed_kn must be at most 5 \(faster is no berthing; got 1e\+300\)"):
            shoal.audit(df, self.grid, dims=DIMS, berthing_speed_kn=1e300)
        with self.assertRaisesRegex(ValueError, "berth_tolerance_m must be at most 1000"):
            shoal.audit(df, self.grid, dims=DIMS, berth_tolerance_m=1e300)
        with self.assertRaisesRegex(ValueError, "no lat column"):
            shoal.audit(df.drop(columns=["LAT"]), self.grid, dims=DIMS)
        with self.assertRaisesRegex(ValueError, "columns: id column 'mmsi_typo' is not in the DataFrame"):
            shoal.audit(df, self.grid, dims=DIMS, columns={"id": "mmsi_typo"})
        with self.assertRaisesRegex(TypeError, r"^shoal.audit\(\) got an unexpected keyword argument 'no_such_option'$"):
            shoal.audit(df, self.grid, dims=DIMS, no_such_option=1)
        with self.assertRaisesRegex(shoal.InputError, "not_a_dataset.txt"):
            shoal.audit(df, self.grid, dims=DIMS, berths=support.data("coast/not_a_dataset.txt"))

    def test_a_wrong_keyword_or_type_is_one_line_naming_it(self):
        # The message names the keyword (and the nearest known one), in one line whose length does
        # not grow with the data: pybind11's own listed every argument, the fixes' columns too
        # (177 KB for 4,061 rows).
        small = read_fixes(os.path.join(support.AIS_CASES, "passes_clear.csv"))
        big = pd.concat([small] * 200, ignore_index=True)
        cases = [
            ({"margn_m": 50}, "shoal.audit() got an unexpected keyword argument 'margn_m' (did you mean 'margin_m'?)"),
            ({"margin_m": "50"}, "shoal.audit(): margin_m must be a number, not str '50'"),
            ({"margin_m": None}, "shoal.audit(): margin_m must be a number, not NoneType None"),
            ({"jobs": -1}, "shoal.audit(): jobs must be a whole number >= 0, not int -1"),
            ({"jobs": 1.5}, "shoal.audit(): jobs must be a whole number, not float 1.5"),
            ({"encounters": "yes"}, "shoal.audit(): encounters must be True or False, not str 'yes'"),
            ({"berths": 3}, "shoal.audit(): berths must be a path (str or os.PathLike) or a list of paths, not int 3"),
            ({"progress": 3}, "shoal.audit(): progress must be a callable(done, total) or None, not int 3"),
            ({"world": 1}, "shoal.audit(): world must be a str or None, not int 1"),
            ({"dims": "abc"}, "shoal.audit(): dims must be four numbers (a, b, c, d), not str 'abc'"),
            ({"ship": 3, "dims": None}, "shoal.audit(): ship must be a path (str or os.PathLike), not int 3"),
            # Past what the checks know (an unsigned beyond 64 bits): still one line, the options only.
            ({"jobs": 2 ** 70}, "shoal.audit(): an option's value has a type the audit does not take "
                                "(jobs=1180591620717411303424, ship=None, dims=(100, 20, 8, 8))"),
        ]
        for kw, message in cases:
            kw = dict({"dims": DIMS}, **kw)
            for df in (small, big):
                with self.assertRaises(TypeError, msg=kw) as caught:
                    shoal.audit(df, self.grid, **kw)
                self.assertEqual(str(caught.exception), message)
                self.assertIsNone(caught.exception.__cause__)
                self.assertTrue(caught.exception.__suppress_context__ or caught.exception.__context__ is None)
        with self.assertRaisesRegex(TypeError, r"^shoal.audit\(\): grid must be a shoal.Grid .*not str$"):
            shoal.audit(small, "coast.shoalgrid", dims=DIMS)
        # What the checks let through is the audit's: numpy numbers work.
        ok = shoal.audit(small, self.grid, dims=np.array(DIMS, dtype=float), margin_m=np.float32(50), jobs=np.int64(1))
        self.assertEqual(ok.summary["fixes"], len(small))

    def test_times_are_utc_datetimes(self):
        track = os.path.join(support.AIS_CASES, "aground_at_speed.csv")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            result = shoal.audit(read_fixes(track), self.grid, dims=DIMS, columns=COLUMNS, file=track)
        for layer, names in ((result.events, ("start", "end", "start_not_before")), (result.tracks, ("start", "end"))):
            for name in names:
                self.assertEqual(str(layer[name].dtype), "datetime64[ns, UTC]", name)
        # The fixes' own times bound the track's (BaseDateTime in the CSV, read here by pandas).
        fixes = pd.to_datetime(read_fixes(track)["BaseDateTime"], utc=True)
        self.assertEqual(result.tracks["start"].iloc[0], fixes.min())
        self.assertEqual(result.tracks["end"].iloc[0], fixes.max())
        grounding = result.events[result.events["kind"] == "grounding"].iloc[0]
        self.assertTrue(fixes.min() <= grounding["start"] <= grounding["end"] <= fixes.max())
        self.assertAlmostEqual((grounding["end"] - grounding["start"]).total_seconds(), grounding["duration_s"], places=2)
        self.assertEqual(result.summary["first_fix"], fixes.min())
        self.assertEqual(result.summary["last_fix"], fixes.max())
        # Time arithmetic as pandas users do it: events per hour.
        self.assertEqual(int(result.events.set_index("start").resample("1H").size().sum()), len(result.events))
        # The report's times as they come, whole seconds beside milliseconds and none, in either
        # order (pandas 2 infers one format from the first unless told ISO 8601).
        for texts in (["2014-08-15T19:01:30Z", "2014-08-15T19:01:30.813Z", "", None], ["2014-08-15T19:01:30.813Z", "2014-08-15T19:01:30Z"]):
            times = shoal._datetimes(texts)
            self.assertEqual(str(times.dtype), "datetime64[ns, UTC]")
            self.assertEqual(sorted(t.value for t in times if t is not pd.NaT), [1408129290000000000, 1408129290813000000])
            self.assertEqual(int(times.isna().sum()), len(texts) - 2)

    def test_progress_is_called(self):
        df = read_fixes(os.path.join(support.AIS_CASES, "moored_then_leaves.csv"))
        seen = []
        shoal.audit(df, self.grid, dims=DIMS, progress=lambda done, total: seen.append((done, total)))
        self.assertTrue(seen)
        self.assertEqual(seen[-1], (len(df), len(df)))  # once at the end: every fix swept
        self.assertTrue(all(t == len(df) and 0 <= d <= t for d, t in seen))

        def fail(done, total):
            raise KeyError("stop")
        with self.assertRaises(KeyError):  # an error in the callback is raised once the audit is over
            shoal.audit(df, self.grid, dims=DIMS, progress=fail)


if __name__ == "__main__":
    unittest.main()
