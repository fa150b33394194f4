#!/usr/bin/python3
"""Writes tacoma_berthing.csv and tacoma_pier_collision.csv: two AIS tracks in the
MarineCadastre CSV layout against the S-57 cut tests/data/coast/US5WA22M_tacoma_cut.000
(Port of Tacoma, the point between the Hylebos and Blair waterways: Piers 23-25, the wharf on
the Hylebos side, dolphins, pontoons).

Run with Debian's /usr/bin/python3 (python3-gdal; no other modules):

    /usr/bin/python3 tests/data/tracks/make_tacoma_tracks.py

The output is the same on every run (one fixed seed per track). Geometry is computed with OGR
(GEOS) in a local transverse Mercator frame (WGS84 ellipsoid) centred on the cut; true
headings become grid azimuths with the frame's meridian convergence. The hazards are read
from the cut with OGR and built as docs/method.md says, independently of shoal's code: LNDARE
polygons; SLCONS, PONTON, HULKES and MORFAC (not CATMOR 6 chains nor 7 mooring buoys) as
structures, their polygons as they are, their lines within 1 m and their points within 2.5 m
(exact GEOS buffers of 64 segments a quarter circle: shoal's polygons, circumscribed with 8,
reach 0.5 % farther, 5 mm on a line, which moves a contact by about a millisecond here);
DEPARE and DRGARE whose DRVAL1 is under the vessel's draught. Every position gets gaussian GPS
jitter (sigma 2 m east and 2 m north, independently), is written with 6 decimals, and every
check on a written fix is made on the values read back. Hulls: the rectangle of Length x Width
centred on the position (shoal's `--hull-from-length-width`: the reference point amidships),
and shoal's generated 36-point outline for those dimensions (src/hull/hull.cpp
generate_outline, rebuilt here as in ais_cases/make_cases.py), which lies inside the rectangle.

tacoma_berthing.csv (MMSI 366990001, "HARBOUR TEST BERTH", 120 x 20 m, no draught given: the
chart draws a 3.6 m and a 5.4 m strip along the face, which a loaded 120 m ship's draught
would touch before the wharf): from the waterway's mouth, 1.1 km north-west of its berth and
25 m off the line of the wharf face (and of Pier 25's, in line with it), it comes in at 8.0 kn
slowing steadily to 0 over 540 s (a = 0.0076 m/s^2); over the last 250 m its offset from the
face closes (half a cosine, 4.5 degrees at most off the face's line) to 1.5 m more than at
the berth, which it closes sideways over the last 120 s (0.0125 m/s), and it lies alongside
the wharf on the Hylebos side (S-57 SLCONS CATSLC 6, no name) for 2 h,
starboard side to, heading 132 true, its side 0.8 m off the charted face line (fenders),
inside the 1 m band the line becomes. Fixes every 10 s, Status 0 under way, 5 (moored) from
the first fix at rest; Heading the path's direction, then the berth heading.

tacoma_pier_collision.csv (MMSI 366990002, "HARBOUR TEST ALLISION", 60 x 12 m, draught
3.2 m): from 1.4 km off in the bay it runs at 9.5 kn, course and heading 56 true,
into the south-west side of Pier 23 (S-57 SLCONS CATSLC 4, OBJNAM "Pier 23"), 13 degrees off
square; from the moment of first contact (on the un-jittered line) it decelerates at 0.4 m/s^2
and stops 29.9 m on, 12.2 s later, then lies there 1 h. Fixes every 10 s,
Status 0 throughout.

Hand-derived moments (this script checks, on every run, that it finds them again):

tacoma_berthing.csv
  - un-jittered: the outline first comes within the wharf's band at t = 520.648 s
    after the first fix (06:08:40.648Z; the rectangle at 402.148 s), at
    0.29 kn; nothing else is touched before: the first contact is the wharf.
  - written fixes: 431 of the 721 fixes at rest touch a
    structure with the outline, the first at line 56 (06:09:00Z);
    the first written fix whose outline touches anything is line 42,
    and what it touches is LNDARE 0226008303A61C83, SLCONS 02261233AB491C83 CATSLC 6.

tacoma_pier_collision.csv
  - first contact on the un-jittered line: T = 280.113 s after the first fix with
    shoal's outline (14:04:40.113Z); the rectangle 279.823 s; the bow tip alone
    (a point of the outline) 280.113 s. What it touches first: SLCONS 02260FBBE4961C83 'Pier 23' CATSLC 4.
  - first contact on the written fixes (positions interpolated linearly, headings the shorter
    way, as shoal sweeps them): 280.485 s with the outline (14:04:40.485Z),
    279.994 s with the rectangle; the fixes around it are lines
    30 and 31. What it touches first: SLCONS 02260FBBE4961C83 'Pier 23' CATSLC 4.
  - the contact point (outline, written fixes): 47.284332 N, 122.413629 W.

The MMSIs, names and voyages are invented (public domain); the chart is NOAA's (see
tests/data/README.md).
"""

import datetime as dt
import math
import os
import random
import sys

from osgeo import ogr, osr

ogr.UseExceptions()
osr.UseExceptions()

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
CUT = os.path.join(REPO, "tests", "data", "coast", "US5WA22M_tacoma_cut.000")
CENTRE = (-122.4095, 47.28325)  # the cut's box centre

WHARF_LNAM = "02261233AB491C83"  # SLCONS CATSLC 6, the wharf along the point's Hylebos side
SIGMA_M = 2.0
KN = 1852.0 / 3600.0  # m/s per knot
LINE_HALF_WIDTH_M, POINT_RADIUS_M = 1.0, 2.5  # docs/method.md, coast::structure_*
RESULTS = """Hand-derived moments (this script checks, on every run, that it finds them again):

tacoma_berthing.csv
  - un-jittered: the outline first comes within the wharf's band at t = {berth_T_outline} s
    after the first fix ({berth_T_outline_time}; the rectangle at {berth_T_box} s), at
    {berth_speed_kn:.2f} kn; nothing else is touched before: the first contact is the wharf.
  - written fixes: {berth_fixes_touch} of the {berth_fixes_at_rest} fixes at rest touch a
    structure with the outline, the first at line {berth_first_touch_line} ({berth_first_touch_time});
    the first written fix whose outline touches anything is line {berth_first_any_line},
    and what it touches is {berth_first_any_what}.

tacoma_pier_collision.csv
  - first contact on the un-jittered line: T = {coll_T_outline:.3f} s after the first fix with
    shoal's outline ({coll_T_outline_time}); the rectangle {coll_T_box:.3f} s; the bow tip alone
    (a point of the outline) {coll_T_tip:.3f} s. What it touches first: {coll_first_what}.
  - first contact on the written fixes (positions interpolated linearly, headings the shorter
    way, as shoal sweeps them): {coll_T_written:.3f} s with the outline ({coll_T_written_time}),
    {coll_T_written_box:.3f} s with the rectangle; the fixes around it are lines
    {coll_line_before} and {coll_line_after}. What it touches first: {coll_written_what}.
  - the contact point (outline, written fixes): {coll_contact_lat:.6f} N, {coll_contact_lon:.6f} W.
"""

HEADER = ("MMSI,BaseDateTime,LAT,LON,SOG,COG,Heading,VesselName,IMO,CallSign,VesselType,Status,"
          "Length,Width,Draft,Cargo,TransceiverClass")

WGS84 = osr.SpatialReference()
WGS84.ImportFromEPSG(4326)
WGS84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)


# ---------------------------------------------------------------------------------------------
# Hulls (x forward, y starboard, metres from the reference point)


def box_outline(length, width):
    a, c = length / 2, width / 2
    return [(a, -c), (a, c), (-a, c), (-a, -c)]


def shoal_outline(length, width, n=36):
    """shoal's generated outline for dims (L/2, L/2, W/2, W/2) (src/hull/hull.cpp)."""
    a = b = length / 2
    c = d = width / 2
    half_beam, centre = 0.5 * (c + d), 0.5 * (d - c)
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


def polygon(pts):
    ring = ogr.Geometry(ogr.wkbLinearRing)
    for x, y in list(pts) + [pts[0]]:
        ring.AddPoint_2D(x, y)
    poly = ogr.Geometry(ogr.wkbPolygon)
    poly.AddGeometry(ring)
    return poly


def point(x, y):
    p = ogr.Geometry(ogr.wkbPoint)
    p.AddPoint_2D(x, y)
    return p


# ---------------------------------------------------------------------------------------------
# The frame and the chart's hazards


class Chart:
    def __init__(self):
        lon0, lat0 = CENTRE
        tm = osr.SpatialReference()
        tm.ImportFromProj4("+proj=tmerc +lat_0=%.9f +lon_0=%.9f +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +no_defs"
                           % (lat0, lon0))
        self.fwd = osr.CoordinateTransformation(WGS84, tm)
        self.inv = osr.CoordinateTransformation(tm, WGS84)
        self.ds = ogr.Open(CUT)
        self.structures = []  # (label, geometry in local metres)
        for name in ("SLCONS", "PONTON", "HULKES", "MORFAC"):
            layer = self.ds.GetLayerByName(name)
            if layer is None:
                continue
            for f in layer:
                if name == "MORFAC" and f.GetField("CATMOR") in (6, 7):
                    continue
                g = f.GetGeometryRef().Clone()
                g.Transform(self.fwd)
                kind = g.GetGeometryType()
                if kind == ogr.wkbLineString:
                    g = g.Buffer(LINE_HALF_WIDTH_M, 64)
                elif kind == ogr.wkbPoint:
                    g = g.Buffer(POINT_RADIUS_M, 64)
                label = "%s %s%s" % (name, f.GetField("LNAM"), " '%s'" % f.GetField("OBJNAM") if f.GetField("OBJNAM") else "")
                if name == "SLCONS":
                    label += " CATSLC %s" % f.GetField("CATSLC")
                self.structures.append((label, g))
        self.land = []
        for f in self.ds.GetLayerByName("LNDARE"):
            g = f.GetGeometryRef().Clone()
            if g.GetGeometryType() != ogr.wkbPolygon:
                continue  # a point islet is no coastline (shoal skips it too)
            g.Transform(self.fwd)
            self.land.append(("LNDARE %s" % f.GetField("LNAM"), g))
        self.depths = []
        for name in ("DEPARE", "DRGARE"):
            for f in self.ds.GetLayerByName(name):
                g = f.GetGeometryRef().Clone()
                g.Transform(self.fwd)
                self.depths.append(("%s %s DRVAL1 %s" % (name, f.GetField("LNAM"), f.GetField("DRVAL1")), f.GetField("DRVAL1"), g))

    def hazards(self, draught):
        """What the hull of a vessel of that draught must not touch (None: land and structures)."""
        out = list(self.land) + list(self.structures)
        if draught is not None:
            out += [(label, g) for label, d, g in self.depths if d is None or d < draught]
        return out

    def structure(self, layer, where):
        """The feature of `layer` with the most vertices of those that pass the OGR attribute
        filter `where`: (LNAM, local geometry)."""
        lay = self.ds.GetLayerByName(layer)
        lay.SetAttributeFilter(where)
        found = [(f.GetGeometryRef().GetPointCount(), f.GetField("LNAM"), f.GetGeometryRef().Clone()) for f in lay]
        lay.SetAttributeFilter(None)
        _, lnam, g = max(found, key=lambda c: c[0])
        g.Transform(self.fwd)
        return lnam, g

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

    def hull(self, x, y, true_heading, outline):
        th = math.radians(true_heading + self.convergence(x, y))
        fx, fy = math.sin(th), math.cos(th)
        sx, sy = math.cos(th), -math.sin(th)
        return polygon([(x + px * fx + py * sx, y + px * fy + py * sy) for px, py in outline])


def touching(geom, hazards):
    return [label for label, g in hazards if geom.Intersects(g)]


def first_contact(motion, t0, t1, hazards, outline, step=0.25):
    """The first moment in [t0, t1] the hull placed by motion(t) -> (x, y, true heading) touches a
    hazard, to 1 ms, and what it touches then; (None, []) when it never does."""
    def hits(t):
        x, y, h = motion(t)
        return touching(chart.hull(x, y, h, outline), hazards)
    if hits(t0):
        return t0, hits(t0)
    t = t0
    while t < t1:
        t_next = min(t + step, t1)
        if hits(t_next):
            lo, hi = t, t_next
            while hi - lo > 1e-3:
                mid = 0.5 * (lo + hi)
                lo, hi = (lo, mid) if hits(mid) else (mid, hi)
            return hi, hits(hi)
        t = t_next
    return None, []


# ---------------------------------------------------------------------------------------------
# Writing fixes


class Track:
    def __init__(self, mmsi, name, length, width, draught, start, seed):
        self.mmsi, self.name, self.length, self.width, self.draught = mmsi, name, length, width, draught
        self.start = start
        self.rng = random.Random(seed)
        self.rows = []
        self.fixes = []  # dicts: t, line, x, y (as written, read back), heading, sog, status

    def add(self, t, x0, y0, sog_kn, cog, heading, status):
        dx, dy = self.rng.gauss(0.0, SIGMA_M), self.rng.gauss(0.0, SIGMA_M)
        lon, lat = chart.ll(x0 + dx, y0 + dy)
        lat_s, lon_s = "%.6f" % lat, "%.6f" % lon
        when = self.start + dt.timedelta(seconds=t)
        hdg = int(round(heading)) % 360
        self.rows.append(",".join([
            str(self.mmsi), when.strftime("%Y-%m-%dT%H:%M:%S"), lat_s, lon_s, "%.1f" % sog_kn, "%.1f" % (cog % 360.0),
            str(hdg), self.name, "", "", "70", str(status), "%d" % self.length, "%d" % self.width,
            "" if self.draught is None else "%.1f" % self.draught, "70", "A"]))
        x, y = chart.xy(float(lon_s), float(lat_s))
        self.fixes.append({"t": t, "line": len(self.rows) + 1, "x": x, "y": y, "heading": hdg, "status": status,
                           "time": when})

    def write(self, path):
        with open(path, "w", newline="\n") as f:
            f.write(HEADER + "\n")
            for r in self.rows:
                f.write(r + "\n")

    def written_motion(self):
        """Position (linear) and heading (the shorter way) between the written fixes, as shoal sweeps."""
        fx = self.fixes

        def motion(t):
            i = max(0, min(len(fx) - 2, int(t // 10)))
            while i + 1 < len(fx) - 1 and fx[i + 1]["t"] <= t:
                i += 1
            a, b = fx[i], fx[i + 1]
            f = (t - a["t"]) / (b["t"] - a["t"])
            dh = (b["heading"] - a["heading"] + 180.0) % 360.0 - 180.0
            return a["x"] + f * (b["x"] - a["x"]), a["y"] + f * (b["y"] - a["y"]), a["heading"] + f * dh
        return motion

    def time_text(self, t):
        return (self.start + dt.timedelta(seconds=t)).strftime("%H:%M:%S") + (".%03d" % round((t % 1) * 1000)) + "Z"


def bearing(dx, dy):
    return math.degrees(math.atan2(dx, dy)) % 360.0


def main():
    global chart
    chart = Chart()
    out = {}

    # ---- (a) berthing: the long straight segment of the wharf on the Hylebos side
    lay = chart.ds.GetLayerByName("SLCONS")
    best = None
    for f in lay:
        if f.GetField("LNAM") != WHARF_LNAM:
            continue
        assert f.GetField("CATSLC") == 6
        g = f.GetGeometryRef().Clone()
        g.Transform(chart.fwd)
        pts = [g.GetPoint_2D(i) for i in range(g.GetPointCount())]
        for i in range(len(pts) - 1):
            seg = math.hypot(pts[i + 1][0] - pts[i][0], pts[i + 1][1] - pts[i][1])
            if best is None or seg > best[0]:
                best = (seg, f.GetField("LNAM"), pts[i], pts[i + 1])
    seg_len, wharf_lnam, p_se, p_nw = best
    assert seg_len > 250, seg_len
    ux, uy = (p_nw[0] - p_se[0]) / seg_len, (p_nw[1] - p_se[1]) / seg_len  # along the face, towards NW
    nx, ny = uy, -ux  # normal, to the water side (the right of SE -> NW)
    length, width = 120, 20
    berth_off = width / 2 + 0.8
    s_berth = 0.45 * seg_len  # from the SE end
    bx, by = p_se[0] + ux * s_berth, p_se[1] + uy * s_berth
    face_grid = bearing(-ux, -uy)  # heading SE along the face, grid azimuth
    berth_heading = (face_grid - chart.convergence(bx, by))
    v0, t_app = 8.0 * KN, 540.0
    run = v0 * t_app / 2  # 1111 m
    off0, closing, creep, creep_s = 25.0, 250.0, 1.5, 120.0

    def offset(togo):
        """Off the face line: off0 until `closing` metres before the berth, then closing in
        (half a cosine) to berth_off + creep, parallel to the face at the end."""
        end = berth_off + creep
        if togo >= closing:
            return off0, 0.0
        th = math.pi * togo / closing
        return end + (off0 - end) * (1 - math.cos(th)) / 2, (off0 - end) * math.pi / closing * math.sin(th) / 2

    def approach(t):
        """Un-jittered position and true heading at t seconds (0 <= t)."""
        tt = min(t, t_app)
        travelled = v0 * tt - 0.5 * (v0 / t_app) * tt * tt
        togo = run - travelled  # along the face, metres before the berth
        off, doff = offset(togo)
        off -= creep * min(1.0, max(0.0, (tt - (t_app - creep_s)) / creep_s))  # the last 1.5 m sideways
        x = bx + ux * togo + nx * off
        y = by + uy * togo + ny * off
        # direction of travel: d/d(togo) of the path, reversed (togo decreases)
        dx, dy = -(ux + nx * doff), -(uy + ny * doff)
        heading = bearing(dx, dy) - chart.convergence(x, y)
        speed = max(0.0, v0 - (v0 / t_app) * tt)
        return x, y, heading, speed

    trk = Track(366990001, "HARBOUR TEST BERTH", length, width, None, dt.datetime(2023, 7, 14, 6, 0, 0), 20230714)
    n_app = int(t_app // 10)
    for k in range(n_app + 1 + 720):
        t = 10.0 * k
        x, y, h, v = approach(t)
        moving = t < t_app
        trk.add(t, x, y, v / KN, h if moving else berth_heading, h if moving else berth_heading, 0 if moving else 5)
    trk.write(os.path.join(HERE, "tacoma_berthing.csv"))
    outline, box = shoal_outline(length, width), box_outline(length, width)
    hazards = chart.hazards(None)
    motion = lambda t: approach(t)[:3]
    t_o, what_o = first_contact(motion, 0.0, t_app, hazards, outline)
    t_b, _ = first_contact(motion, 0.0, t_app, hazards, box)
    assert t_o is not None and all(wharf_lnam in w for w in what_o), (t_o, what_o)
    out["berth_T_outline"] = "%.3f" % t_o
    out["berth_T_outline_time"] = trk.time_text(t_o)
    out["berth_T_box"] = "%.3f" % t_b
    out["berth_speed_kn"] = approach(t_o)[3] / KN
    structure_hazards = list(chart.structures)
    at_rest = [f for f in trk.fixes if f["status"] == 5]
    touch = [f for f in at_rest if touching(chart.hull(f["x"], f["y"], f["heading"], outline), structure_hazards)]
    out["berth_fixes_touch"] = len(touch)
    out["berth_fixes_at_rest"] = len(at_rest)
    out["berth_first_touch_line"] = touch[0]["line"]
    out["berth_first_touch_time"] = touch[0]["time"].strftime("%H:%M:%SZ")
    first_any = next(f for f in trk.fixes if touching(chart.hull(f["x"], f["y"], f["heading"], outline), hazards))
    out["berth_first_any_line"] = first_any["line"]
    out["berth_first_any_what"] = ", ".join(touching(chart.hull(first_any["x"], first_any["y"], first_any["heading"], outline), hazards))

    # ---- (b) running into Pier 23's south-west side
    pier_lnam, pier = chart.structure("SLCONS", "OBJNAM = 'Pier 23' AND CATSLC = 4")
    pts = [pier.GetPoint_2D(i) for i in range(pier.GetPointCount())]
    # The pier's longest straight side: its axis direction, and which side faces south-west.
    sides = sorted(((math.hypot(pts[i + 1][0] - pts[i][0], pts[i + 1][1] - pts[i][1]), i) for i in range(len(pts) - 1)),
                   reverse=True)
    candidates = []
    for seg, i in sides[:2]:
        a, b = pts[i], pts[i + 1]
        mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
        candidates.append((mx + my, i, seg))  # the south-west side has the smaller x + y
    _, i_side, side_len = min(candidates)
    a, b = pts[i_side], pts[i_side + 1]
    sx_, sy_ = (b[0] - a[0]) / side_len, (b[1] - a[1]) / side_len
    # inward normal (towards the pier) = the normal pointing north-east
    inx, iny = -sy_, sx_
    if inx + iny < 0:
        inx, iny = -inx, -iny
    normal_grid = bearing(inx, iny)
    # aim at the side 70 m from its north-west end, 13 degrees off square (turned towards the north)
    nw_end = a if a[1] > b[1] else b
    se_dir = (sx_, sy_) if a[1] > b[1] else (-sx_, -sy_)
    ax_, ay_ = nw_end[0] + se_dir[0] * 70.0, nw_end[1] + se_dir[1] * 70.0
    course_grid = normal_grid + 13.0
    course = round(course_grid - chart.convergence(ax_, ay_))  # integer true degrees, as AIS writes headings
    cx, cy = math.sin(math.radians(course + chart.convergence(ax_, ay_))), math.cos(math.radians(course + chart.convergence(ax_, ay_)))
    length2, width2, draught2 = 60, 12, 3.2
    v1 = 9.5 * KN
    dist0 = 1400.0  # the reference point starts this far before the aim point, back along the course
    decel = 0.4
    hazards2 = chart.hazards(draught2)

    def straight(t):
        return ax_ - cx * (dist0 - v1 * t), ay_ - cy * (dist0 - v1 * t), course
    T0, what0 = first_contact(straight, 0.0, dist0 / v1 + 10, hazards2, shoal_outline(length2, width2))
    assert T0 is not None and all(pier_lnam in w for w in what0), (T0, what0)
    t_stop = v1 / decel
    stop_m = v1 * v1 / (2 * decel)

    def voyage(t):
        if t <= T0:
            s = v1 * t
            v = v1
        else:
            tt = min(t - T0, t_stop)
            s = v1 * T0 + v1 * tt - 0.5 * decel * tt * tt
            v = max(0.0, v1 - decel * tt)
        return ax_ - cx * (dist0 - s), ay_ - cy * (dist0 - s), course, v

    trk2 = Track(366990002, "HARBOUR TEST ALLISION", length2, width2, draught2, dt.datetime(2023, 7, 14, 14, 0, 0), 20230715)
    n = int((T0 + t_stop) // 10) + 1 + 360
    for k in range(n + 1):
        t = 10.0 * k
        x, y, h, v = voyage(t)
        trk2.add(t, x, y, v / KN, course, course, 0)
    trk2.write(os.path.join(HERE, "tacoma_pier_collision.csv"))
    outline2, box2 = shoal_outline(length2, width2), box_outline(length2, width2)
    mot = lambda t: voyage(t)[:3]
    t_outline, what_outline = first_contact(mot, 0.0, T0 + 30, hazards2, outline2)
    t_box, _ = first_contact(mot, 0.0, T0 + 30, hazards2, box2)
    t_tip, _ = first_contact(mot, 0.0, T0 + 30, hazards2, [(length2 / 2, 0.0), (length2 / 2 - 0.01, 0.0), (length2 / 2 - 0.01, 0.001)])
    assert abs(t_outline - T0) < 1e-3
    wm = trk2.written_motion()
    t_w, what_w = first_contact(wm, 0.0, T0 + 30, hazards2, outline2)
    t_wb, _ = first_contact(wm, 0.0, T0 + 30, hazards2, box2)
    before = [f for f in trk2.fixes if f["t"] <= t_w][-1]["line"]
    after = [f for f in trk2.fixes if f["t"] > t_w][0]["line"]
    x, y, h = wm(t_w)
    hull = chart.hull(x, y, h, outline2)
    contact = None
    for label, g in hazards2:
        if hull.Intersects(g):
            c = hull.Intersection(g).Centroid()
            contact = chart.ll(c.GetX(), c.GetY())
            break
    out.update({
        "coll_course": course, "coll_stop_m": stop_m, "coll_stop_s": t_stop,
        "coll_T_outline": t_outline, "coll_T_outline_time": trk2.time_text(t_outline), "coll_T_box": t_box, "coll_T_tip": t_tip,
        "coll_first_what": ", ".join(what_outline),
        "coll_T_written": t_w, "coll_T_written_time": trk2.time_text(t_w), "coll_T_written_box": t_wb,
        "coll_line_before": before, "coll_line_after": after, "coll_written_what": ", ".join(what_w),
        "coll_contact_lat": contact[1], "coll_contact_lon": -contact[0],
    })
    found = RESULTS.format(**out)
    if " ".join(found.split()) not in " ".join(__doc__.split()):
        sys.stdout.write(found)
        sys.exit("make_tacoma_tracks.py: the moments found (above) are not the ones its docstring states; "
                 "check the change, then put them in the docstring")
    return out


if __name__ == "__main__":
    main()
