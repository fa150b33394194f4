#!/usr/bin/python3
"""Writes the hand-made AIS audit cases of this folder and expected.json.

Run with Debian's /usr/bin/python3 (python3-gdal, GDAL 3.6):

    /usr/bin/python3 tests/data/tracks/ais_cases/make_cases.py

Every track is made against the real coastline examples/data/gof_helsinki_land.geojson (GSHHG
land polygons around Helsinki) for the hull --dims 100,20,8,8. Geometry is computed with OGR
in a local transverse Mercator frame (WGS84 ellipsoid) centred on each case's site; true
headings are turned into grid azimuths with the frame's meridian convergence at the point.
Every position gets gaussian GPS jitter (sigma 3 m east and 3 m north, independently; one
fixed seed per case), is written with 6 decimals, and every check on a written fix is made
on the values read back from the text. The output is the same on every run.
"""

import datetime as dt
import json
import math
import os
import random
import sys

from osgeo import ogr, osr

ogr.UseExceptions()
osr.UseExceptions()

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", "..", "..", ".."))
COAST_REL = "examples/data/gof_helsinki_land.geojson"
COAST = os.path.join(REPO, COAST_REL)

DIMS = (100.0, 20.0, 8.0, 8.0)  # AIS A (to bow), B (to stern), C (to port), D (to starboard)
SIGMA_M = 3.0
KN = 1852.0 / 3600.0  # m/s per knot
HEADER = ("MMSI,BaseDateTime,LAT,LON,SOG,COG,Heading,VesselName,IMO,CallSign,VesselType,Status,"
          "Length,Width,Draft,Cargo,TransceiverClass")

WGS84 = osr.SpatialReference()
WGS84.ImportFromEPSG(4326)
WGS84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)


# ---------------------------------------------------------------------------------------------
# Hull outlines, in ship coordinates (x forward, y to starboard), metres from the reference point


def box_outline(dims=DIMS):
    a, b, c, d = dims
    return [(a, -c), (a, d), (-b, d), (-b, -c)]


def shoal_outline(dims=DIMS, n=36):
    """The outline shoal generates for --dims (src/hull/hull.cpp generate_outline, 36 points:
    a parabolic pointed bow from the shoulder at x = a - min(0.25 L, 0.9 a) to the tip (a, 0),
    a parallel midbody and rounded quarters of radius min(0.3 half beam, 0.08 L, 0.9 b)),
    written again here only to check that the bow's shape matters little."""
    a, b, c, d = dims
    length, half_beam, centre = a + b, 0.5 * (c + d), 0.5 * (d - c)
    per_side = (n - 1 - (1 if n % 2 == 0 else 0)) // 2
    quarter = min(max(int(round(0.22 * per_side)), 1), 4)
    middle = int(0.18 * per_side)
    bow = per_side - quarter - middle
    bow_len = min(0.25 * length, 0.9 * a)
    radius = min(0.3 * half_beam, 0.08 * length, 0.9 * b) if quarter >= 2 else 0.0
    shoulder_x, quarter_x = a - bow_len, -b + radius

    def side(sign):
        edge = d if sign > 0 else -c
        pts = []
        for j in range(bow - 1, -1, -1):
            t = j / bow
            pts.append((shoulder_x + t * bow_len, edge + (centre - edge) * t * t))
        for i in range(1, middle + 1):
            f = i / (middle + 1)
            pts.append((shoulder_x + (quarter_x - shoulder_x) * f, edge))
        if quarter == 1:
            pts.append((-b, edge))
        else:
            for j in range(quarter):
                phi = 0.5 * math.pi * j / (quarter - 1)
                pts.append((-b + radius * (1 - math.sin(phi)), edge - sign * radius * (1 - math.cos(phi))))
        return pts

    out = [(a, centre)] + side(+1)
    if n % 2 == 0:
        out.append((-b, centre))
    out += list(reversed(side(-1)))
    assert len(out) == n
    return out


OUTLINE = shoal_outline()
BOX = box_outline()


# ---------------------------------------------------------------------------------------------
# A site: local frame and the land around it


def point(x, y):
    p = ogr.Geometry(ogr.wkbPoint)
    p.AddPoint_2D(x, y)
    return p


def polygon(pts):
    ring = ogr.Geometry(ogr.wkbLinearRing)
    for x, y in pts + [pts[0]]:
        ring.AddPoint_2D(x, y)
    poly = ogr.Geometry(ogr.wkbPolygon)
    poly.AddGeometry(ring)
    return poly


def linestring(pts):
    line = ogr.Geometry(ogr.wkbLineString)
    for x, y in pts:
        line.AddPoint_2D(x, y)
    return line


class Site:
    """Local transverse Mercator frame centred on (lon0, lat0), with the coastline's land
    polygons cut to a box of +-half_km around it (the cut edges are far from every track)."""

    def __init__(self, lon0, lat0, half_km=12.0):
        self.lon0, self.lat0 = lon0, lat0
        tm = osr.SpatialReference()
        tm.ImportFromProj4("+proj=tmerc +lat_0=%.9f +lon_0=%.9f +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +no_defs"
                           % (lat0, lon0))
        self.fwd = osr.CoordinateTransformation(WGS84, tm)
        self.inv = osr.CoordinateTransformation(tm, WGS84)
        dlat = half_km / 111.0
        dlon = half_km / (111.0 * math.cos(math.radians(lat0)))
        box = polygon([(lon0 - dlon, lat0 - dlat), (lon0 + dlon, lat0 - dlat), (lon0 + dlon, lat0 + dlat),
                       (lon0 - dlon, lat0 + dlat)])
        ds = ogr.Open(COAST)
        layer = ds.GetLayer()
        layer.SetSpatialFilter(box)
        self.land = ogr.Geometry(ogr.wkbMultiPolygon)
        self.fids = {}
        for f in layer:
            g = f.GetGeometryRef().Intersection(box)
            if g is None or g.IsEmpty():
                continue
            g.Transform(self.fwd)
            parts = [g] if g.GetGeometryType() == ogr.wkbPolygon else [g.GetGeometryRef(i) for i in range(g.GetGeometryCount())]
            for p in parts:
                if p.GetGeometryType() == ogr.wkbPolygon:
                    self.land.AddGeometry(p)
                    self.fids.setdefault(f.GetFID(), []).append(p.Clone())
        self.boundary = self.land.GetBoundary()

    def xy(self, lon, lat):
        x, y, _ = self.fwd.TransformPoint(lon, lat)
        return x, y

    def ll(self, x, y):
        lon, lat, _ = self.inv.TransformPoint(x, y)
        return lon, lat

    def convergence(self, x, y):
        """Grid azimuth of true north at (x, y), degrees."""
        lon, lat = self.ll(x, y)
        x1, y1 = self.xy(lon, lat + 1e-5)
        return math.degrees(math.atan2(x1 - x, y1 - y))

    def grid_az(self, true_deg, x, y):
        return true_deg + self.convergence(x, y)

    def true_az(self, grid_deg, x, y):
        return (grid_deg - self.convergence(x, y)) % 360.0

    def hull(self, x, y, true_heading, outline=OUTLINE):
        th = math.radians(self.grid_az(true_heading, x, y))
        fx, fy = math.sin(th), math.cos(th)   # forward
        sx, sy = math.cos(th), -math.sin(th)  # starboard
        return polygon([(x + px * fx + py * sx, y + px * fy + py * sy) for px, py in outline])

    def hull_point(self, x, y, true_heading, px, py):
        th = math.radians(self.grid_az(true_heading, x, y))
        return (x + px * math.sin(th) + py * math.cos(th), y + px * math.cos(th) - py * math.sin(th))

    def touches(self, geom):
        return geom.Intersects(self.land)

    def clearance(self, geom):
        return 0.0 if geom.Intersects(self.land) else geom.Distance(self.land)

    def penetration(self, hull):
        """How far the hull reaches past the coastline: the deepest hull vertex inside land
        (its distance to the coastline), or the deepest coastline vertex inside the hull
        (its distance to the hull's outline); 0 when clear."""
        if not hull.Intersects(self.land):
            return 0.0
        best = 0.0
        ring = hull.GetGeometryRef(0)
        for i in range(ring.GetPointCount() - 1):
            p = point(*ring.GetPoint_2D(i))
            if p.Within(self.land):
                best = max(best, p.Distance(self.boundary))
        hb = hull.GetBoundary()
        env = hull.GetEnvelope()
        for poly in self.land:
            if not hull.Intersects(poly):
                continue
            for r in range(poly.GetGeometryCount()):
                rr = poly.GetGeometryRef(r)
                for i in range(rr.GetPointCount()):
                    vx, vy = rr.GetPoint_2D(i)
                    if env[0] <= vx <= env[1] and env[2] <= vy <= env[3]:
                        p = point(vx, vy)
                        if p.Within(hull):
                            best = max(best, p.Distance(hb))
        return best


# ---------------------------------------------------------------------------------------------
# Writing fixes


class Vessel:
    def __init__(self, mmsi, name, vtype=70, length=120, width=16, draft=7.0, cargo=70):
        self.mmsi, self.name, self.vtype = mmsi, name, vtype
        self.length, self.width, self.draft, self.cargo = length, width, draft, cargo


def fmt_opt(v, f="%.1f"):
    return "" if v is None else f % v


class Track:
    """Rows of one vessel; each fix is jittered, written, and read back for the checks."""

    def __init__(self, site, vessel, start, seed):
        self.site, self.vessel, self.start = site, vessel, start
        self.rng = random.Random(seed)
        self.seed = seed
        self.rows = []   # text lines (without the header)
        self.fixes = []  # dicts: t, line, x, y (written, local), x0, y0 (un-jittered), heading, ...

    def jitter(self):
        return self.rng.gauss(0.0, SIGMA_M), self.rng.gauss(0.0, SIGMA_M)

    def add(self, t, x0, y0, sog, cog, heading, status, jitter=None, lonlat=None):
        """Adds a fix at t seconds after start at the un-jittered local position (x0, y0).
        heading: true heading in integer degrees or None (written 511). lonlat overrides the
        position (an outlier written as given)."""
        if lonlat is None:
            dx, dy = jitter if jitter is not None else self.jitter()
            lon, lat = self.site.ll(x0 + dx, y0 + dy)
            lat_s, lon_s = "%.6f" % lat, "%.6f" % lon
        else:
            lon, lat = lonlat
            lat_s, lon_s = "%.6f" % lat, "%.6f" % lon
        when = self.start + dt.timedelta(seconds=t)
        hdg = 511 if heading is None else int(heading) % 360
        v = self.vessel
        row = ",".join([str(v.mmsi), when.strftime("%Y-%m-%dT%H:%M:%S"), lat_s, lon_s, fmt_opt(sog), fmt_opt(cog),
                        str(hdg), v.name, "", "", str(v.vtype), str(status), str(v.length), str(v.width),
                        "%.1f" % v.draft, str(v.cargo), "A"])
        self.rows.append(row)
        fx = dict(t=t, line=len(self.rows) + 1, time=when, lat=float(lat_s), lon=float(lon_s), x0=x0, y0=y0,
                  heading=None if heading is None else hdg, sog=sog, cog=cog, status=status)
        if lonlat is None:
            fx["x"], fx["y"] = self.site.xy(fx["lon"], fx["lat"])
        self.fixes.append(fx)
        return fx

    def write(self, path):
        with open(path, "w", newline="\n") as f:
            f.write(HEADER + "\n")
            for r in self.rows:
                f.write(r + "\n")


def iso(start, t):
    when = start + dt.timedelta(seconds=t)
    return when.strftime("%Y-%m-%dT%H:%M:%S.%f")[:-4] + "Z"


def r2(v):
    return None if v is None else round(v, 2)


def bisect(f, lo, hi, tol=0.001):
    """First t in (lo, hi] with f(t) true, given f(lo) false and f(hi) true."""
    assert not f(lo) and f(hi)
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if f(mid):
            hi = mid
        else:
            lo = mid
    return hi


def first_true(f, t0, t1, step):
    """Bracket of the first t (scanning from t0 by step) where f is true, then bisected."""
    t = t0
    prev = t0
    assert not f(t0)
    while t < t1:
        t = min(t + step, t1)
        if f(t):
            return bisect(f, prev, t)
        prev = t
    return None


def contact_intervals(flags, times):
    """[(first_true_time, last_true_time)] runs of true flags."""
    out, cur = [], None
    for flag, t in zip(flags, times):
        if flag and cur is None:
            cur = [t, t]
        elif flag:
            cur[1] = t
        elif cur is not None:
            out.append(tuple(cur))
            cur = None
    if cur is not None:
        out.append(tuple(cur))
    return out


def segment_by_vertices(site, fid, lonlat0, lonlat1):
    """Checks that two given vertices are consecutive vertices of feature `fid` of the
    coastline, and returns them in local metres."""
    ds = ogr.Open(COAST)
    feature = ds.GetLayer().GetFeature(fid)
    g = feature.GetGeometryRef().Clone()
    found = False
    for r in range(g.GetGeometryCount()):
        ring = g.GetGeometryRef(r)
        pts = [ring.GetPoint_2D(i) for i in range(ring.GetPointCount())]
        for i in range(len(pts) - 1):
            a, b = pts[i], pts[i + 1]
            same = lambda p, q: abs(p[0] - q[0]) < 1e-9 and abs(p[1] - q[1]) < 1e-9
            if (same(a, lonlat0) and same(b, lonlat1)) or (same(a, lonlat1) and same(b, lonlat0)):
                found = True
    assert found, "segment not in feature %d" % fid
    return site.xy(*lonlat0), site.xy(*lonlat1)


def fix_report(site, fx, outline=OUTLINE):
    """Contact facts of a written fix with a known heading."""
    h = site.hull(fx["x"], fx["y"], fx["heading"], outline)
    return dict(line=fx["line"], time=fx["time"].strftime("%Y-%m-%dT%H:%M:%SZ"),
                contact=site.touches(h), clearance_m=r2(site.clearance(h)), penetration_m=r2(site.penetration(h)))


# ---------------------------------------------------------------------------------------------
# Cases 1 and 2: aground at speed


# Island GSHHG feature 1740 (1.26 km2), its south shore: an east-west segment of 464 m at
# 60.1695583 N, open water south of it for more than 2.5 km.
C1_FID = 1740
C1_SEG = ((25.3333028, 60.1695583), (25.3249409, 60.1695583))
C1_COURSE = 3          # true course and heading, degrees
C1_SPEED_KN = 10.0
C1_T_TARGET = 224.3    # seconds from the first fix to the bow tip's contact (aimed at; T is computed)


def case_aground(no_sog):
    mid_ll = ((C1_SEG[0][0] + C1_SEG[1][0]) / 2, C1_SEG[0][1])
    site = Site(*mid_ll)
    a, b = segment_by_vertices(site, C1_FID, *C1_SEG)
    mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    th = math.radians(site.grid_az(C1_COURSE, mx, my))
    ux, uy = math.sin(th), math.cos(th)
    v = C1_SPEED_KN * KN
    # The reference point starts so that the bow tip reaches the segment's midpoint at
    # C1_T_TARGET on a straight line: the tip is then 100 m + v*t ahead of it.
    d0 = DIMS[0] + v * C1_T_TARGET
    sx, sy = mx - ux * d0, my - uy * d0

    def ref(t):
        return sx + ux * v * t, sy + uy * v * t

    def tip_in(t):
        x, y = ref(t)
        return site.touches(point(*site.hull_point(x, y, C1_COURSE, DIMS[0], 0.0)))

    def outline_in(t, outline):
        x, y = ref(t)
        return site.touches(site.hull(x, y, C1_COURSE, outline))

    t_end = C1_T_TARGET + 30
    T_tip = first_true(tip_in, 0.0, t_end, 0.5)
    T_outline = first_true(lambda t: outline_in(t, OUTLINE), 0.0, t_end, 0.5)
    T_box = first_true(lambda t: outline_in(t, BOX), 0.0, t_end, 0.5)
    # Cross-check the tip's contact analytically: where the tip's straight path first enters land.
    tip0 = site.hull_point(*ref(0.0), C1_COURSE, DIMS[0], 0.0)
    tip1 = site.hull_point(*ref(t_end), C1_COURSE, DIMS[0], 0.0)
    cut = linestring([tip0, tip1]).Intersection(site.land)
    first_d = min(math.hypot(x - tip0[0], y - tip0[1]) for x, y in _coords(cut))
    T_ray = first_d / v
    assert abs(T_ray - T_tip) < 0.01, (T_ray, T_tip)
    # Nothing before: the hull's swept area from the start to just before contact is clear.
    h0 = site.hull(*ref(0.0), C1_COURSE)
    h1 = site.hull(*ref(T_outline - 0.01), C1_COURSE)
    swept = h0.Union(h1).ConvexHull()  # the outline is convex: this is the area it sweeps
    assert not site.touches(swept)
    start_clearance = site.clearance(h0)
    assert start_clearance >= 1000.0, start_clearance
    contact_ll = site.ll(*site.hull_point(*ref(T_tip), C1_COURSE, DIMS[0], 0.0))

    if no_sog:
        vessel = Vessel(230990002, "AGROUND NO SOG")
        start = dt.datetime(2024, 5, 2, 10, 0, 0)
        seed = 20240502
    else:
        vessel = Vessel(230990001, "AGROUND AT SPEED")
        start = dt.datetime(2024, 5, 1, 10, 0, 0)
        seed = 20240501
    tr = Track(site, vessel, start, seed)
    t_stop = 10 * (int(T_tip // 10) + 1)  # the first fix after contact: there it stops
    assert 2.0 <= t_stop - T_tip <= 8.0, "T must fall well between two fixes"
    t = 0
    while t <= t_stop:
        x, y = ref(t)
        if no_sog:
            tr.add(t, x, y, None, None, None, 0)
        else:
            tr.add(t, x, y, C1_SPEED_KN, float(C1_COURSE), C1_COURSE, 0)
        t += 10
    xs, ys = ref(t_stop)
    t_status6 = t_stop + 300
    while t <= t_stop + 1800:
        status = 6 if t >= t_status6 else 0
        if no_sog:
            tr.add(t, xs, ys, None, None, None, status)
        else:
            tr.add(t, xs, ys, tr.rng.choice((0.0, 0.1)), float(C1_COURSE), C1_COURSE, status)
        t += 10

    # The written (jittered) fixes, with the heading they would have: the course.
    flags = []
    for fx in tr.fixes:
        h = site.hull(fx["x"], fx["y"], C1_COURSE)
        flags.append(site.touches(h))
    first_in = flags.index(True)
    assert all(flags[first_in:]), "every fix after the first contact is in contact"
    assert tr.fixes[first_in]["t"] == t_stop
    # The contact time on the written track: positions interpolated linearly between the
    # written fixes before and at the first contact, heading the course.
    fa, fb = tr.fixes[first_in - 1], tr.fixes[first_in]

    def interp_in(tt):
        f = (tt - fa["t"]) / (fb["t"] - fa["t"])
        x = fa["x"] + f * (fb["x"] - fa["x"])
        y = fa["y"] + f * (fb["y"] - fa["y"])
        return site.touches(site.hull(x, y, C1_COURSE))

    T_written = bisect(interp_in, fa["t"], fb["t"])
    speed_written = math.hypot(fb["x"] - fa["x"], fb["y"] - fa["y"]) / (fb["t"] - fa["t"]) / KN
    bearing_written = site.true_az(math.degrees(math.atan2(fb["x"] - fa["x"], fb["y"] - fa["y"])), fa["x"], fa["y"])

    def interp_in_bearing(tt):
        f = (tt - fa["t"]) / (fb["t"] - fa["t"])
        x = fa["x"] + f * (fb["x"] - fa["x"])
        y = fa["y"] + f * (fb["y"] - fa["y"])
        return site.touches(site.hull(x, y, bearing_written))

    T_written_bearing = bisect(interp_in_bearing, fa["t"], fb["t"])
    rest = tr.fixes[first_in]
    pen_rest = site.penetration(site.hull(xs, ys, C1_COURSE))

    geometry = dict(
        site=dict(coast_feature_id=C1_FID, shore_segment_lonlat=C1_SEG,
                  shore="south shore of an island east of Helsinki, east-west, land to the north"),
        course_true_deg=C1_COURSE, speed_kn=C1_SPEED_KN,
        start_clearance_m=r2(start_clearance),
        T_s=round(T_tip, 2), T=iso(start, T_tip),
        T_method="bow tip (x=100, y=0) on the un-jittered straight-line motion, first contact with land bisected "
                 "to 0.001 s (OGR Intersects); cross-checked by intersecting the tip's path with the land",
        T_pointed_bow_outline_s=round(T_outline, 2), T_box_outline_s=round(T_box, 2),
        T_written_track_s=round(T_written, 2),
        T_written_track_note="hull outline on the written (jittered) fixes, position interpolated linearly between "
                             "line %d and line %d, heading %s" % (fa["line"], fb["line"],
                                                                   "the course (3 degrees)"),
        contact_point_lonlat=[round(contact_ll[0], 7), round(contact_ll[1], 7)],
        last_fix_before_contact_line=fa["line"], first_fix_in_contact_line=fb["line"],
        first_fix_in_contact_time=fb["time"].strftime("%Y-%m-%dT%H:%M:%SZ"),
        stop_position_lonlat=[round(site.ll(xs, ys)[0], 7), round(site.ll(xs, ys)[1], 7)],
        bow_past_coastline_at_stop_m=r2(pen_rest),
        status_6_from_time=(start + dt.timedelta(seconds=t_status6)).strftime("%Y-%m-%dT%H:%M:%SZ"),
        fixes_in_contact_lines=[fb["line"], tr.fixes[-1]["line"]],
    )
    if no_sog:
        geometry["speed_from_written_positions_kn"] = round(speed_written, 2)
        geometry["bearing_from_written_positions_deg"] = round(bearing_written, 2)
        geometry["T_written_track_bearing_s"] = round(T_written_bearing, 2)
        geometry["T_written_track_bearing_note"] = ("as T_written_track_s, heading the bearing from line %d to line %d"
                                                    % (fa["line"], fb["line"]))
    expect = dict(groundings=1, grounding_start=iso(start, T_tip), start_tolerance_s=5.0 if no_sog else 3.0,
                  speed_kn=[9.0, 11.0])
    if no_sog:
        expect["speed_source"] = "positions"
        expect["note"] = "SOG and COG empty, Heading 511 throughout: speed and heading come from positions"
    return tr, geometry, expect


def _coords(geom):
    out = []
    n = geom.GetGeometryCount()
    if n == 0:
        for i in range(geom.GetPointCount()):
            out.append(geom.GetPoint_2D(i))
    else:
        for i in range(n):
            out += _coords(geom.GetGeometryRef(i))
    return out


# ---------------------------------------------------------------------------------------------
# Case 3: moored alongside, then leaves


# Island GSHHG feature 1624 (2.39 km2, east of Helsinki), its south shore: an east-west
# segment of 369 m at 60.1528954 N, open water south of it.
C3_FID = 1624
C3_SEG = ((25.1266346, 60.1528954), (25.1199969, 60.1528954))
C3_HEADING = 270   # heading west: the starboard side faces the shore to the north
C3_GAP = 1.5       # metres between the starboard side and the coastline
C3_LATERAL = 0.8   # m/s to port, reached 10 s after casting off
C3_LAT_END = 90    # s: the lateral push eases off over the next 60 s
C3_AHEAD_FROM = 60  # s: goes ahead, to 8 kn in 180 s
C3_TURN = 90.0     # degrees turned to port
C3_TURN_FROM = 70  # s
C3_TURN_S = 180    # s


def case_moored():
    mid_ll = ((C3_SEG[0][0] + C3_SEG[1][0]) / 2, C3_SEG[0][1])
    site = Site(*mid_ll)
    a, b = segment_by_vertices(site, C3_FID, *C3_SEG)
    mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    # Hull centred on the segment: heading west, the bow is 100 m west of the reference point
    # and the stern 20 m east, so the reference point is 40 m east of the hull's middle.
    x0 = mx + 40.0
    y0 = my - C3_GAP - DIMS[3]
    h = site.hull(x0, y0, C3_HEADING)
    gap = site.clearance(h)
    assert abs(gap - C3_GAP) < 0.01, gap
    vessel = Vessel(230990003, "MOORED THEN LEAVES")
    start = dt.datetime(2024, 5, 3, 6, 0, 0)
    # Seed 20240503 let only one of the 21 moored fixes touch; 20240522 lets six touch, apart.
    tr = Track(site, vessel, start, 20240522)

    # Moored: every 3 min for an hour. The first fix's jitter is drawn again until its hull is clear.
    for i in range(21):
        t = 180 * i
        jit = tr.jitter()
        if i == 0:
            while site.touches(site.hull(*site.xy(*site.ll(x0 + jit[0], y0 + jit[1])), C3_HEADING)):
                jit = tr.jitter()
        tr.add(t, x0, y0, 0.0, None, C3_HEADING, 5, jitter=jit)
    moored = [fix_report(site, fx) for fx in tr.fixes]
    assert not moored[0]["contact"]
    assert sum(f["contact"] for f in moored) >= 4, "jitter makes the hull touch and clear repeatedly"

    # Leaving, from t = 3600 s: bow and stern thrusters push it to port (south), away from the
    # shore (lateral speed to 0.8 m/s within 10 s, easing off from 60 s to 120 s); from 40 s it
    # goes ahead, to 8 kn at 220 s; from 60 s to 180 s it turns 40 degrees to port.
    t_dep = 3600.0
    grid_h0 = site.grid_az(C3_HEADING, x0, y0)

    def controls(tp):
        w = C3_LATERAL * min(tp / 10.0, 1.0) if tp <= C3_LAT_END else C3_LATERAL * max(0.0, (C3_LAT_END + 60 - tp) / 60.0)
        u = 0.0 if tp <= C3_AHEAD_FROM else 8.0 * KN * min((tp - C3_AHEAD_FROM) / 180.0, 1.0)
        dh = -C3_TURN * min(max((tp - C3_TURN_FROM) / C3_TURN_S, 0.0), 1.0)
        return u, w, dh

    path = []  # (tp, x, y, grid heading, vx, vy)
    x, y = x0, y0
    step = 0.05
    tp = 0.0
    while tp <= 600.0 + 1e-9:
        u, w, dh = controls(tp)
        gh = math.radians(grid_h0 + dh)
        fx_, fy_ = math.sin(gh), math.cos(gh)
        px, py = -math.cos(gh), math.sin(gh)  # port
        vx, vy = u * fx_ + w * px, u * fy_ + w * py
        path.append((tp, x, y, grid_h0 + dh, vx, vy))
        x += vx * step
        y += vy * step
        tp = round(tp + step, 6)
    by_t = {round(p[0], 2): p for p in path}
    # The un-jittered path's least clearance, every second.
    least = []
    for s in range(1, 601):
        p = by_t[round(float(s), 2)]
        th = site.true_az(p[3], p[1], p[2])
        least.append((site.clearance(site.hull(p[1], p[2], th)), s))
    for s in range(10, 601, 10):
        p = by_t[round(float(s), 2)]
        th_true = site.true_az(p[3], p[1], p[2])
        speed = math.hypot(p[4], p[5])
        cog = site.true_az(math.degrees(math.atan2(p[4], p[5])), p[1], p[2])
        tr.add(t_dep + s, p[1], p[2], round(speed / KN, 1), round(cog, 1) % 360.0, int(round(th_true)) % 360, 0)
    leaving = [fix_report(site, fx) for fx in tr.fixes[21:]]
    assert not any(f["contact"] for f in leaving), "the leaving fixes must be clear"
    last = tr.fixes[-1]
    geometry = dict(
        site=dict(coast_feature_id=C3_FID, shore_segment_lonlat=C3_SEG,
                  shore="south shore of an island east of Helsinki, east-west, land to the north"),
        heading_true_deg=C3_HEADING, starboard_side_gap_m=C3_GAP,
        berth_reference_point_lonlat=[round(v, 7) for v in site.ll(x0, y0)],
        moored_lines=[moored[0]["line"], moored[-1]["line"]],
        moored_fixes_in_contact_lines=[f["line"] for f in moored if f["contact"]],
        moored_fixes_clear_lines=[f["line"] for f in moored if not f["contact"]],
        moored_max_penetration_m=max(f["penetration_m"] for f in moored),
        last_moored_fix_in_contact=moored[-1]["contact"],
        leaving_lines=[leaving[0]["line"], leaving[-1]["line"]],
        leaving_least_clearance_m_unjittered_after_10s=r2(min(c for c, s in least if s >= 10)),
        leaving_least_clearance_m_written_fixes=min(f["clearance_m"] for f in leaving),
        leaving_clearance_m_first_written_fix=leaving[0]["clearance_m"],
        final_speed_kn=last["sog"], final_heading_true_deg=last["heading"],
        moored_fixes=moored,
    )
    expect = dict(groundings=0, note="contacts while moored may be reported as another kind (alongside); "
                                      "the departure is clear of land")
    return tr, geometry, expect


# ---------------------------------------------------------------------------------------------
# Case 4: berthing sideways


# Mainland (GSHHG feature 1120) near Espoo: an east-west shore segment of 375 m at
# 60.1562219 N, land to the north, open water south.
C4_FID = 1120
C4_SEG = ((24.7916991, 60.1562219), (24.7849393, 60.1562219))
C4_HEADING = 90      # heading east: the port side faces the shore to the north
C4_SPEED_KN = 0.3
C4_MOVE_S = 280      # seconds of sideways motion, fix to fix
C4_OVERLAP = 2.5     # metres the port side ends up past the coastline


def case_berthing():
    mid_ll = ((C4_SEG[0][0] + C4_SEG[1][0]) / 2, C4_SEG[0][1])
    site = Site(*mid_ll)
    a, b = segment_by_vertices(site, C4_FID, *C4_SEG)
    mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    v = C4_SPEED_KN * KN
    travel = v * C4_MOVE_S
    gap0 = travel - C4_OVERLAP
    x0 = mx - 40.0  # heading east: the reference point is 40 m west of the hull's middle
    y0 = my - gap0 - DIMS[2]
    th = math.radians(site.grid_az(0.0, x0, y0))  # moving true north

    def ref(t):
        s = v * min(t, C4_MOVE_S)
        return x0 + math.sin(th) * s, y0 + math.cos(th) * s

    gap_start = site.clearance(site.hull(*ref(0), C4_HEADING))
    assert abs(gap_start - gap0) < 0.05, (gap_start, gap0)
    T_contact = first_true(lambda t: site.touches(site.hull(*ref(t), C4_HEADING)), 0.0, C4_MOVE_S, 1.0)
    pen_final = site.penetration(site.hull(*ref(C4_MOVE_S), C4_HEADING))
    assert 2.0 <= pen_final <= 3.0, pen_final
    vessel = Vessel(230990004, "BERTHING SIDEWAYS")
    start = dt.datetime(2024, 5, 4, 8, 0, 0)
    tr = Track(site, vessel, start, 20240504)
    for t in range(0, C4_MOVE_S + 1 + 1200, 10):
        x, y = ref(t)
        if t < C4_MOVE_S:
            tr.add(t, x, y, C4_SPEED_KN, 0.0, C4_HEADING, 0)
        else:
            tr.add(t, x, y, 0.0, None, C4_HEADING, 5 if t > C4_MOVE_S else 0)
    reps = [fix_report(site, fx) for fx in tr.fixes]
    assert not reps[0]["contact"]
    first_in = next(r for r in reps if r["contact"])
    arrive = next(r for r, fx in zip(reps, tr.fixes) if fx["t"] == C4_MOVE_S)
    at_rest = [r for r, fx in zip(reps, tr.fixes) if fx["t"] >= C4_MOVE_S]
    geometry = dict(
        site=dict(coast_feature_id=C4_FID, shore_segment_lonlat=C4_SEG,
                  shore="mainland shore west of Helsinki (Espoo), east-west, land to the north"),
        heading_true_deg=C4_HEADING, cog_true_deg=0.0, speed_kn=C4_SPEED_KN,
        start_gap_m=r2(gap_start),
        first_contact_T_s=round(T_contact, 2), first_contact_T=iso(start, T_contact),
        first_contact_method="pointed-bow outline on the un-jittered motion, bisected (OGR Intersects)",
        first_fix_in_contact_line=first_in["line"],
        arrival_line=arrive["line"], arrival_time=arrive["time"],
        overlap_at_rest_m_unjittered=r2(pen_final),
        at_rest_lines=[at_rest[0]["line"], at_rest[-1]["line"]],
        at_rest_fixes_in_contact=sum(1 for r in at_rest if r["contact"]),
        at_rest_fixes=len(at_rest),
        at_rest_penetration_m_range=[min(r["penetration_m"] for r in at_rest), max(r["penetration_m"] for r in at_rest)],
    )
    expect = dict(groundings=0, note="a slow sideways approach onto a berth (0.3 kn): contacts may be reported as "
                                      "another kind (alongside)")
    return tr, geometry, expect


# ---------------------------------------------------------------------------------------------
# Case 5: a jump and a fix at 0,0 in open water


# Open water in Pohjanpitajanlahti (west of Helsinki): more than 600 m from land around the
# route's middle; the mainland lies all round.
C5_MID = (23.9576576, 60.2219457)
C5_COURSE = 51
C5_SPEED_KN = 12.0
C5_DURATION_S = 900
C5_JUMP_INDEX = 45   # the middle fix
C5_NULL_INDEX = 20
C5_JUMP_M = 5000.0


def case_jump():
    site = Site(*C5_MID)
    v = C5_SPEED_KN * KN
    th = math.radians(site.grid_az(C5_COURSE, 0.0, 0.0))
    ux, uy = math.sin(th), math.cos(th)
    half = v * C5_DURATION_S / 2

    def ref(t):
        s = v * t - half
        return ux * s, uy * s

    # Least clearance of the un-jittered hull, every second.
    least = min(site.clearance(site.hull(*ref(float(t)), C5_COURSE)) for t in range(0, C5_DURATION_S + 1))
    assert least >= 500.0, least
    # The jump: 5 km from the middle fix's position, in the direction that lies deepest in the mainland.
    mainland = site.fids[1120]
    best = None
    xm, ym = ref(C5_JUMP_INDEX * 10.0)
    for deg in range(360):
        jx, jy = xm + C5_JUMP_M * math.sin(math.radians(deg)), ym + C5_JUMP_M * math.cos(math.radians(deg))
        p = point(jx, jy)
        if any(p.Within(m) for m in mainland):
            depth = p.Distance(site.boundary)
            if best is None or depth > best[0]:
                best = (depth, deg, jx, jy)
    depth, jump_dir, jx, jy = best
    assert depth >= 1000.0, depth
    jump_ll = site.ll(jx, jy)
    vessel = Vessel(230990005, "JUMP AND NULL ISLAND")
    start = dt.datetime(2024, 5, 5, 12, 0, 0)
    tr = Track(site, vessel, start, 20240505)
    for i in range(C5_DURATION_S // 10 + 1):
        t = 10 * i
        x, y = ref(t)
        jit = tr.jitter()  # drawn for every fix, so the other fixes do not depend on the outliers
        if i == C5_JUMP_INDEX:
            tr.add(t, x, y, C5_SPEED_KN, float(C5_COURSE), C5_COURSE, 0, lonlat=jump_ll)
        elif i == C5_NULL_INDEX:
            tr.add(t, x, y, C5_SPEED_KN, float(C5_COURSE), C5_COURSE, 0, lonlat=(0.0, 0.0))
        else:
            tr.add(t, x, y, C5_SPEED_KN, float(C5_COURSE), C5_COURSE, 0, jitter=jit)
    good = [fx for i, fx in enumerate(tr.fixes) if i not in (C5_JUMP_INDEX, C5_NULL_INDEX)]
    least_written = min(site.clearance(site.hull(fx["x"], fx["y"], C5_COURSE)) for fx in good)
    assert least_written >= 500.0
    jf, nf = tr.fixes[C5_JUMP_INDEX], tr.fixes[C5_NULL_INDEX]
    jdist = math.hypot(jx - tr.fixes[C5_JUMP_INDEX - 1]["x"], jy - tr.fixes[C5_JUMP_INDEX - 1]["y"])
    geometry = dict(
        site="open water in Pohjanpitajanlahti, west of Helsinki, mainland all round",
        course_true_deg=C5_COURSE, speed_kn=C5_SPEED_KN,
        least_hull_clearance_m_unjittered=r2(least), least_hull_clearance_m_written_fixes=r2(least_written),
        jump=dict(line=jf["line"], time=jf["time"].strftime("%Y-%m-%dT%H:%M:%SZ"), lonlat=[jf["lon"], jf["lat"]],
                  from_nominal_position_m=C5_JUMP_M, direction_true_deg=jump_dir,
                  from_previous_fix_m=r2(jdist), depth_inside_mainland_m=r2(depth)),
        null_island=dict(line=nf["line"], time=nf["time"].strftime("%Y-%m-%dT%H:%M:%SZ"), lonlat=[0.0, 0.0]),
    )
    expect = dict(groundings=0, events=0, close_passes=0, margin_m=50.0,
                  outliers=dict(count=2, lines=sorted([jf["line"], nf["line"]])),
                  note="the hull stays more than 500 m from land; the jump into the mainland and the fix at 0,0 "
                       "are outliers to drop, never swept through")
    return tr, geometry, expect


# ---------------------------------------------------------------------------------------------
# Case 6: lying still, heading unknown


# Island GSHHG feature 1652 (0.60 km2), its south shore: an east-west segment of 462 m at
# 60.1753872 N, land to the north.
C6_FID = 1652
C6_SEG = ((25.2449683, 60.1753872), (25.2366369, 60.1753872))
C6_OFF = 30.0  # reference point south of the shore's middle


def case_still():
    mid_ll = ((C6_SEG[0][0] + C6_SEG[1][0]) / 2, C6_SEG[0][1])
    site = Site(*mid_ll)
    a, b = segment_by_vertices(site, C6_FID, *C6_SEG)
    mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    th = math.radians(site.grid_az(180.0, mx, my))
    x0, y0 = mx + C6_OFF * math.sin(th), my + C6_OFF * math.cos(th)
    d_ref = point(x0, y0).Distance(site.land)
    assert abs(d_ref - C6_OFF) < 0.01 and not point(x0, y0).Within(site.land)
    # Headings (true, whole degrees) at which the un-jittered hull overlaps land.
    over = [hd for hd in range(360) if site.touches(site.hull(x0, y0, hd))]
    runs = contact_intervals([hd in over for hd in range(360)], list(range(360)))
    if len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == 359:
        runs = [(runs[-1][0], runs[0][1])] + runs[1:-1]
    vessel = Vessel(230990006, "STILL NO HEADING")
    start = dt.datetime(2024, 5, 6, 3, 0, 0)
    tr = Track(site, vessel, start, 20240506)
    for i in range(21):
        tr.add(180 * i, x0, y0, 0.0, None, None, 15)
    at_north = [site.touches(site.hull(fx["x"], fx["y"], 0)) for fx in tr.fixes]
    geometry = dict(
        site=dict(coast_feature_id=C6_FID, shore_segment_lonlat=C6_SEG,
                  shore="south shore of an island east of Helsinki, east-west, land to the north"),
        reference_point_lonlat=[round(v, 7) for v in site.ll(x0, y0)],
        reference_point_to_land_m=r2(d_ref),
        headings_overlapping_land_true_deg=[list(r) for r in runs],
        headings_overlapping_land_count=len(over),
        clear_at_heading_90_and_270=not site.touches(site.hull(x0, y0, 90)) and not site.touches(site.hull(x0, y0, 270)),
        written_fixes_in_contact_if_heading_0=sum(at_north), written_fixes=len(tr.fixes),
    )
    expect = dict(groundings=0, heading_known=False, heading_source="none",
                  note="Heading 511, COG empty, SOG 0.0: the heading is unknown and must be reported as such; "
                       "at headings near north the hull would overlap land, at east or west it is clear")
    return tr, geometry, expect


# ---------------------------------------------------------------------------------------------
# Case 7: passing an island, clear


# An islet with no other land within 3 km (GSHHG feature 1713, 0.056 km2), south-east of Helsinki.
C7_FID = 1713
C7_COURSE = 75
C7_SPEED_KN = 12.0
C7_DURATION_S = 600
C7_CLEAR = 250.0  # least hull clearance of the un-jittered track


def case_passes():
    ds = ogr.Open(COAST)
    feature = ds.GetLayer().GetFeature(C7_FID)
    c = feature.GetGeometryRef().Centroid()
    site = Site(c.GetX(), c.GetY())
    isl = site.fids[C7_FID][0]
    v = C7_SPEED_KN * KN
    th = math.radians(site.grid_az(C7_COURSE, 0.0, 0.0))
    ux, uy = math.sin(th), math.cos(th)
    half = v * C7_DURATION_S / 2

    def least_for(off, step=5):
        def ref(t):
            s = v * t - half
            return ux * s + uy * off, uy * s - ux * off  # offset to starboard of the course line
        return min(site.clearance(site.hull(*ref(float(t)), C7_COURSE)) for t in range(0, C7_DURATION_S + 1, step)), ref

    lo, hi = 0.0, 2000.0  # the island passes to port: the track is offset to starboard
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        if least_for(mid, 10)[0] < C7_CLEAR:
            lo = mid
        else:
            hi = mid
    least, ref = least_for(hi, 1)
    assert C7_CLEAR - 1 <= least <= C7_CLEAR + 5, least
    vessel = Vessel(230990007, "PASSES CLEAR")
    start = dt.datetime(2024, 5, 7, 14, 0, 0)
    tr = Track(site, vessel, start, 20240507)
    for t in range(0, C7_DURATION_S + 1, 10):
        tr.add(t, *ref(t), C7_SPEED_KN, float(C7_COURSE), C7_COURSE, 0)
    cl = [site.clearance(site.hull(fx["x"], fx["y"], C7_COURSE)) for fx in tr.fixes]
    near = min(range(len(cl)), key=lambda i: cl[i])
    isl_d = min(site.hull(fx["x"], fx["y"], C7_COURSE).Distance(isl) for fx in tr.fixes)
    assert min(cl) >= 200.0 and abs(isl_d - min(cl)) < 1e-6, "the island is the nearest land"
    geometry = dict(
        site=dict(coast_feature_id=C7_FID, island="islet south-east of Helsinki, no other land within 3 km"),
        course_true_deg=C7_COURSE, speed_kn=C7_SPEED_KN,
        least_hull_clearance_m_unjittered=r2(least), least_hull_clearance_m_written_fixes=r2(min(cl)),
        nearest_fix_line=tr.fixes[near]["line"],
    )
    expect = dict(groundings=0, events=0, close_passes=0, margin_m=50.0)
    return tr, geometry, expect


# ---------------------------------------------------------------------------------------------
# Real-world cases (shoal check --world real, the default outside exercise mode): helpers


ARGS_DIMS = "--dims 100,20,8,8"
HULL_RADIUS = 100.0  # --dims 100,20,8,8: the bow tip is the hull point farthest from the reference point
# shoal's hull circle (heading unknown) is a 36-gon around the circle of that radius
CIRCLE_R = HULL_RADIUS / math.cos(math.pi / 36)


def circle(x, y, r=CIRCLE_R, n=36):
    return polygon([(x + r * math.cos(2 * math.pi * k / n), y + r * math.sin(2 * math.pi * k / n)) for k in range(n)])


def turn_deg(a, b):
    d = (b - a) % 360.0
    return d - 360.0 if d > 180.0 else d


def interp_fix(fa, fb, t):
    """Position and true heading on the written track between fixes fa and fb at time t: both
    linear in time (the heading along the shorter turn), as a sweep between fixes does."""
    f = (t - fa["t"]) / (fb["t"] - fa["t"])
    x = fa["x"] + f * (fb["x"] - fa["x"])
    y = fa["y"] + f * (fb["y"] - fa["y"])
    h = None
    if fa["heading"] is not None and fb["heading"] is not None:
        h = (fa["heading"] + f * turn_deg(fa["heading"], fb["heading"])) % 360.0
    return x, y, h


def written_hull(site, fa, fb, t, outline=OUTLINE):
    x, y, h = interp_fix(fa, fb, t)
    return site.hull(x, y, h, outline)


def contact_times(site, fa, fb, outline=OUTLINE, step=0.05, hull_of=None):
    """Times (every `step` s) strictly between fixes fa and fb at which the hull on the written
    track touches land."""
    out = []
    n = int(round((fb["t"] - fa["t"]) / step))
    for k in range(1, n):
        t = fa["t"] + k * step
        h = hull_of(t) if hull_of else written_hull(site, fa, fb, t, outline)
        if site.touches(h):
            out.append(round(t, 3))
    return out


def max_penetration(site, hulls):
    return max([site.penetration(h) for h in hulls] or [0.0])


def tstr(fx):
    return fx["time"].strftime("%Y-%m-%dT%H:%M:%SZ")

# ---------------------------------------------------------------------------------------------
# Case 8: aground, seen by sparse fixes (every 10 min), no heading and no COG


C8_CLEAR_FIXES = 4        # fixes under way, 600 s apart, at 10 kn
C8_BEFORE_SEEN_S = 180.0  # the bow touches this long before the first fix in contact
C8_STOP_S = 10.0          # it stops, decelerating evenly, this long after touching
C8_REST_S = 3 * 3600      # lies aground 3 h
C8_EVERY_S = 600


def case_aground_sparse(gap_s, mmsi, name, start, seed):
    """The voyage of case 1 (10 kn, course 003, onto the south shore of island 1740), seen every
    600 s; between the last clear fix and the first fix in contact gap_s seconds."""
    mid_ll = ((C1_SEG[0][0] + C1_SEG[1][0]) / 2, C1_SEG[0][1])
    site = Site(*mid_ll, half_km=15)
    a, b = segment_by_vertices(site, C1_FID, *C1_SEG)
    mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    th = math.radians(site.grid_az(C1_COURSE, mx, my))
    ux, uy = math.sin(th), math.cos(th)
    v = C1_SPEED_KN * KN
    t_last_clear = C8_EVERY_S * (C8_CLEAR_FIXES - 1)
    t_seen = t_last_clear + gap_s
    t_touch = t_seen - C8_BEFORE_SEEN_S
    decel = v / C8_STOP_S
    d0 = DIMS[0] + v * t_touch  # the bow tip reaches the segment's midpoint at t_touch
    sx, sy = mx - ux * d0, my - uy * d0

    def ref(t):
        if t <= t_touch:
            s = v * t
        else:
            dt_ = min(t - t_touch, C8_STOP_S)
            s = v * t_touch + v * dt_ - 0.5 * decel * dt_ * dt_
        return sx + ux * s, sy + uy * s

    T_tip = first_true(lambda t: site.touches(point(*site.hull_point(*ref(t), C1_COURSE, DIMS[0], 0.0))),
                       t_touch - 20, t_touch + 5, 0.5)
    assert abs(T_tip - t_touch) < 0.05, (T_tip, t_touch)
    T_outline = first_true(lambda t: site.touches(site.hull(*ref(t), C1_COURSE)), t_touch - 20, t_touch + 5, 0.5)
    vessel = Vessel(mmsi, name)
    tr = Track(site, vessel, start, seed)
    for i in range(C8_CLEAR_FIXES):
        t = C8_EVERY_S * i
        tr.add(t, *ref(t), C1_SPEED_KN, None, None, 0)
    t = t_seen
    while t <= t_seen + C8_REST_S:
        tr.add(t, *ref(t), 0.0, None, None, 0)
        t += C8_EVERY_S
    fx = tr.fixes
    last_clear, first_in = fx[C8_CLEAR_FIXES - 1], fx[C8_CLEAR_FIXES]
    # Under way: heading unknown too (511, COG empty); whatever heading, the hull lies in its
    # circle: the circle of every fix under way, and of every chord between them, is clear.
    way = fx[:C8_CLEAR_FIXES]
    way_dist = [point(f["x"], f["y"]).Distance(site.land) for f in way]
    assert min(way_dist) > CIRCLE_R + 200, way_dist
    for fa, fb in zip(way, way[1:]):
        assert not site.touches(linestring([(fa["x"], fa["y"]), (fb["x"], fb["y"])]).Buffer(CIRCLE_R))
    # At rest: every fix's circle overlaps land; so does the hull at the true heading (003).
    rest = fx[C8_CLEAR_FIXES:]
    rest_dist = [point(f["x"], f["y"]).Distance(site.land) for f in rest]
    assert max(rest_dist) < HULL_RADIUS - 10
    assert all(site.touches(site.hull(f["x"], f["y"], C1_COURSE)) for f in rest)
    # The sweep from the last clear fix to the first fix in contact, positions interpolated
    # linearly: when the circle (heading unknown at the later fix) and when the hull at the
    # bearing between them would first touch.
    def chord(t):
        f = (t - last_clear["t"]) / (first_in["t"] - last_clear["t"])
        return (last_clear["x"] + f * (first_in["x"] - last_clear["x"]),
                last_clear["y"] + f * (first_in["y"] - last_clear["y"]))

    bearing = site.true_az(math.degrees(math.atan2(first_in["x"] - last_clear["x"], first_in["y"] - last_clear["y"])),
                           last_clear["x"], last_clear["y"])
    t_circle = first_true(lambda t: site.touches(circle(*chord(t))), last_clear["t"], first_in["t"], 1.0)
    t_circle_exact = first_true(lambda t: point(*chord(t)).Distance(site.land) <= HULL_RADIUS, last_clear["t"],
                                first_in["t"], 1.0)
    t_hull = first_true(lambda t: site.touches(site.hull(*chord(t), bearing)), last_clear["t"], first_in["t"], 1.0)
    x_touch, y_touch = ref(t_touch)
    x_rest, y_rest = ref(t_touch + C8_STOP_S)
    chord_speed = math.hypot(first_in["x"] - last_clear["x"], first_in["y"] - last_clear["y"]) / gap_s / KN
    lead = first_in["t"] - t_circle
    geometry = dict(
        site=dict(coast_feature_id=C1_FID, shore_segment_lonlat=C1_SEG,
                  shore="south shore of an island east of Helsinki (case 1's), east-west, land to the north"),
        course_true_deg=C1_COURSE, speed_kn=C1_SPEED_KN, fixes_every_s=C8_EVERY_S,
        last_clear_fix_line=last_clear["line"], last_clear_fix_time=tstr(last_clear),
        first_fix_in_contact_line=first_in["line"], first_fix_in_contact_time=tstr(first_in),
        gap_s=gap_s,
        true_bow_contact_s=round(T_tip, 2), true_bow_contact=iso(start, T_tip),
        true_bow_contact_note="the bow tip touches %.0f s before the first fix in contact (un-jittered motion, bisected); "
                              "the pointed-bow outline at %.2f s; it stops %.0f s later, %.1f m further on"
                              % (C8_BEFORE_SEEN_S, T_outline, C8_STOP_S, 0.5 * v * C8_STOP_S),
        fixes_under_way_reference_point_to_land_m=[r2(d) for d in way_dist],
        fixes_at_rest_reference_point_to_land_m=[min(r2(d) for d in rest_dist), max(r2(d) for d in rest_dist)],
        hull_radius_m=HULL_RADIUS, shoal_circle_radius_m=round(CIRCLE_R, 2),
        at_rest_every_fix_in_contact="circle (heading unknown) and hull at heading 003 both overlap land at every fix at rest",
        penetration_at_rest_heading_003_m=r2(site.penetration(site.hull(x_rest, y_rest, C1_COURSE))),
        chord_speed_kn=round(chord_speed, 2),
        sweep_circle_first_contact_s=round(t_circle, 2), sweep_circle_first_contact=iso(start, t_circle),
        sweep_exact_circle_first_contact_s=round(t_circle_exact, 2),
        sweep_hull_at_bearing_first_contact_s=round(t_hull, 2), bearing_true_deg=round(bearing, 2),
        sweep_note="positions interpolated linearly from line %d to line %d: the hull's circle (shoal's 36-gon, radius "
                   "%.2f m) first touches land %.1f s before the first fix in contact; the hull at the bearing %.1f s before"
                   % (last_clear["line"], first_in["line"], CIRCLE_R, lead, first_in["t"] - t_hull),
        true_stop_from_true_contact_m=r2(math.hypot(x_rest - x_touch, y_rest - y_touch)),
        rest_from_sweep_contact_m=r2(math.hypot(first_in["x"] - chord(t_circle)[0], first_in["y"] - chord(t_circle)[1])),
    )
    return tr, geometry, site, last_clear, first_in, t_circle, start

# ---------------------------------------------------------------------------------------------
# Case 10: a ferry calling hourly at a pier the chart draws as land


# Island GSHHG feature 1572 (1.3 km2, south-east of Helsinki), its north shore: an east-west
# segment of 738 m at 60.10623 N, land to the south, open water north for 3 km.
C10_FID = 1572
C10_SEG = ((25.0449683, 60.1062486), (25.0582284, 60.1062181))
C10_SHORE_TRUE = 90.0   # the shore runs east-west (true bearing of the segment, west to east, rounded)
C10_ANGLE = 10          # the ferry's heading converges with the shore by this much (land to starboard)
C10_HEADING = 100       # true heading while berthing and at the berth
C10_CRUISE_KN = 12.0
C10_DECEL_KN_S = 0.04   # even deceleration from 12 kn to rest in 300 s
C10_STEADY_S = 60       # seconds at 12 kn before slowing
C10_CONTACT_KN = 4.5    # the hull first touches the charted land at this speed (aimed at)
C10_REST_S = 900        # lies 15 min
C10_CALLS = 6
C10_SIDE_MS = 0.6       # casting off: thrusters push it to port at this speed (ramp 10 s) for 60 s
C10_DEP_S = 360         # seconds of departure recorded
C10_DEP_TURN = 45.0     # degrees turned to port while leaving


def ferry_call_motion(site, rx, ry):
    """One call relative to its first fix (r = 0): (position, true heading, speed kn, status) at r,
    for the approach, the stay and the departure. (rx, ry): the reference point at rest."""
    a = C10_DECEL_KN_S * KN  # m/s^2
    t_dec = C10_CRUISE_KN / C10_DECEL_KN_S
    r_rest = C10_STEADY_S + t_dec
    gh = math.radians(site.grid_az(C10_HEADING, rx, ry))
    ux, uy = math.sin(gh), math.cos(gh)
    px, py = -math.cos(gh), math.sin(gh)  # port

    def to_go(r):  # distance still to run to the rest position
        if r >= r_rest:
            return 0.0
        if r >= C10_STEADY_S:
            return 0.5 * a * (r_rest - r) ** 2
        return 0.5 * a * t_dec ** 2 + C10_CRUISE_KN * KN * (C10_STEADY_S - r)

    def approach(r):
        s = to_go(r)
        v = 0.0 if r >= r_rest else (a * (r_rest - r) / KN if r >= C10_STEADY_S else C10_CRUISE_KN)
        return rx - ux * s, ry - uy * s, float(C10_HEADING), v

    return approach, r_rest, (ux, uy), (px, py)


def ferry_departure(site, rx, ry, step=0.05):
    """The departure from rest at (rx, ry), integrated: {t: (x, y, true heading, sog kn, cog true)}."""
    gh0 = site.grid_az(C10_HEADING, rx, ry)
    out = {}
    x, y = rx, ry
    n = int(round(C10_DEP_S / step))
    for k in range(n + 1):
        t = k * step
        w = C10_SIDE_MS * min(t / 10.0, 1.0) if t <= 60 else max(0.0, C10_SIDE_MS * (70 - t) / 10.0)
        u = 0.0 if t <= 70 else min((t - 70) * 0.05, C10_CRUISE_KN) * KN   # ahead from 70 s, +0.05 kn/s
        dh = -C10_DEP_TURN * min(max((t - 40) / 90.0, 0.0), 1.0)
        g = math.radians(gh0 + dh)
        vx = u * math.sin(g) - w * math.cos(g)
        vy = u * math.cos(g) + w * math.sin(g)
        if k % 20 == 0:
            sp = math.hypot(vx, vy)
            cog = site.true_az(math.degrees(math.atan2(vx, vy)), x, y) if sp > 0 else None
            out[round(t, 2)] = (x, y, site.true_az(gh0 + dh, x, y), sp / KN, cog)
        x += vx * step
        y += vy * step
    return out


def case_ferry():
    mid_ll = ((C10_SEG[0][0] + C10_SEG[1][0]) / 2, (C10_SEG[0][1] + C10_SEG[1][1]) / 2)
    site = Site(*mid_ll, half_km=6)
    a, b = segment_by_vertices(site, C10_FID, *C10_SEG)
    mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    # The rest position: the hull's middle over the segment's middle, the reference point at an
    # offset d north of the shore line, chosen (bisected) so that the hull first touches the
    # charted shore when the ferry is down to C10_CONTACT_KN.
    s_c_target = (C10_CONTACT_KN * KN) ** 2 / (2 * C10_DECEL_KN_S * KN)

    def rest_at(d):
        gh = math.radians(site.grid_az(C10_HEADING, mx, my))
        # the hull's middle (40 m ahead of the reference point) over the segment's middle
        return mx - 40 * math.sin(gh), my - 40 * math.cos(gh) + d

    def s_c(d):
        rx, ry = rest_at(d)
        approach, r_rest, _, _ = ferry_call_motion(site, rx, ry)
        first = first_true(lambda r: site.touches(site.hull(*approach(r)[:3])), 0.0, r_rest, 2.0)
        return None if first is None else 0.5 * C10_DECEL_KN_S * KN * (r_rest - first) ** 2

    lo, hi = -60.0, 60.0  # d=-60 touches early, d=60 never
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        sc = s_c(mid)
        if sc is not None and sc > s_c_target:
            lo = mid
        else:
            hi = mid
    d = hi
    rx, ry = rest_at(d)
    approach, r_rest, _, _ = ferry_call_motion(site, rx, ry)
    dep = ferry_departure(site, rx, ry)
    r_first = first_true(lambda r: site.touches(site.hull(*approach(r)[:3])), 0.0, r_rest, 2.0)
    v_first = approach(r_first)[3]
    pen_rest = site.penetration(site.hull(rx, ry, C10_HEADING))
    # The un-jittered approach is clear until r_first (every second), the departure clear after the
    # contact ends.
    assert all(not site.touches(site.hull(*approach(float(r))[:3])) for r in range(0, int(r_first)))
    dep_contact = [t for t in sorted(dep) if site.touches(site.hull(*dep[t][:3]))]
    t_free = max(dep_contact)
    dep_clear = min(site.clearance(site.hull(*dep[t][:3])) for t in sorted(dep) if t >= 70)
    assert dep_clear > 10.0, dep_clear

    vessel = Vessel(230990010, "FERRY HOURLY", vtype=60, draft=5.5, cargo=60)
    start = dt.datetime(2024, 5, 10, 6, 0, 0)

    def write(seed):
        tr = Track(site, vessel, start, seed)
        calls = []
        for c in range(C10_CALLS):
            t0 = 3600 * c
            first_line = len(tr.fixes) + 2
            r = 0
            while r < r_rest:
                x, y, h, v = approach(r)
                tr.add(t0 + r, x, y, round(v, 1), float(C10_HEADING), C10_HEADING, 0)
                r += 10
            r = r_rest
            while r <= r_rest + C10_REST_S:
                tr.add(t0 + r, rx, ry, 0.0, None, C10_HEADING, 5)
                r += 60
            r_dep0 = r_rest + C10_REST_S
            for k in range(1, C10_DEP_S // 10 + 1):
                x, y, h, v, cog = dep[float(10 * k)]
                tr.add(t0 + r_dep0 + 10 * k, x, y, round(v, 1), None if cog is None else round(cog, 1),
                       int(round(h)) % 360, 0)
            calls.append((first_line, len(tr.fixes) + 1, t0, t0 + r_dep0 + C10_DEP_S))
        return tr, calls

    def contiguous(tr, calls):
        fx = tr.fixes
        for first_line, last_line, t0, t1 in calls:
            flags = [site.touches(site.hull(fx[i]["x"], fx[i]["y"], fx[i]["heading"]))
                     for i in range(first_line - 2, last_line - 1)]
            ins = [j for j, f in enumerate(flags) if f]
            if not ins or not all(flags[ins[0]:ins[-1] + 1]):
                return False
        return True

    # Jitter may make a fix just after the first touch look clear (the overlap grows 1-3 m in 10 s):
    # the seed is the first from 20240510 whose every call is in contact from its first fix in
    # contact to its last (one contact per call, as the ferry's real motion has).
    seed = 20240510
    tr, calls = write(seed)
    tried = [seed]
    while not contiguous(tr, calls):
        seed += 1
        tried.append(seed)
        tr, calls = write(seed)
    per_call = []
    fx = tr.fixes
    for first_line, last_line, t0, t1 in calls:
        idx = list(range(first_line - 2, last_line - 1))
        flags = [site.touches(site.hull(fx[i]["x"], fx[i]["y"], fx[i]["heading"])) for i in idx]
        k = flags.index(True)
        last_in = max(j for j, f in enumerate(flags) if f)
        fa, fb = fx[idx[k - 1]], fx[idx[k]]
        times = contact_times(site, fa, fb, step=0.1)
        t_c = times[0] if times else fb["t"]
        rest_i = next(i for i in idx if fx[i]["status"] == 5)
        pens = [site.penetration(site.hull(fx[i]["x"], fx[i]["y"], C10_HEADING)) for i in idx if fx[i]["status"] == 5]
        per_call.append(dict(
            lines=[first_line, last_line], first_fix=tstr(fx[idx[0]]), last_fix=tstr(fx[idx[-1]]),
            last_fix_clear_line=fa["line"], last_fix_clear_sog_kn=fa["sog"],
            first_fix_in_contact_line=fb["line"], first_fix_in_contact_sog_kn=fb["sog"],
            contact_written_track=iso(start, t_c),
            rest_first_fix=tstr(fx[rest_i]), rest_first_fix_line=fx[rest_i]["line"],
            last_fix_in_contact_line=fx[idx[last_in]]["line"],
            penetration_at_rest_m=[r2(min(pens)), r2(max(pens))]))
    geometry = dict(
        site=dict(coast_feature_id=C10_FID, shore_segment_lonlat=C10_SEG,
                  shore="north shore of an island south-east of Helsinki, east-west, land to the south, open water north"),
        story="a pier (or linkspan) this chart does not draw: the charted shore lies some 20 m seaward of it",
        heading_true_deg=C10_HEADING, converging_with_shore_deg=C10_ANGLE,
        approach="12 kn for 60 s, then an even deceleration of 0.04 kn/s to rest in 300 s (926 m); fixes every 10 s "
                 "under way, every 60 s at rest; Status 0 under way, 5 at rest",
        rest_reference_point_lonlat=[round(v, 7) for v in site.ll(rx, ry)],
        rest_reference_point_to_shore_line_m=r2(point(rx, ry).Distance(site.boundary)),
        first_contact_s_after_call_start=round(r_first, 2), first_contact_speed_kn=round(v_first, 2),
        first_contact_to_rest_s=round(r_rest - r_first, 2),
        first_contact_to_rest_m=round(0.5 * C10_DECEL_KN_S * KN * (r_rest - r_first) ** 2, 1),
        deceleration_kn_s=C10_DECEL_KN_S,
        penetration_at_rest_m_unjittered=r2(pen_rest),
        departure="thrusters push it 36 m to port in 60 s (easing off by 70 s), turning it 45 degrees to port from 40 s to "
                  "130 s; ahead from 70 s (+0.05 kn/s to 12 kn); recorded 360 s",
        departure_contact_ends_s=round(t_free, 2), departure_least_clearance_from_70s_m=r2(dep_clear),
        calls=per_call, seeds_tried=tried,
        note="the recording covers only a box around the pier: between calls the ferry is away "
             "(gaps of 33 min, longer than --max-gap)",
    )
    return tr, geometry

# ---------------------------------------------------------------------------------------------
# Case 11: a transit straight through a narrow piece of charted land


# A narrow peninsula (about 190 m wide, running north-south) at the south end of an island west
# of central Helsinki (GSHHG feature 1524, 4.47 km2): open water on both sides for more than
# 3 km along course 075.
C11_FID = 1524
C11_THROUGH = (24.8910, 60.1408)  # a point on the peninsula the course line passes through
C11_COURSE = 75
C11_SPEED_KN = 8.0
C11_DURATION_S = 1500             # 25 min, the crossing in the middle
C11_DIMS_LENGTH = DIMS[0] + DIMS[1]


def case_canal():
    site = Site(*C11_THROUGH, half_km=8)
    v = C11_SPEED_KN * KN
    th = math.radians(site.grid_az(C11_COURSE, 0.0, 0.0))
    ux, uy = math.sin(th), math.cos(th)
    half = v * C11_DURATION_S / 2

    def ref(t):
        s = v * t - half + DIMS[0] / 2 - DIMS[1] / 2  # the hull's middle passes the point at mid-time
        return ux * s, uy * s

    line = linestring([ref(0.0), ref(float(C11_DURATION_S))])
    core = line.Intersection(site.land)
    assert core.GetGeometryType() == ogr.wkbLineString, "the course line crosses land once"
    assert any(core.Intersects(p) for p in site.fids[C11_FID]), "the land crossed is feature C11_FID"
    width = core.Length()
    # Nothing else within 60 m of the course line (the hull's half beam and the 50 m margin).
    wide = linestring([ref(-20.0), ref(C11_DURATION_S + 20.0)]).Buffer(60.0).Intersection(site.land)
    assert wide.GetGeometryType() == ogr.wkbPolygon, "one piece of land near the course line"
    t_in = first_true(lambda t: site.touches(site.hull(*ref(t), C11_COURSE)), 0.0, C11_DURATION_S, 1.0)
    t_out = first_true(lambda t: not site.touches(site.hull(*ref(t), C11_COURSE)), t_in + 1.0, C11_DURATION_S, 1.0)
    pens = [(site.penetration(site.hull(*ref(float(t)), C11_COURSE)), t) for t in range(int(t_in), int(t_out) + 1)]
    pen_max, t_pen = max(pens)
    vessel = Vessel(230990011, "CANAL TRANSIT")
    start = dt.datetime(2024, 5, 11, 13, 0, 0)
    tr = Track(site, vessel, start, 20240511)
    for t in range(0, C11_DURATION_S + 1, 10):
        tr.add(t, *ref(t), C11_SPEED_KN, float(C11_COURSE), C11_COURSE, 0)
    reps = [fix_report(site, fx) for fx in tr.fixes]
    in_lines = [r["line"] for r in reps if r["contact"]]
    assert in_lines == list(range(in_lines[0], in_lines[-1] + 1)), "one run of fixes in contact"
    fa = tr.fixes[in_lines[0] - 3]
    fb = tr.fixes[in_lines[0] - 2]
    t_written = contact_times(site, fa, fb, step=0.05)[0]
    fc, fd = tr.fixes[in_lines[-1] - 2], tr.fixes[in_lines[-1] - 1]
    t_written_end = [t for t in contact_times(site, fc, fd, step=0.05)][-1]
    pen_written = max(r["penetration_m"] for r in reps)
    clear = [r["clearance_m"] for r in reps if not r["contact"]]
    geometry = dict(
        site=dict(coast_feature_id=C11_FID, point_lonlat=C11_THROUGH,
                  land="a narrow north-south peninsula at the south end of an island west of central Helsinki, open "
                       "water on both sides along the course for more than 3 km"),
        course_true_deg=C11_COURSE, speed_kn=C11_SPEED_KN, duration_s=C11_DURATION_S,
        land_crossed_along_course_m=r2(width),
        first_contact_s=round(t_in, 2), first_contact=iso(start, t_in),
        last_contact_s=round(t_out, 2), last_contact=iso(start, t_out),
        contact_duration_s=round(t_out - t_in, 1),
        max_penetration_m_unjittered=r2(pen_max), max_penetration_at=iso(start, t_pen),
        max_penetration_m_written_fixes=r2(pen_written),
        hull_length_plus_50_m=C11_DIMS_LENGTH + 50.0,
        first_contact_written_track=iso(start, t_written), last_contact_written_track=iso(start, t_written_end),
        fixes_in_contact_lines=[in_lines[0], in_lines[-1]],
        least_clearance_of_other_fixes_m=min(clear),
        nothing_else_within_60_m_of_the_course_line=True,
    )
    return tr, geometry

# ---------------------------------------------------------------------------------------------
# Case 12: touch and go: the bow clips a corner of land between two fixes


# An islet's sharp south-west corner (GSHHG feature 1347, 0.023 km2, Espoo archipelago; an
# interior angle of 44 degrees between edges of 264 m and 183 m).
C12_FID = 1347
C12_CORNER = (24.7432822, 60.0928817)
C12_FIX_K = 18            # the last fix before the clip (fixes every 10 s from 0)
C12_T_K = 10.0 * C12_FIX_K
C12_STRIKE = C12_T_K + 6  # the strike: 10 kn falls to 4 kn in 3 s
C12_TURN_FROM = C12_T_K - 15
C12_TURN_TO = C12_T_K + 25
C12_RATE = 2.0            # degrees per second to port (hard over), ...
C12_RATE_HIT = 4.0        # ... 4 in the 4 s after the strike (the blow on the starboard bow)
C12_DURATION_S = 600
C12_AT_STRIKE = (80.0, -4.0, 20.0)  # the corner in the ship frame at the strike (x, y); heading = bisector + 90 + this


def tg_speed(t):
    if t < C12_STRIKE:
        return 10.0
    if t < C12_STRIKE + 3:
        return 10.0 - 6.0 * (t - C12_STRIKE) / 3
    if t < C12_T_K + 20:
        return 4.0
    if t < C12_T_K + 80:
        return 4.0 + 3.0 * (t - C12_T_K - 20) / 60
    return 7.0


def tg_rate(t):
    if t < C12_TURN_FROM or t >= C12_TURN_TO:
        return 0.0
    if C12_STRIKE <= t < C12_STRIKE + 4:
        return C12_RATE_HIT
    return C12_RATE


def corner_and_bisector(site, fid, lonlat):
    ds = ogr.Open(COAST)
    feature = ds.GetLayer().GetFeature(fid)
    ring = feature.GetGeometryRef().GetGeometryRef(0)
    pts = [ring.GetPoint_2D(i) for i in range(ring.GetPointCount() - 1)]
    i = [k for k, p in enumerate(pts) if abs(p[0] - lonlat[0]) < 1e-9 and abs(p[1] - lonlat[1]) < 1e-9]
    assert len(i) == 1, "the corner is a vertex of the feature"
    i = i[0]
    a, v, b = [site.xy(*p) for p in (pts[i - 1], pts[i], pts[(i + 1) % len(pts)])]
    e1, e2 = (a[0] - v[0], a[1] - v[1]), (b[0] - v[0], b[1] - v[1])
    l1, l2 = math.hypot(*e1), math.hypot(*e2)
    angle = math.degrees(math.acos((e1[0] * e2[0] + e1[1] * e2[1]) / l1 / l2))
    bx, by = -(e1[0] / l1 + e2[0] / l2), -(e1[1] / l1 + e2[1] / l2)
    return v, math.degrees(math.atan2(bx, by)), angle, (l1, l2)


def case_touch_and_go():
    site = Site(*C12_CORNER, half_km=5)
    V, beta, angle, edges = corner_and_bisector(site, C12_FID, C12_CORNER)
    # The motion in a frame where the first course is grid north, integrated every 0.01 s.
    step = 0.01
    path = {}
    x = y = h = 0.0
    for k in range(int(round(C12_DURATION_S / step)) + 1):
        t = k * step
        if k % 5 == 0:
            path[round(t, 2)] = (x, y, h)
        v = tg_speed(t) * KN
        x += v * math.sin(math.radians(h)) * step
        y += v * math.cos(math.radians(h)) * step
        h -= tg_rate(t) * step
    # Placed so that at the strike the corner lies at C12_AT_STRIKE's (x, y) in the ship frame,
    # the heading then being the corner's outward bisector + 90 + C12_AT_STRIKE[2] degrees (grid).
    xv, yv, delta = C12_AT_STRIKE
    gp = path[round(C12_STRIKE, 2)]
    hs = beta + 90.0 + delta
    h0 = hs - gp[2]
    f = (math.sin(math.radians(hs)), math.cos(math.radians(hs)))
    s = (math.cos(math.radians(hs)), -math.sin(math.radians(hs)))
    rx, ry = V[0] - xv * f[0] - yv * s[0], V[1] - xv * f[1] - yv * s[1]
    c, si = math.cos(math.radians(h0)), math.sin(math.radians(h0))
    ox, oy = rx - (gp[0] * c + gp[1] * si), ry - (-gp[0] * si + gp[1] * c)
    world = {t: (ox + p[0] * c + p[1] * si, oy - p[0] * si + p[1] * c, h0 + p[2]) for t, p in path.items()}

    def true_pose(t):
        x_, y_, gh = world[round(t, 2)]
        return x_, y_, site.true_az(gh, x_, y_)

    # The real motion touches land only between fix k and fix k + 1.
    phys = [t / 20.0 for t in range(0, 20 * C12_DURATION_S + 1) if site.touches(site.hull(*true_pose(t / 20.0)))]
    assert phys and C12_T_K < phys[0] and phys[-1] < C12_T_K + 10, (phys[:1], phys[-1:])
    pen_phys = max(site.penetration(site.hull(*true_pose(t))) for t in phys)
    vessel = Vessel(230990012, "TOUCH AND GO")
    start = dt.datetime(2024, 5, 12, 15, 0, 0)

    def write(seed):
        tr = Track(site, vessel, start, seed)
        for i in range(C12_DURATION_S // 10 + 1):
            t = 10.0 * i
            x_, y_, th_ = true_pose(t)
            tr.add(int(t), x_, y_, round(tg_speed(t), 1), round(th_, 1) % 360.0, int(round(th_)) % 360, 0)
        return tr

    def written_facts(tr):
        fx = tr.fixes
        clear = [site.clearance(site.hull(f["x"], f["y"], f["heading"])) for f in fx]
        times = {}
        for i in range(len(fx) - 1):
            ts = contact_times(site, fx[i], fx[i + 1], step=0.05)
            if ts:
                times[i] = ts
        return clear, times

    # Jitter (3 m) is as large as the clip: the seed is the first from 20240612 whose written track
    # (positions and heading linear between fixes) touches land between fix k and k + 1 only, at
    # least 3 m deep, with every fix's hull at least 3 m clear.
    seed = 20240612
    tried = []
    while True:
        tried.append(seed)
        tr = write(seed)
        clear, times = written_facts(tr)
        if list(times) == [C12_FIX_K] and min(clear) >= 3.0:
            fa, fb = tr.fixes[C12_FIX_K], tr.fixes[C12_FIX_K + 1]
            pen_w = max(site.penetration(written_hull(site, fa, fb, t)) for t in times[C12_FIX_K])
            if pen_w >= 3.0:
                break
        seed += 1
    ts = times[C12_FIX_K]
    geometry = dict(
        site=dict(coast_feature_id=C12_FID, corner_lonlat=C12_CORNER, corner_interior_angle_deg=round(angle, 1),
                  corner_edges_m=[round(e, 1) for e in edges],
                  land="a sharp corner of an islet in the Espoo archipelago; nothing else within 1 km of the track"),
        motion="10 kn straight, turning to port at 2 deg/s from %s (hard over); at the strike (%s, 6 s after line %d) the "
               "speed falls to 4 kn in 3 s and the blow on the starboard bow swings it at 4 deg/s for 4 s; turning ends at "
               "%s (88 degrees in all); 4 kn, then up to 7 kn in 60 s and on, clear"
               % (iso(start, C12_TURN_FROM), iso(start, C12_STRIKE), C12_FIX_K + 2, iso(start, C12_TURN_TO)),
        last_fix_before_line=fa["line"], last_fix_before=tstr(fa), last_fix_before_sog_kn=fa["sog"],
        last_fix_before_heading=fa["heading"],
        first_fix_after_line=fb["line"], first_fix_after=tstr(fb), first_fix_after_sog_kn=fb["sog"],
        first_fix_after_heading=fb["heading"],
        speed_drop_kn_per_s=round((fa["sog"] - fb["sog"]) / 10.0, 2),
        real_contact=[iso(start, phys[0]), iso(start, phys[-1])], real_contact_s=round(phys[-1] - phys[0], 2),
        real_penetration_m=r2(pen_phys),
        written_track_contact=[iso(start, ts[0]), iso(start, ts[-1])], written_track_contact_s=round(ts[-1] - ts[0], 2),
        written_track_penetration_m=r2(pen_w),
        written_fix_clearance_m=dict(before=r2(clear[C12_FIX_K]), after=r2(clear[C12_FIX_K + 1]), least=r2(min(clear)),
                                     least_before_line=min(range(C12_FIX_K), key=lambda i: clear[i]) + 2,
                                     least_before=r2(min(clear[:C12_FIX_K]))),
        close_pass_note="the approach passes within the 50 m margin of the islet before the clip: a close pass may be "
                        "reported besides the contact",
        written_track_note="positions and heading linear between fixes; no other contact on the written track",
        seeds_tried=tried,
    )
    return tr, geometry, start, ts

# ---------------------------------------------------------------------------------------------
# Case 13: a pilot boat berthing


# Island GSHHG feature 1493 (0.89 km2, south of Helsinki), its west shore: a north-south
# segment of 743 m at 24.9958 E, land to the east, open water west for 4 km.
C13_FID = 1493
C13_SEG = ((24.9958038, 60.1299763), (24.9957427, 60.1366445))
C13_LENGTH, C13_WIDTH = 20, 6
C13_DIMS = (C13_LENGTH / 2, C13_LENGTH / 2, C13_WIDTH / 2, C13_WIDTH / 2)  # shoal --hull-from-length-width
C13_OUTLINE = shoal_outline(C13_DIMS)
C13_HEADING = 20          # converging 20 degrees with the shore, starboard side to it
C13_CONTACT_KN = 0.6      # the hull first touches the charted shore at this speed (aimed at)
C13_REST_S = 3600


def pilot_speed(r):
    """Speed (kn) r seconds after the first fix: 15 kn for 60 s, down to 3 kn in 60 s, 3 kn for 30 s,
    then evenly to rest in 120 s."""
    if r < 60:
        return 15.0
    if r < 120:
        return 15.0 - 12.0 * (r - 60) / 60
    if r < 150:
        return 3.0
    if r < 270:
        return 3.0 * (270 - r) / 120
    return 0.0


def pilot_to_go(r, dt_=0.01):
    """Distance (m) still to run at r."""
    n = int(round((270 - r) / dt_)) if r < 270 else 0
    return sum(pilot_speed(r + (k + 0.5) * dt_) for k in range(n)) * KN * dt_


def case_pilot():
    mid_ll = ((C13_SEG[0][0] + C13_SEG[1][0]) / 2, (C13_SEG[0][1] + C13_SEG[1][1]) / 2)
    site = Site(*mid_ll, half_km=6)
    a, b = segment_by_vertices(site, C13_FID, *C13_SEG)
    mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
    assert point(mx + 5, my).Within(site.land) and not point(mx - 5, my).Within(site.land)
    gh = math.radians(site.grid_az(C13_HEADING, mx, my))
    ux, uy = math.sin(gh), math.cos(gh)
    to_go = {r: pilot_to_go(float(r)) for r in range(0, 271, 10)}
    # distance to go at the aimed contact speed (in the even deceleration from 3 kn)
    r_c = 270 - C13_CONTACT_KN / 3.0 * 120
    s_c_target = pilot_to_go(r_c)

    def hull_at(rx, ry, s):
        return site.hull(rx - ux * s, ry - uy * s, C13_HEADING, C13_OUTLINE)

    def first_contact_to_go(d):
        rx, ry = mx - d, my
        lo, hi = 0.0, 300.0
        if not site.touches(hull_at(rx, ry, 0.0)):
            return None
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if site.touches(hull_at(rx, ry, mid)):
                lo = mid
            else:
                hi = mid
        return lo

    lo, hi = 0.0, 20.0  # reference point this far west of the shore at rest
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        s = first_contact_to_go(mid)
        if s is not None and s > s_c_target:
            lo = mid
        else:
            hi = mid
    rx, ry = mx - hi, my
    s_c = first_contact_to_go(hi)
    assert abs(s_c - s_c_target) < 0.05, (s_c, s_c_target)
    t_c = bisect(lambda r: site.touches(hull_at(rx, ry, pilot_to_go(r))), 150.0, 270.0, 0.01)
    # nothing touched before that: the approach's hull every second
    assert not any(site.touches(hull_at(rx, ry, pilot_to_go(float(r)))) for r in range(0, int(t_c)))
    pen_rest = site.penetration(site.hull(rx, ry, C13_HEADING, C13_OUTLINE))
    vessel = Vessel(230990013, "PILOT BERTHING", vtype=50, length=C13_LENGTH, width=C13_WIDTH, draft=2.0, cargo=50)
    start = dt.datetime(2024, 5, 13, 4, 0, 0)
    def write(seed):
        tr = Track(site, vessel, start, seed)
        for r in range(0, 270, 10):
            s = to_go[r]
            tr.add(r, rx - ux * s, ry - uy * s, round(pilot_speed(r), 1), float(C13_HEADING), C13_HEADING, 0)
        for r in range(270, 270 + C13_REST_S + 1, 10):
            tr.add(r, rx, ry, 0.0, None, C13_HEADING, 5 if r >= 300 else 0)
        return tr

    # Jitter (3 m) can put a fix of the last slow metres onto the shore early: the seed is the first
    # from 20240713 whose written track first touches land after the SOG is under 1 kn (the fix
    # before the contact under 1 kn), as the boat's real motion does.
    seed = 20240713
    tried = []
    while True:
        tried.append(seed)
        tr = write(seed)
        fx = tr.fixes
        k = next(i for i in range(1, len(fx)) if site.touches(site.hull(fx[i]["x"], fx[i]["y"], C13_HEADING, C13_OUTLINE))
                 or contact_times(site, fx[i - 1], fx[i], C13_OUTLINE, step=0.5))
        if fx[k - 1]["sog"] < 1.0:
            break
        seed += 1
    times = contact_times(site, fx[k - 1], fx[k], C13_OUTLINE, step=0.05)
    t_written = times[0] if times else fx[k]["t"]
    reps = [dict(fix_report(site, fx, C13_OUTLINE), sog=fx["sog"]) for fx in tr.fixes]
    first_in = next(i for i, r in enumerate(reps) if r["contact"])
    at_rest = reps[27:]
    geometry = dict(
        site=dict(coast_feature_id=C13_FID, shore_segment_lonlat=C13_SEG,
                  shore="west shore of an island south of Helsinki, north-south, land to the east, open water west"),
        hull="Length 20, Width 6 (AIS columns); shoal --hull-from-length-width: A=B=10, C=D=3 (reference point amidships)",
        heading_true_deg=C13_HEADING, converging_with_shore_deg=20,
        speeds="15 kn for 60 s, to 3 kn in 60 s, 3 kn for 30 s, then evenly to rest in 120 s (0.025 kn/s); fixes every "
               "10 s; at rest from %s, Status 5 from 30 s later, 1 h" % iso(start, 270),
        rest_reference_point_lonlat=[round(v, 7) for v in site.ll(rx, ry)],
        rest_reference_point_to_shore_m=r2(point(rx, ry).Distance(site.boundary)),
        first_contact_s=round(t_c, 2), first_contact=iso(start, t_c), first_contact_speed_kn=round(pilot_speed(t_c), 2),
        first_contact_to_rest_m=round(s_c, 2),
        penetration_at_rest_m_unjittered=r2(pen_rest),
        first_written_fix_in_contact_line=reps[first_in]["line"], first_written_fix_in_contact_sog_kn=reps[first_in]["sog"],
        fix_before_it_sog_kn=reps[first_in - 1]["sog"],
        first_contact_written_track=iso(start, t_written), fix_before_written_contact_sog_kn=fx[k - 1]["sog"],
        seeds_tried=tried,
        at_rest_fixes=len(at_rest), at_rest_fixes_in_contact=sum(1 for r in at_rest if r["contact"]),
        at_rest_penetration_m_max=max(r["penetration_m"] for r in at_rest),
        at_rest_note="jitter (3 m) is half the boat's beam: at rest the hull touches and clears the shore from fix to fix",
    )
    return tr, geometry

# ---------------------------------------------------------------------------------------------
# Case 14: sparse fixes whose straight line cuts a skerry's corner


# An islet 3.6 km from any other land (GSHHG feature 1280, 0.047 km2, south of Espoo): an
# octagon; its north-east corner is the 105 m edge from (24.7407797, 60.0108034) to
# (24.7399405, 60.0112459).
C14_FID = 1280
C14_CORNER_EDGE = ((24.7407797, 60.0108034), (24.7399405, 60.0112459))
C14_SPEED_KN = 12.0
C14_EVERY_S = 180
C14_TURN = 60.0          # degrees to port between the two fixes around the islet (an arc)
C14_LEG_FIXES = 3        # fixes on each straight leg besides the two around the islet
C14_PEN = 25.0           # the straight line's hull sweep reaches this far into the islet (aimed at)


def case_skerry():
    ds = ogr.Open(COAST)
    feature = ds.GetLayer().GetFeature(C14_FID)
    c = feature.GetGeometryRef().Centroid()
    site = Site(c.GetX(), c.GetY(), half_km=5)
    isl = site.fids[C14_FID][0]
    others = [p for fid, ps in site.fids.items() if fid != C14_FID for p in ps]
    nearest_other = min([isl.Distance(p) for p in others] or [1e9])
    assert nearest_other > 3000, nearest_other
    (p0, p1) = [site.xy(*ll) for ll in C14_CORNER_EDGE]
    qx, qy = (p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2
    ex, ey = p1[0] - p0[0], p1[1] - p0[1]
    el = math.hypot(ex, ey)
    mx_, my_ = ey / el, -ex / el           # normal of the edge
    if point(qx + 5 * mx_, qy + 5 * my_).Within(site.land):
        mx_, my_ = -mx_, -my_              # pointing out of the islet
    m_az = math.degrees(math.atan2(mx_, my_))
    v = C14_SPEED_KN * KN
    arc = v * C14_EVERY_S
    R = arc / math.radians(C14_TURN)
    half = math.radians(C14_TURN / 2)
    # grid headings: at the arc's middle the outward normal is to starboard (a turn to port)
    h_mid = m_az - 90.0
    h_in, h_out = h_mid + C14_TURN / 2, h_mid - C14_TURN / 2

    def layout(e):
        """The path when the chord between the two fixes around the islet lies e metres out from
        the corner edge's middle: {t: (x, y, grid heading)} at the fixes, and the arc as a function."""
        cx, cy = qx + mx_ * (e - R * math.cos(half)), qy + my_ * (e - R * math.cos(half))  # turn centre

        def on_arc(phi):  # phi: angle from the arc's middle, + towards the start
            a = math.radians(m_az) + phi
            return cx + R * math.sin(a), cy + R * math.cos(a), h_mid + math.degrees(phi)

        # phi = +half at the first fix (A), -half at the second (B); the turn goes from A to B
        ax, ay, _ = on_arc(half)
        bx, by, _ = on_arc(-half)
        fixes = []
        ti, to_ = math.radians(h_in), math.radians(h_out)
        for k in range(C14_LEG_FIXES, 0, -1):
            fixes.append((ax - math.sin(ti) * arc * k, ay - math.cos(ti) * arc * k, h_in))
        fixes.append((ax, ay, h_in))
        fixes.append((bx, by, h_out))
        for k in range(1, C14_LEG_FIXES + 1):
            fixes.append((bx + math.sin(to_) * arc * k, by + math.cos(to_) * arc * k, h_out))
        return fixes, on_arc

    def chord_hulls(fixes, steps=360):
        (ax, ay, ha), (bx, by, hb) = fixes[C14_LEG_FIXES], fixes[C14_LEG_FIXES + 1]
        out = []
        for k in range(1, steps):
            f = k / steps
            x, y = ax + f * (bx - ax), ay + f * (by - ay)
            gh = ha + f * turn_deg(ha, hb)
            out.append(site.hull(x, y, site.true_az(gh, x, y)))
        return out

    lo, hi = -200.0, 200.0
    for _ in range(16):
        e = 0.5 * (lo + hi)
        fixes, _ = layout(e)
        if max_penetration(site, chord_hulls(fixes, 45)) > C14_PEN:
            lo = e
        else:
            hi = e
    fixes, on_arc = layout(hi)
    pen_chord = max_penetration(site, chord_hulls(fixes))
    arc_poses = [on_arc(half - 2 * half * k / 360) for k in range(361)]
    arc_clear = min(site.clearance(site.hull(x, y, site.true_az(gh, x, y))) for x, y, gh in arc_poses)
    vessel = Vessel(230990014, "SKERRY SPARSE")
    start = dt.datetime(2024, 5, 14, 16, 0, 0)
    tr = Track(site, vessel, start, 20240514)
    for i, (x, y, gh) in enumerate(fixes):
        th_ = site.true_az(gh, x, y)
        tr.add(C14_EVERY_S * i, x, y, C14_SPEED_KN, round(th_, 1) % 360.0, int(round(th_)) % 360, 0)
    fx = tr.fixes
    clear = [site.clearance(site.hull(f["x"], f["y"], f["heading"])) for f in fx]
    assert min(clear) > 100.0, clear
    fa, fb = fx[C14_LEG_FIXES], fx[C14_LEG_FIXES + 1]
    ts = contact_times(site, fa, fb, step=0.25)
    pen_w = max(site.penetration(written_hull(site, fa, fb, t)) for t in ts)
    for i in range(len(fx) - 1):
        if i != C14_LEG_FIXES:
            assert not contact_times(site, fx[i], fx[i + 1], step=1.0), i
    ref_in = [t for t in ts if point(*interp_fix(fa, fb, t)[:2]).Within(site.land)]
    geometry = dict(
        site=dict(coast_feature_id=C14_FID, corner_edge_lonlat=C14_CORNER_EDGE,
                  land="an octagonal islet (185 m x 285 m) south of Espoo, %.1f km from any other land" % (nearest_other / 1000)),
        speed_kn=C14_SPEED_KN, fixes_every_s=C14_EVERY_S,
        real_path="straight, then an arc of %.0f m radius turning %.0f degrees to port around the islet between line %d "
                  "and line %d, then straight; heading = course" % (R, C14_TURN, fa["line"], fb["line"]),
        real_path_least_hull_clearance_m=r2(arc_clear),
        headings_true_deg=[f["heading"] for f in fx],
        fixes_hull_clearance_m=[r2(c) for c in clear],
        around_the_islet_lines=[fa["line"], fb["line"]], around_the_islet_times=[tstr(fa), tstr(fb)],
        straight_line_contact=[iso(start, ts[0]), iso(start, ts[-1])],
        straight_line_contact_note="positions and heading linear between line %d and line %d (the written, jittered fixes): "
                                   "the hull cuts the islet's north-east corner" % (fa["line"], fb["line"]),
        straight_line_penetration_m=r2(pen_w), straight_line_penetration_m_unjittered=r2(pen_chord),
        reference_point_on_land_along_straight_line=bool(ref_in),
        other_fix_to_fix_lines_clear=True,
    )
    return tr, geometry, start, ts

# ---------------------------------------------------------------------------------------------
# Real-world cases: what a correct audit reports


def case_sparse_600():
    tr, geometry, site, last_clear, first_in, t_circle, start = case_aground_sparse(
        600, 230990008, "AGROUND SPARSE", dt.datetime(2024, 5, 8, 9, 0, 0), 20240508)
    lead = math.ceil(first_in["t"] - t_circle) + 1.0
    expect = dict(
        exit_status=1, groundings=1, events=1, grade=3,
        start_earliest=iso(start, first_in["t"] - lead), start_latest=tstr(first_in),
        start_window_note="the contact lies between line %d (clear) and line %d (in contact); swept with positions "
                          "interpolated between them it begins %.1f s before line %d (geometry.sweep_note): start is that "
                          "or the first fix in contact, no earlier than %.0f s before it"
                          % (last_clear["line"], first_in["line"], first_in["t"] - t_circle, first_in["line"], lead),
        start_not_before=tstr(last_clear), start_not_before_tolerance_s=1.0,
        start_uncertainty_is_start_minus_start_not_before=True, uncertainty_tolerance_s=1.0,
        speed_before_kn=[9.5, 10.5],
        rule="under way (10 kn) and seen clear at line %d; at rest in contact from line %d for 3 h within 170 m of where "
             "it touched; fixes 600 s apart (sparse), no berth (one vessel, Status 0, no --berths): grounding, grade 3"
             % (last_clear["line"], first_in["line"]))
    return tr, geometry, expect


def case_sparse_840():
    tr, geometry, site, last_clear, first_in, t_circle, start = case_aground_sparse(
        840, 230990009, "AGROUND SPARSE GAP", dt.datetime(2024, 5, 9, 9, 0, 0), 20240509)
    expect = dict(
        exit_status=1, groundings=1, events=1,
        start=tstr(first_in), start_tolerance_s=1.0,
        start_not_before=tstr(last_clear), start_not_before_tolerance_s=1.0,
        start_uncertainty_s=840.0, uncertainty_tolerance_s=1.0,
        speed_before_kn=[9.5, 10.5],
        rule="a gap of 840 s (> --max-gap 600) between line %d (clear, 10 kn) and line %d; from line %d it lies still in "
             "contact for 3 h where no other vessel stays: a grounding inside the gap, start = line %d, "
             "start_not_before = line %d" % (last_clear["line"], first_in["line"], first_in["line"], first_in["line"],
                                              last_clear["line"]))
    return tr, geometry, expect


def case_ferry_expect():
    tr, geometry = case_ferry()
    expect = dict(
        exit_status=0, groundings=0, contact_events=C10_CALLS, kinds=["alongside"],
        calls=[[c["first_fix"], c["last_fix"]] for c in geometry["calls"]],
        rule="each call: the hull touches the charted shore under way (4.4-4.8 kn at the fix before) and comes to rest "
             "%.0f s later, slowing evenly at 0.04 kn/s (not abrupt: under 0.2 kn/s); moored (Status 5) where the ferry "
             "lies every hour: alongside, one event per call (its contact lasts from the approach to the departure)"
             % geometry["first_contact_to_rest_s"])
    return tr, geometry, expect


def case_canal_expect():
    tr, geometry = case_canal()
    expect = dict(
        exit_status=0, groundings=0, contact_events=1, kind="chart_disagrees",
        disagreement="sailed_through",
        start=geometry["first_contact_written_track"], start_tolerance_s=2.0,
        simulated=dict(exit_status=1, groundings=1, contact_events=1),
        rule="it goes on through %.0f m of charted land at 8 kn without slowing; deepest %.0f m inside (under hull "
             "length + 50 m = 170 m): chart_disagrees, sailed_through. --world simulated: a grounding"
             % (geometry["land_crossed_along_course_m"], geometry["max_penetration_m_unjittered"]))
    return tr, geometry, expect


def case_touch_and_go_expect():
    tr, geometry, start, ts = case_touch_and_go()
    expect = dict(
        exit_status=1, groundings=1, contact_events=1, grade=2, reason_contains="touch and go",
        start_earliest=geometry["last_fix_before"], start_latest=geometry["first_fix_after"],
        rule="the contact lies between two fixes 10 s apart; 10 kn before, 4 kn after (<= half), a drop of 0.6 kn/s "
             "(>= 0.2): touch and go, a grounding of grade 2")
    return tr, geometry, expect


def case_pilot_expect():
    tr, geometry = case_pilot()
    expect = dict(
        exit_status=0, groundings=0, contact_events=1, kinds=["alongside"],
        rule="the boat touches the shore at 0.6 kn (the fix before under 1 kn) after slowing evenly over 2 min, and "
             "lies there 1 h (Status 5): alongside; its touches while lying there (jitter) are the same stay: one event")
    return tr, geometry, expect


def case_skerry_expect():
    tr, geometry, start, ts = case_skerry()
    a, b = geometry["around_the_islet_times"]
    expect = dict(
        exit_status=0, groundings=0, contact_events=1, kind="chart_disagrees", disagreement="between_fixes",
        start_earliest=a, start_latest=b,
        simulated=dict(exit_status=1, groundings=1, contact_events=1),
        rule="only the straight line between two fixes 180 s apart touches land (both fixes clear, 12 kn before and "
             "after): chart_disagrees, between_fixes. --world simulated: a grounding")
    return tr, geometry, expect


REAL_WORLD_CASES = [
    ("aground_sparse.csv", case_sparse_600, ARGS_DIMS,
     "case 1's voyage (10 kn onto an island) seen every 600 s, no heading and no COG: aground 3 h (SOG 0, Status 0)"),
    ("aground_sparse_gap.csv", case_sparse_840, ARGS_DIMS,
     "the same with 840 s (a gap longer than --max-gap) between the last clear fix and the first fix in contact"),
    ("ferry_hourly.csv", case_ferry_expect, ARGS_DIMS,
     "a ferry calls hourly for 6 h at a pier the chart draws as land: 12 kn, slowing evenly (0.04 kn/s), 15 min moored"),
    ("canal_transit.csv", case_canal_expect, ARGS_DIMS,
     "8 kn for 25 min straight through a 187 m wide piece of charted land (a canal the chart lacks)"),
    ("touch_and_go.csv", case_touch_and_go_expect, ARGS_DIMS,
     "10 kn, turning hard, the bow clips an islet's corner between two fixes 10 s apart; 4 kn after, then on at 7 kn"),
    ("pilot_berthing.csv", case_pilot_expect, ARGS_DIMS + " --hull-from-length-width",
     "a 20 m pilot boat (Length 20, Width 6) comes in at 15 kn, slows to rest in 2 min touching the shore at 0.6 kn, lies 1 h"),
    ("skerry_sparse.csv", case_skerry_expect, ARGS_DIMS,
     "12 kn, fixes 180 s apart: the straight line between two fixes cuts an islet's corner the vessel went round"),
]


# ---------------------------------------------------------------------------------------------


CASES = [
    ("aground_at_speed.csv", lambda: case_aground(False),
     "10 kn straight onto an island's south shore; stops dead at the first fix in contact, aground 30 min"),
    ("aground_at_speed_no_sog.csv", lambda: case_aground(True),
     "the same voyage with SOG and COG empty and Heading 511 throughout"),
    ("moored_then_leaves.csv", case_moored,
     "moored 1 h with the starboard side 1.5 m off an island's shore (jitter touches and clears), then leaves at 8 kn"),
    ("berthing_sideways.csv", case_berthing,
     "moves sideways at 0.3 kn from 40 m off onto a mainland shore, overlapping it 2.5 m, lies 20 min"),
    ("jump_and_null_island.csv", case_jump,
     "12 kn in open water, one fix jumps 5 km into the mainland and back, another is at 0,0"),
    ("still_no_heading.csv", case_still,
     "lies still 1 h 30 m off a shore, heading unknown (511), COG empty"),
    ("passes_clear.csv", case_passes,
     "12 kn past an islet with the hull 250 m clear"),
]


def main():
    out = dict(
        description="Hand-made AIS tracks (MarineCadastre CSV layout) against the GSHHG coastline "
                    "examples/data/gof_helsinki_land.geojson, made by make_cases.py in this folder.",
        coast=COAST_REL, dims=list(DIMS),
        command="shoal check --coast %s --dims 100,20,8,8 FILE -o REPORT.geojson" % COAST_REL,
        hull="AIS A=100 (to bow), B=20, C=8, D=8: 120 m x 16 m, reference point on the centre line 100 m behind the bow",
        jitter=dict(sigma_m=SIGMA_M, model="gaussian, east and north independently, one fixed seed per case "
                                          "(Python random.Random(seed).gauss)"),
        frame="geometry in a local transverse Mercator frame (WGS84 ellipsoid) centred on each case's site; OGR "
              "(GEOS) Intersects/Distance; true headings turned into grid azimuths with the meridian convergence",
        lines="line numbers count the header as line 1",
        cases={},
    )
    for name, fn, what in CASES:
        tr, geometry, expect = fn()
        path = os.path.join(HERE, name)
        tr.write(path)
        out["cases"][name] = dict(
            what=what, mmsi=tr.vessel.mmsi, vessel_name=tr.vessel.name, seed=tr.seed, fixes=len(tr.fixes),
            lines=[2, len(tr.fixes) + 1], first_fix=tr.fixes[0]["time"].strftime("%Y-%m-%dT%H:%M:%SZ"),
            last_fix=tr.fixes[-1]["time"].strftime("%Y-%m-%dT%H:%M:%SZ"),
            expect=expect, geometry=geometry)
        print("%-28s %4d fixes %6d bytes" % (name, len(tr.fixes), os.path.getsize(path)))
    # The real-world cases (tests/cli/real_world_test.cpp): `args` are the options of their
    # command, `shoal check --coast COAST ARGS FILE -o REPORT`.
    for name, fn, args, what in REAL_WORLD_CASES:
        tr, geometry, expect = fn()
        path = os.path.join(HERE, name)
        tr.write(path)
        out["cases"][name] = dict(
            what=what, args=args, command="shoal check --coast %s %s FILE -o REPORT.geojson" % (COAST_REL, args),
            mmsi=tr.vessel.mmsi, vessel_name=tr.vessel.name, seed=tr.seed, fixes=len(tr.fixes),
            lines=[2, len(tr.fixes) + 1], first_fix=tr.fixes[0]["time"].strftime("%Y-%m-%dT%H:%M:%SZ"),
            last_fix=tr.fixes[-1]["time"].strftime("%Y-%m-%dT%H:%M:%SZ"),
            expect=expect, geometry=geometry)
        assert os.path.getsize(path) < 60000, name
        print("%-28s %4d fixes %6d bytes" % (name, len(tr.fixes), os.path.getsize(path)))
    with open(os.path.join(HERE, "expected.json"), "w", newline="\n") as f:
        json.dump(out, f, indent=1, default=str)
        f.write("\n")


if __name__ == "__main__":
    sys.exit(main())
