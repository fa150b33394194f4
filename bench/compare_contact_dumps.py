#!/usr/bin/python3
"""Compares two SHOAL_BENCH_DUMP files of bench/frame_contacts.c (the old library's and the new
one's) within tolerances, for changes that may move the answers by rounding or choose another
of equal-depth candidates (docs/performance.md, issue 37).

    /usr/bin/python3 bench/compare_contact_dumps.py OLD.dump NEW.dump [--depth-tol M] [--angle-tol RAD] [--same-point M]

A dump line is "FRAME REGION DEPTH X Y NX NY HAZARD" (ship frame, metres on the ground; the
regions deepest first) or "FRAME none". Checked: the same frames in contact, the same number of
regions in each, each region's depth within --depth-tol (default 2e-6 m: shoal_contacts is
exact to a micrometre, include/shoal/check/contacts.hpp, so two answers differ by at most
twice that), its hazard equal, and its normal within --angle-tol (default 1e-3 rad) unless the
depth is not unique in direction:
 - the deepest point is another (more than --same-point apart, default 1e-6 m): the same depth
   within the tolerance is reached at two points, and each answer's normal is its own point's.
   An interior deepest point lies on the medial axis, a ridge between two boundary pieces,
   and a search exact to a micrometre in depth may stop micrometres to millimetres along or
   beside it (more where the depth varies slowly, as along a hull edge nearly parallel to
   the boundary; anywhere along a pier of parallel sides). Counted, with how far apart;
 - or it is the same point on a ridge, where either normal frees it by the same depth: the
   old deepest point lies as near the new answer's boundary point (point + depth x normal) as
   its own depth, and the new one as near the old's, within twice the depth tolerance.
Any other normal that differs fails. Regions are
matched by their order, and where depths within the tolerance tie, by the nearest normal.
Prints the worst differences; exit status 1 when a check fails, 2 on a bad file.
"""
import math
import sys


def read(path):
    frames = {}
    try:
        with open(path) as f:
            for n, line in enumerate(f, 1):
                w = line.split()
                if len(w) == 2 and w[1] == "none":
                    frames.setdefault(int(w[0]), [])
                    continue
                if len(w) != 8:
                    sys.exit("%s:%d: not a dump line (FRAME REGION DEPTH X Y NX NY HAZARD): %r" % (path, n, line.strip()))
                frames.setdefault(int(w[0]), []).append(tuple(float(v) for v in w[2:7]) + (int(w[7]),))
    except OSError as e:
        print("%s: %s" % (path, e.strerror), file=sys.stderr)
        sys.exit(2)
    return frames


def angle(a, b):
    dot = max(-1.0, min(1.0, a[3] * b[3] + a[4] * b[4]))
    return math.acos(dot)


def ambiguous(a, b, tol):
    """Whether each answer's point is as near the other's boundary point as its own."""
    def dist_to_coast(p, q):
        cx, cy = q[1] + q[0] * q[3], q[2] + q[0] * q[4]
        return math.hypot(p[1] - cx, p[2] - cy)
    margin = tol
    return abs(dist_to_coast(a, b) - a[0]) <= margin and abs(dist_to_coast(b, a) - b[0]) <= margin


def match(old, new, tol):
    """new's regions in old's order: by order, a run of depths tied within tol by nearest normal."""
    out, rest = [], list(new)
    for o in old:
        best = min(range(len(rest)), key=lambda k: (abs(rest[k][0] - o[0]) > tol, angle(o, rest[k]), k))
        out.append(rest.pop(best))
    return out


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    opts = dict(a[2:].split("=", 1) for a in argv[1:] if a.startswith("--") and "=" in a)
    if len(args) != 2 or any(k not in ("depth-tol", "angle-tol", "same-point") for k in opts):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    depth_tol = float(opts.get("depth-tol", 2e-6))
    angle_tol = float(opts.get("angle-tol", 1e-3))
    same_point = float(opts.get("same-point", 1e-6))
    old, new = read(args[0]), read(args[1])
    failures = []
    if set(old) != set(new):
        failures.append("frames in contact differ: %d only in the old, %d only in the new" % (len(set(old) - set(new)), len(set(new) - set(old))))
    worst_depth = (0.0, None)
    worst_angle = (0.0, None)   # where the depth is unique in direction
    worst_move = (0.0, None)    # of the deepest point (not checked: equal depths anywhere along an edge)
    ambiguous_normals = 0
    other_points = 0            # another deepest point of the same depth, the normal other
    worst_other = (0.0, None)
    bands = [0, 0, 0]           # of those: apart by at most 10 um, 1 mm, more
    regions = 0
    for frame in sorted(set(old) & set(new)):
        a, b = old[frame], new[frame]
        if len(a) != len(b):
            failures.append("frame %d: %d regions in the old, %d in the new" % (frame, len(a), len(b)))
            continue
        for k, (ra, rb) in enumerate(zip(a, match(a, b, depth_tol))):
            regions += 1
            dd = abs(ra[0] - rb[0])
            if dd > worst_depth[0]:
                worst_depth = (dd, (frame, k))
            if dd > depth_tol:
                failures.append("frame %d region %d: depth %.9f m, was %.9f m" % (frame, k, rb[0], ra[0]))
            if ra[5] != rb[5]:
                failures.append("frame %d region %d: hazard %d, was %d" % (frame, k, rb[5], ra[5]))
            move = math.hypot(ra[1] - rb[1], ra[2] - rb[2])
            if move > worst_move[0]:
                worst_move = (move, (frame, k))
            ang = angle(ra, rb)
            if ang > angle_tol:
                if move > same_point:
                    other_points += 1
                    bands[0 if move <= 1e-5 else 1 if move <= 1e-3 else 2] += 1
                    if move > worst_other[0]:
                        worst_other = (move, (frame, k))
                    continue
                if ambiguous(ra, rb, 2 * depth_tol):
                    ambiguous_normals += 1
                    continue
                failures.append("frame %d region %d: normal (%.6f, %.6f), was (%.6f, %.6f): %.3g rad" % (frame, k, rb[3], rb[4], ra[3], ra[4], ang))
            if ang > worst_angle[0]:
                worst_angle = (ang, (frame, k))
    print("%d frames in contact (old %d, new %d), %d regions compared" % (len(set(old) & set(new)), len(old), len(new), regions))
    print("worst depth difference: %.3g m (frame, region %s; tolerance %.3g m)" % (worst_depth[0], worst_depth[1], depth_tol))
    print("worst normal angle at the same point off a ridge: %.3g rad (%s; tolerance %.3g rad)" % (worst_angle[0], worst_angle[1], angle_tol))
    print("the same point on a ridge, either normal freeing it by the same depth: %d" % ambiguous_normals)
    print("another deepest point of the same depth, its normal other: %d (%d within 10 um of the old, %d within 1 mm, %d farther;"
          " farthest %.3g m, %s)" % (other_points, bands[0], bands[1], bands[2], worst_other[0], worst_other[1]))
    print("worst move of the deepest point (not checked): %.3g m (%s)" % (worst_move[0], worst_move[1]))
    for f in failures[:20]:
        print("FAIL " + f)
    if failures:
        print("%d failures" % len(failures))
        return 1
    print("OK")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
