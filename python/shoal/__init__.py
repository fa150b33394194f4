"""shoal: ship tracks audited against chart coastlines, from Python.

    import shoal
    grid = shoal.Grid.build(["coast.geojson"])            # or shoal.Grid.load("coast.shoalgrid")
    det = shoal.Detector(grid, dims=(100, 20, 8, 8))       # or ship="ship.json"
    r = det.check(lat, lon, heading)                        # numpy arrays in, arrays out (GIL released)
    result = shoal.audit(df, grid, dims=(100, 20, 8, 8))    # a pandas DataFrame of fixes
    result.events, result.tracks, result.problems           # the report's layers as (Geo)DataFrames

The C++ library does the work (the extension shoal._shoal); this file turns DataFrames into its
columns and its layers back into DataFrames. `shoal.dask` drives the `shoal` executable and
imports without the extension.
"""

try:
    from ._shoal import Detector, Grid, InputError, UsageError, __version__, _audit
    from ._shoal import _column_table, _is_time_column_name, _normalise_column_name
except ImportError as _error:  # the extension is not built here (a sanitizer build) or not found
    _import_error = _error

    def __getattr__(name):
        if name.startswith("__") or name not in ("Detector", "Grid", "InputError", "UsageError", "__version__", "_audit", "audit",
                                                  "DEFAULT_COLUMNS"):
            # Not the extension's: the ordinary AttributeError, so `from shoal import dask` imports the submodule.
            raise AttributeError("module 'shoal' has no attribute %r" % name)
        raise ImportError(
            "shoal.%s needs the extension shoal._shoal, which did not import (%s); build shoal with pybind11-dev "
            "and python3-dev installed and put the build's python folder (or <prefix>/lib/python3/dist-packages) "
            "on PYTHONPATH" % (name, _import_error))

__all__ = ["Grid", "Detector", "InputError", "UsageError", "audit", "AuditResult", "DEFAULT_COLUMNS"]

# The column names shoal.audit looks for when `columns` does not say (case-insensitive, a leading
# "#" and blanks ignored; the first present wins): the track readers' own table
# (shoal/track/columns.hpp), for the roles a DataFrame's fixes have, and `line`.
_ROLES = ("id", "time", "lat", "lon", "heading", "cog", "sog", "a", "b", "c", "d", "draught", "name", "nav_status",
          "mobile_type", "ship_type")
if "_column_table" in globals():
    DEFAULT_COLUMNS = {field: names for field, names in _column_table() if field in _ROLES}
    DEFAULT_COLUMNS = {role: DEFAULT_COLUMNS[role] for role in _ROLES}
    DEFAULT_COLUMNS["line"] = []


class AuditResult:
    """What shoal.audit found: the report's layers.

    events, tracks (GeoDataFrames in EPSG:4326 when geopandas imports, else DataFrames with
    lon/lat columns), problems (DataFrame), run and summary (dicts); times are datetime64[ns, UTC]
    (Timestamps in the dicts); in exercise mode
    (encounters=True) also encounters and closest_approaches. Field names, types, units and
    rounding are the report's (docs/user-guide.md, "Report").
    """

    def __init__(self, layers):
        self.__dict__.update(layers)

    def __repr__(self):
        s = self.summary
        return "<shoal.AuditResult: %d tracks, %d fixes, %d events (%d groundings), %d problems>" % (
            s["tracks"], s["fixes"], s["events"], s["groundings"], len(self.problems))


def _find_columns(df, columns):
    by_name = {}
    for c in df.columns:
        by_name.setdefault(_normalise_column_name(str(c)), c)
    found = {}
    given = dict(columns or {})
    unknown = set(given) - set(DEFAULT_COLUMNS)
    if unknown:
        raise ValueError("columns: unknown role(s) %s; roles are %s" % (sorted(unknown), ", ".join(DEFAULT_COLUMNS)))
    for role, names in DEFAULT_COLUMNS.items():
        if role in given:
            if given[role] is None:
                continue
            if given[role] not in df.columns:
                raise ValueError("columns: %s column %r is not in the DataFrame (its columns: %s)"
                                 % (role, given[role], ", ".join(map(str, df.columns))))
            found[role] = given[role]
            continue
        for n in names:
            if n in by_name:
                found[role] = by_name[n]
                break
        if role == "time" and role not in found:  # as the CSV reader: TIMESTAMP_UTC, Time (UTC), ...
            spelt = [c for c in df.columns if _is_time_column_name(str(c))]
            if spelt:
                found[role] = spelt[0]
    if "id" not in found and "name" in found:  # as the CSV reader: the vessel's name identifies it
        found["id"] = found["name"]
    for role in ("time", "lat", "lon"):
        if role not in found:
            raise ValueError("the fixes have no %s column (looked for %s; name it with columns={%r: ...})"
                             % (role, ", ".join(DEFAULT_COLUMNS[role]), role))
    if any(r in found for r in "abcd") and not all(r in found for r in "abcd"):
        for r in "abcd":
            found.pop(r, None)
    return found


def _texts(series):
    """A column as strings: integral floats without ".0" (an MMSI read with NaN in it), missing as ""."""
    import numpy as np
    import pandas as pd
    s = series
    if pd.api.types.is_float_dtype(s):
        v = s.to_numpy(dtype=float)
        ok = np.isfinite(v)
        if np.all(v[ok] == np.round(v[ok])):
            s = s.astype("Int64")
    out = s.astype("string").fillna("")
    return out.tolist()


def _numbers(series):
    import pandas as pd
    if pd.api.types.is_bool_dtype(series):
        series = series.astype(float)
    return pd.to_numeric(series, errors="coerce").to_numpy(dtype=float, na_value=float("nan"))


def _times(series):
    """("time", epoch seconds) for datetimes and numbers, ("time_text", strings) for text (read as the CSV reader reads it)."""
    import numpy as np
    import pandas as pd
    if pd.api.types.is_datetime64_any_dtype(series):
        s = series
        if getattr(s.dt, "tz", None) is not None:
            s = s.dt.tz_convert("UTC").dt.tz_localize(None)
        ns = s.to_numpy(dtype="datetime64[ns]")
        out = ns.astype("int64").astype(float) / 1e9
        out[np.isnat(ns)] = np.nan
        return "time", out
    if pd.api.types.is_numeric_dtype(series):
        return "time", _numbers(series)
    return "time_text", _texts(series)


def _columns_of(df, found):
    cols = {}
    for role, name in found.items():
        s = df[name]
        if role in ("id", "name", "nav_status", "mobile_type"):
            cols[role] = _texts(s)
        elif role == "time":
            key, values = _times(s)
            cols[key] = values
        else:
            cols[role] = _numbers(s)
    return cols


def _datetimes(values):
    """The report's times (ISO 8601 UTC text, "2014-08-15T19:01:30Z" or with milliseconds "...30.813Z",
    track::format_iso8601; "" or None for none) as a datetime64[ns, UTC] Series (NaT for none)."""
    import pandas as pd
    texts = pd.Series([v if v else None for v in values], dtype=object)
    # pandas' own ISO 8601 parser, exact to the nanosecond. From pandas 2 a format is inferred
    # from the first time and every other must match it, so whole seconds beside milliseconds
    # would fail: "ISO8601" takes each as it comes (pandas 1.5, Debian 12's, always did).
    major = int(pd.__version__.split(".")[0])
    return pd.to_datetime(texts, utc=True, **({"format": "ISO8601"} if major >= 2 else {}))


def _frame(layer):
    import pandas as pd
    dtypes = {"integer": "Int64", "real": "float64", "boolean": "boolean", "text": "object"}
    data = {}
    for name, kind in zip(layer["names"], layer["types"]):
        values = layer["columns"][name]
        data[name] = _datetimes(values) if kind == "datetime" else pd.Series(values, dtype=dtypes[kind])
    df = pd.DataFrame(data, columns=layer["names"])
    df.attrs["units"] = dict(zip(layer["names"], layer["units"]))
    return df


def _one_row(layer):
    row = {}
    for name, kind in zip(layer["names"], layer["types"]):
        v = layer["columns"][name][0]
        row[name] = _datetimes([v]).iloc[0] if kind == "datetime" else v  # a Timestamp (UTC), NaT for none
    return row


def _with_points(df, points, use_geopandas):
    if use_geopandas:
        import geopandas as gpd
        xs = [p[0] for p in points]
        ys = [p[1] for p in points]
        out = gpd.GeoDataFrame(df, geometry=gpd.points_from_xy(xs, ys, crs="EPSG:4326"), crs="EPSG:4326")
        out.attrs.update(df.attrs)
        return out
    df = df.copy()
    df["lon"] = [p[0] for p in points]
    df["lat"] = [p[1] for p in points]
    return df


def _with_lines(df, lines, use_geopandas):
    if not use_geopandas:
        return df
    import geopandas as gpd
    from shapely.geometry import MultiLineString
    geoms = [MultiLineString([[tuple(p) for p in piece] for piece in pieces if len(piece) >= 2]) for pieces in lines]
    out = gpd.GeoDataFrame(df, geometry=gpd.GeoSeries(geoms, crs="EPSG:4326"), crs="EPSG:4326")
    out.attrs.update(df.attrs)
    return out


def _geopandas_available():
    try:
        import geopandas  # noqa: F401
        return True
    except ImportError:
        return False


def _audit_keywords():
    """{keyword: type} of shoal._audit's options, read from the extension's own signature (pybind11
    writes it as the docstring's first line: "_audit(grid: ..., *, ship: object = None, margin_m:
    float = 50.0, ...) -> dict"), so that the keywords checked here are the extension's."""
    import re
    first = (_audit.__doc__ or "").splitlines()[0] if _audit.__doc__ else ""
    m = re.search(r"\*, (.*)\) ->", first)
    if not m:
        return None
    out = {}
    for part in m.group(1).split(", "):
        name, _, rest = part.partition(": ")
        out[name] = rest.partition(" = ")[0]
    return out


# The options whose type pybind11 sees as `object`, and what each takes (checked here, so that an
# error names the keyword: the extension's own message for a bad argument holds every argument).
_PATHS = "a path (str or os.PathLike) or a list of paths"
_OBJECT_KINDS = {"ship": "path", "berths": "paths", "vessels": "paths", "dims": "dims", "ukc": "number",
                 "hazard_depth_m": "number", "progress": "callable", "world": "text"}


def _is_path(v):
    import os
    return isinstance(v, (str, os.PathLike))


def _type_problem(kind, v):
    """What is wrong with v as a `kind` (pybind11's type name or one of _OBJECT_KINDS), or None."""
    import numbers
    import numpy as np
    is_bool = isinstance(v, (bool, np.bool_))
    if kind == "float":
        return None if isinstance(v, numbers.Real) and not is_bool else "a number"
    if kind == "int":
        if not isinstance(v, numbers.Integral) or is_bool:
            return "a whole number"
        return None if v >= 0 else "a whole number >= 0"
    if kind == "bool":
        return None if is_bool else "True or False"
    if v is None:  # not given (ship or dims: the extension says which to give)
        return None
    if kind == "path":
        return None if _is_path(v) else "a path (str or os.PathLike)"
    if kind == "paths":
        if _is_path(v):
            return None
        try:
            ok = not isinstance(v, (bytes, dict)) and all(_is_path(p) for p in v)
        except TypeError:
            ok = False
        return None if ok else _PATHS
    if kind == "dims":
        try:
            ok = not isinstance(v, (str, bytes)) and all(isinstance(x, numbers.Real) and not isinstance(x, (bool, np.bool_)) for x in v)
        except TypeError:
            ok = False
        return None if ok else "four numbers (a, b, c, d)"
    if kind == "number":
        return None if isinstance(v, numbers.Real) and not is_bool else "a number or None"
    if kind == "callable":
        return None if callable(v) else "a callable(done, total) or None"
    if kind == "text":
        return None if isinstance(v, str) else "a str or None"
    return None


def _type_name(v):
    t = type(v)
    return t.__name__ if t.__module__ == "builtins" else "%s.%s" % (t.__module__, t.__name__)


def _short(v):
    text = repr(v)
    return text if len(text) <= 60 else text[:57] + "..."


def _check_options(grid, ship, dims, options):
    """One-line TypeErrors naming the keyword for an unknown option or a value of the wrong type,
    before the extension sees them (its own message would repeat every argument: the fixes too)."""
    if not isinstance(grid, Grid):
        raise TypeError("shoal.audit(): grid must be a shoal.Grid (shoal.Grid.load(path) or shoal.Grid.build(paths)), not %s"
                        % _type_name(grid))
    known = _audit_keywords()
    if known is None:  # a signature this file cannot read: the extension checks alone
        return
    for name in options:
        if name not in known or name in ("ship", "dims"):
            import difflib
            near = difflib.get_close_matches(name, [k for k in known if k not in ("ship", "dims")] +
                                             ["ship", "dims", "columns", "file", "geo"], n=1)
            raise TypeError("shoal.audit() got an unexpected keyword argument %r%s" %
                            (name, " (did you mean %r?)" % near[0] if near else ""))
    given = dict(options, ship=ship, dims=dims)
    for name, v in given.items():
        kind = known.get(name)
        kind = _OBJECT_KINDS.get(name, kind) if kind == "object" else kind
        want = _type_problem(kind, v)
        if want:
            raise TypeError("shoal.audit(): %s must be %s, not %s %s" % (name, want, _type_name(v), _short(v)))


def audit(fixes, grid, *, ship=None, dims=None, columns=None, file="DataFrame", geo=None, **options):
    """Audits the tracks in a DataFrame of fixes as `shoal check` audits a track file.

    fixes: a pandas DataFrame, one fix per row: id (MMSI or track name; without one, the rows are
    one track named after `file`), time (datetime64, epoch seconds, or text read as the CSV reader
    reads it), lat, lon (WGS84 degrees), optionally heading, cog, sog (knots), a, b, c, d (AIS
    dimensions, metres), draught (metres), name, nav_status (AIS number or text), mobile_type (DMA's
    "Type of mobile": Base Station and AtoN rows are skipped), ship_type (the AIS number 1-255; a
    text such as DMA's "Cargo" is not read), line (the row's line in its file;
    default the row number, 1-based). Columns are found by the CSV reader's
    names (DEFAULT_COLUMNS) unless `columns` maps a role to a column ({"id": "MMSI", ...}; None: not
    used). grid: a shoal.Grid. ship (a ship file) or dims (a, b, c, d): the hull of tracks without
    their own dimensions. file: the name events and problems give for the rows' source.

    options, as shoal check's: margin_m (50), step_m (5), max_gap_s (600), max_speed_kn (60),
    berthing_speed_kn (1, at most 5), stop_diameter_m (50), stop_time_s (120), jobs (0: all cores),
    encounters (False), ship_margin_m (20), max_encounters_per_ship (20; 0: no limit), berths
    (paths), berth_tolerance_m (10), vessels (vessels CSV paths), ukc, hazard_depth_m (the limiting
    depth wanted; a grid built for another is warned about), progress (a callable(done, total) called about ten times a second),
    world ("real": the chart is a model, the vessels' motion and the run's traffic decide a
    contact's kind; "simulated": the chart is the world; default real, simulated with encounters).
    geo: GeoDataFrames (True), DataFrames (False), or GeoDataFrames when geopandas imports (None).

    An unknown keyword or a value of the wrong type raises a one-line TypeError naming it.
    A bad row (no position, an impossible time, ...) costs that row: it is listed in `problems`
    and counted in the tracks' skipped_rows, and a warning says how many. Returns an AuditResult.
    """
    import pandas as pd
    if not isinstance(fixes, pd.DataFrame):
        raise TypeError("fixes must be a pandas DataFrame (got %s)" % type(fixes).__name__)
    _check_options(grid, ship, dims, options)
    found = _find_columns(fixes, columns)
    cols = _columns_of(fixes, found)
    try:
        raw = _audit(grid, cols, str(file), ship=ship, dims=dims, **options)
    except TypeError as e:
        if "incompatible function arguments" not in str(e):
            raise
        # A value the checks above let through and the extension's types do not take: said in one
        # line with the options (pybind11's message lists every argument, the fixes' columns too).
        given = ", ".join("%s=%s" % (k, _short(v)) for k, v in dict(options, ship=ship, dims=dims).items())
        raise TypeError("shoal.audit(): an option's value has a type the audit does not take (%s)" % given) from None
    use_geopandas = _geopandas_available() if geo is None else bool(geo)
    layers = {
        "events": _with_points(_frame(raw["events"]), raw["event_points"], use_geopandas),
        "tracks": _with_lines(_frame(raw["tracks"]), raw["track_lines"], use_geopandas),
        "problems": _frame(raw["problems"]),
        "run": _one_row(raw["run"]),
        "summary": _one_row(raw["summary"]),
    }
    if "encounters" in raw:
        layers["encounters"] = _with_points(_frame(raw["encounters"]), raw["encounter_points"], use_geopandas)
        layers["closest_approaches"] = _frame(raw["closest_approaches"])
    return AuditResult(layers)
