#!/usr/bin/env python3
# Written for issue 40's near-coast measurement (a helper's script, 2026-12-07); not part of the tests.
"""Compare the events of two shoal check GeoJSON reports (old vs new).

Usage: compare_events.py OLD.geojson NEW.geojson
Events are matched in order (both reports list them per track in time order) and, as a check,
by (track, start). Old kinds: grounding, close_pass. New kinds: contact kinds (grounding,
in_contact_at_start, chart_disagrees, alongside, expected_contact) and close_pass; a new
contact kind is counted equal to an old 'grounding'. Every property both reports have is
compared, and the point geometry. Prints counts and the fields that differ.
Exit 0 when count, contact/close type, start, end, least clearance, point and every other
common field agree (kind name, label and penetration_m reported apart).
"""
import json, sys, collections

CONTACT = {"grounding", "in_contact_at_start", "chart_disagrees", "alongside", "expected_contact"}

def load(p):
    d = json.load(open(p))
    return [f for f in d["features"]]

def cls(kind):
    return "contact" if kind in CONTACT else kind

old, new = load(sys.argv[1]), load(sys.argv[2])
print(f"events: old {len(old)}, new {len(new)}")
print("old kinds:", dict(collections.Counter(f["properties"]["kind"] for f in old)))
print("new kinds:", dict(collections.Counter(f["properties"]["kind"] for f in new)))
ko = collections.Counter((f["properties"]["track"], f["properties"]["start"]) for f in old)
kn = collections.Counter((f["properties"]["track"], f["properties"]["start"]) for f in new)
print("events keyed by (track, start): same set" if ko == kn else f"keyed sets differ: {len(ko - kn)} only old, {len(kn - ko)} only new")
old_s = sorted(old, key=lambda f: (f["properties"]["track"], f["properties"]["start"], f["properties"]["kind"]))
new_s = sorted(new, key=lambda f: (f["properties"]["track"], f["properties"]["start"], f["properties"]["kind"]))
common = sorted(set(old[0]["properties"]) & set(new[0]["properties"])) if old and new else []
only_new = sorted(set(new[0]["properties"]) - set(old[0]["properties"])) if new else []
only_old = sorted(set(old[0]["properties"]) - set(new[0]["properties"])) if old else []
print(f"common properties ({len(common)}):", ", ".join(common))
print(f"properties only in new ({len(only_new)}):", ", ".join(only_new))
print(f"properties only in old ({len(only_old)}):", ", ".join(only_old))
diff = collections.Counter(); examples = {}
kindmap = collections.Counter()
geom_diff = 0
for a, b in zip(old_s, new_s):
    pa, pb = a["properties"], b["properties"]
    kindmap[(pa["kind"], pb["kind"])] += 1
    for k in common:
        va, vb = pa[k], pb[k]
        if k == "kind":
            if cls(va if va != "grounding" else "grounding") != cls(vb) and not (va == "grounding" and vb in CONTACT):
                diff[k] += 1; examples.setdefault(k, (pa["track"], pa["start"], va, vb))
            continue
        if va != vb:
            diff[k] += 1; examples.setdefault(k, (pa["track"], pa["start"], va, vb))
    if a["geometry"] != b["geometry"]:
        geom_diff += 1; examples.setdefault("geometry", (pa["track"], pa["start"], a["geometry"], b["geometry"]))
print("kind old -> new:", {f"{x}->{y}": n for (x, y), n in sorted(kindmap.items())})
print("point geometries differing:", geom_diff)
if diff:
    for k, n in diff.most_common():
        print(f"  field {k}: {n} differ, e.g. {examples[k]}")
else:
    print("every common property equal (kind: a new contact kind counted equal to old 'grounding')")
# What must agree: count, the set of (track, start), contact or close pass, and every common
# field but the kind's name, its label (made from the kind) and penetration_m (since 19cf891 a
# contact that reaches no fix takes its penetration from its swept poses too, so it may be
# deeper: reported apart).
loose = {"kind", "label", "penetration_m"}
bad = len(old) != len(new) or ko != kn or geom_diff or any(k not in loose for k in diff) or diff.get("kind", 0)
pd = [(a["properties"]["penetration_m"], b["properties"]["penetration_m"]) for a, b in zip(old_s, new_s)
      if a["properties"]["penetration_m"] != b["properties"]["penetration_m"]]
if pd:
    deeper = sum(1 for x, y in pd if x is not None and y is not None and y > x)
    print(f"penetration_m: {len(pd)} of {sum(1 for f in new if f['properties']['kind'] in CONTACT)} contacts differ, new deeper in {deeper}; "
          f"largest difference {max(abs((y or 0) - (x or 0)) for x, y in pd):.3f} m")
else:
    print("penetration_m: equal on every event")
print("VERDICT:", "SAME EVENTS (count, contact/close, track, start, end, duration, least clearance, point, heading, fix; "
      "penetration as above)" if not bad else "EVENTS DIFFER")
sys.exit(1 if bad else 0)
