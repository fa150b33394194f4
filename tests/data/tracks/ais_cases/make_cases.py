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
    with open(os.path.join(HERE, "expected.json"), "w", newline="\n") as f:
        json.dump(out, f, indent=1, default=str)
        f.write("\n")


if __name__ == "__main__":
    sys.exit(main())
