#!/usr/bin/python3
"""Regenerates the QGIS layer styles shoal writes beside its reports (src/report/qgis/styles/*.qml).

They are made with QGIS's own API, so that QGIS reads them back as written. Run with Debian's
python3-qgis (QGIS 3.22): QT_QPA_PLATFORM=offscreen /usr/bin/python3 scripts/make-qgis-styles.py
The .qml files are committed; the build embeds them. Field names are the report's (see
schemas/report.schema.json and docs/user-guide.md).
"""
import os
import sys
import tempfile

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("XDG_RUNTIME_DIR", tempfile.mkdtemp(prefix="xdg-"))
from qgis.core import (QgsApplication, QgsVectorLayer, QgsSymbol, QgsRendererCategory,
                       QgsCategorizedSymbolRenderer, QgsRuleBasedRenderer, QgsPalLayerSettings,
                       QgsVectorLayerSimpleLabeling, QgsTextFormat, QgsTextBufferSettings,
                       QgsMarkerSymbol, QgsLineSymbol, QgsFillSymbol, QgsWkbTypes,
                       QgsVectorLayerTemporalProperties, Qgis)
from qgis.PyQt.QtGui import QColor, QFont

out_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src", "report", "qgis", "styles")
app = QgsApplication([], False)
app.initQgis()

MAGENTA, VIOLET = "#c51b7d", "#756bb1"
RED, AMBER, GREEN, GREY = "#e31a1c", "#ff9f00", "#33a02c", "#6a7f95"
BLUE, PURPLE = "#1f78b4", "#6a3d9a"
STEEL = "#4a7fa8"
TEAL = "#17becf"  # the chart disagrees with the traffic, as in the --plot picture
ORANGE_RED = "#d7301f"
VIOLET_TRACK = "#8a76b8"  # as in the --plot picture


# Scales (1:N) that keep a large report quick to draw (docs/performance.md, "The report in
# QGIS: 10,000 tracks"): track labels only when zoomed in closer than 1:50,000, and the hull
# poses only closer than 1:250,000 (a 100 m hull is 0.4 mm there); no layer draws more
# than 2,000 labels.
TRACK_LABELS_SCALE, POSES_SCALE, MAX_LABELS = 50000, 250000, 2000


def labels(field, placement, zoomed_in_from=None):
    """Labels of `field`; with `zoomed_in_from` (a scale 1:N), only at that scale and closer."""
    s = QgsPalLayerSettings()
    s.fieldName = field
    s.placement = placement
    s.limitNumLabels = True
    s.maxNumLabels = MAX_LABELS
    if zoomed_in_from:
        s.scaleVisibility = True
        s.minimumScale = zoomed_in_from  # the most zoomed-out scale at which labels are drawn
        s.maximumScale = 0
    fmt = QgsTextFormat()
    fmt.setFont(QFont("Sans Serif", 9))
    fmt.setSize(9)
    buf = QgsTextBufferSettings()
    buf.setEnabled(True)
    buf.setSize(1)
    buf.setColor(QColor("white"))
    fmt.setBuffer(buf)
    s.setFormat(fmt)
    return QgsVectorLayerSimpleLabeling(s)


def temporal(layer, start, end=None, accumulate=False, end_included=True):
    """The layer's temporal properties, so QGIS's temporal controller plays the run: features
    from `start` to `end` (both included, or the end not with `end_included=False`), or, with no
    end, from `start` on (accumulate) or at `start`."""
    t = layer.temporalProperties()
    t.setIsActive(True)
    t.setStartField(start)
    if end:
        t.setMode(QgsVectorLayerTemporalProperties.ModeFeatureDateTimeStartAndEndFromFields)
        t.setEndField(end)
    else:
        t.setMode(QgsVectorLayerTemporalProperties.ModeFeatureDateTimeInstantFromField)
        t.setAccumulateFeatures(accumulate)
    t.setLimitMode(Qgis.VectorTemporalLimitMode.IncludeBeginIncludeEnd if end_included else Qgis.VectorTemporalLimitMode.IncludeBeginExcludeEnd)


def save(layer, name):
    path = os.path.join(out_dir, name + ".qml")
    msg, ok = layer.saveNamedStyle(path)
    if not ok:
        sys.exit(f"saving {path}: {msg}")
    print("wrote", os.path.relpath(path))


# events: points; groundings red circles on land, blue squares in shallow water, purple stars on
# a danger (rock, wreck, obstruction); contacts that are not groundings small and muted (alongside
# steel blue, in contact at the start grey, in an expected-contact area green); close passes amber
# triangles; labelled with the time
events = QgsVectorLayer("Point?crs=EPSG:4326&field=kind:string&field=hit:string&field=label:string&field=start:datetime&field=end:datetime",
                        "events", "memory")
temporal(events, "start", accumulate=True)  # an event appears at its time and stays
root = QgsRuleBasedRenderer.Rule(None)
for expr, colour, shape, size, label in (
        ("\"kind\" = 'grounding' AND (\"hit\" IS NULL OR \"hit\" NOT IN ('shallow', 'danger', 'structure'))", RED, "circle", "4.2", "aground on land"),
        ("\"kind\" = 'grounding' AND \"hit\" = 'shallow'", BLUE, "square", "4.0", "aground in shallow water"),
        ("\"kind\" = 'grounding' AND \"hit\" IN ('danger', 'structure')", PURPLE, "star", "5.2", "aground on a danger or structure (rock, wreck, obstruction; pier, wharf, pontoon, dolphin, hulk)"),
        ("\"kind\" = 'alongside'", STEEL, "circle", "2.8", "alongside (stopped or berthing: not a grounding)"),
        ("\"kind\" = 'in_contact_at_start'", GREY, "circle", "2.6", "in contact at the first fix (not seen begin)"),
        ("\"kind\" = 'expected_contact'", GREEN, "circle", "2.6", "contact in a berth, harbour or anchorage area"),
        ("\"kind\" = 'close_pass'", AMBER, "triangle", "4.2", "close pass"),
        ("\"kind\" = 'chart_disagrees'", TEAL, "triangle", "2.6", "the chart disagrees with the traffic (sailed through, between fixes: not a grounding)"),
        # a GeoJSON report holds exercise-mode encounters in the same layer: drawn as in `encounters`
        ("\"kind\" = 'collision'", MAGENTA, "diamond", "4.2", "ship-ship collision"),
        ("\"kind\" = 'close_quarters'", VIOLET, "pentagon", "4.2", "ship-ship close quarters"),
        # and --assess breaches: drawn as in `breaches`
        ("\"kind\" = 'breach'", ORANGE_RED, "cross2", "4.6", "assessment breach")):
    sym = QgsMarkerSymbol.createSimple({"name": shape, "color": colour, "outline_color": "#000000",
                                        "outline_width": "0.4", "size": size})
    root.appendChild(QgsRuleBasedRenderer.Rule(sym, 0, 0, expr, label))
events.setRenderer(QgsRuleBasedRenderer(root))
events.setLabeling(labels("label", QgsPalLayerSettings.OverPoint))
events.setLabelsEnabled(True)
save(events, "events")

# hulls: the hull footprint at each event, outlined in the event's colour
hulls = QgsVectorLayer("Polygon?crs=EPSG:4326&field=kind:string&field=label:string&field=start:datetime", "hulls", "memory")
temporal(hulls, "start", accumulate=True)
cats = []
for value, colour, fill, label in (("grounding", RED, "227,26,28,60", "hull aground"),
                                   ("alongside", STEEL, "74,127,168,40", "hull alongside (not a grounding)"),
                                   ("in_contact_at_start", GREY, "106,127,149,40", "hull in contact at the first fix"),
                                   ("expected_contact", GREEN, "51,160,44,40", "hull in an expected-contact area"),
                                   ("close_pass", AMBER, "255,159,0,60", "hull at closest pass"),
                                   ("collision", MAGENTA, "197,27,125,60", "hulls in collision (both ships)"),
                                   ("close_quarters", VIOLET, "117,107,177,60", "hulls at closest quarters (both ships)")):
    sym = QgsFillSymbol.createSimple({"color": fill, "outline_color": colour, "outline_width": "0.6",
                                      "style": "solid"})
    cats.append(QgsRendererCategory(value, sym, label))
hulls.setRenderer(QgsCategorizedSymbolRenderer("kind", cats))
save(hulls, "hulls")

# encounters (exercise mode): ship-to-ship collisions and close quarters, labelled with the time
encounters = QgsVectorLayer("Point?crs=EPSG:4326&field=kind:string&field=label:string&field=start:datetime&field=end:datetime",
                            "encounters", "memory")
temporal(encounters, "start", accumulate=True)
cats = []
for value, colour, shape, label in (("collision", MAGENTA, "diamond", "ship-ship collision"),
                                    ("close_quarters", VIOLET, "pentagon", "ship-ship close quarters")):
    sym = QgsMarkerSymbol.createSimple({"name": shape, "color": colour, "outline_color": "#000000",
                                        "outline_width": "0.4", "size": "4.6"})
    cats.append(QgsRendererCategory(value, sym, label))
encounters.setRenderer(QgsCategorizedSymbolRenderer("kind", cats))
encounters.setLabeling(labels("label", QgsPalLayerSettings.OverPoint))
encounters.setLabelsEnabled(True)
save(encounters, "encounters")

# breaches (--assess): a cross at the worst moment of each breach of a scored criterion,
# labelled with the criterion and the time; shown from its start to its end
breaches = QgsVectorLayer("Point?crs=EPSG:4326&field=criterion:string&field=criterion_kind:string&field=label:string"
                          "&field=start:datetime&field=end:datetime", "breaches", "memory")
temporal(breaches, "start", "end")
sym = QgsMarkerSymbol.createSimple({"name": "cross2", "color": ORANGE_RED, "outline_color": ORANGE_RED,
                                    "outline_width": "0.8", "size": "4.6"})
breaches.setRenderer(QgsCategorizedSymbolRenderer("criterion_kind", [
    QgsRendererCategory(kind, sym.clone(), label) for kind, label in (
        ("land_clearance", "too close to land"), ("under_keel_clearance", "under-keel clearance too small"),
        ("cpa", "CPA too small"), ("speed_limit", "over the speed limit"), ("no_entry", "inside a no-entry area"),
        ("close_quarters_time", "too long in close quarters"))]))
breaches.setLabeling(labels("label", QgsPalLayerSettings.OverPoint))
breaches.setLabelsEnabled(True)
save(breaches, "breaches")

# tracks: coloured by least clearance (NULL: never within the search limit, or no fix on the
# chart); a track with fixes outside the chart and nothing closer than 200 m (every track wholly
# outside it among them) is "no chart" (light grey, dashed), never "200 m or more" (issue 39)
NO_CHART = "#969696"
tracks = QgsVectorLayer("MultiLineString?crs=EPSG:4326&field=track:string&field=min_clearance_m:double&field=groundings:integer"
                        "&field=uncovered_fixes:integer"
                        "&field=start:datetime&field=end:datetime", "tracks", "memory")
temporal(tracks, "start", "end")  # a track is drawn while its vessel is on record
root = QgsRuleBasedRenderer.Rule(None)
for expr, colour, label in (('"groundings" > 0', RED, "aground"),
                            ('"min_clearance_m" = 0', VIOLET_TRACK, "in contact, not a grounding (alongside, at the start, expected)"),
                            ('"min_clearance_m" > 0 AND "min_clearance_m" < 50', AMBER, "closer than 50 m"),
                            ('"min_clearance_m" >= 50 AND "min_clearance_m" < 200', GREEN, "50 to 200 m"),
                            ('coalesce("min_clearance_m", 1e99) >= 200 AND "uncovered_fixes" > 0', NO_CHART,
                             "no chart (all or part of the track outside the chart: not known clear)"),
                            ("ELSE", GREY, "200 m or more")):
    sym = QgsLineSymbol.createSimple({"line_color": colour, "line_width": "0.7"})
    if colour == NO_CHART:
        sym.symbolLayer(0).setUseCustomDashPattern(True)
        sym.symbolLayer(0).setCustomDashVector([1.5, 1.5])
    rule = QgsRuleBasedRenderer.Rule(sym, 0, 0, "" if expr == "ELSE" else expr, label)
    if expr == "ELSE":
        rule.setIsElse(True)
    root.appendChild(rule)
tracks.setRenderer(QgsRuleBasedRenderer(root))
tracks.setLabeling(labels("track", QgsPalLayerSettings.Line, TRACK_LABELS_SCALE))
tracks.setLabelsEnabled(True)
save(tracks, "tracks")

# poses: the hull at each kept fix, from its time until the next kept pose (the temporal
# controller moves the hulls); red in contact, amber within 50 m, else dark slate
poses = QgsVectorLayer("Polygon?crs=EPSG:4326&field=track:string&field=clearance_m:double&field=contact:boolean&field=covered:boolean"
                       "&field=time:datetime&field=until:datetime", "poses", "memory")
root = QgsRuleBasedRenderer.Rule(None)
for expr, fill, colour, label in (('"contact"', "227,26,28,150", RED, "hull in contact"),
                                  ('NOT "covered"', "160,160,160,60", NO_CHART, "no chart (pose outside the chart: not known clear)"),
                                  ('"clearance_m" < 50', "255,159,0,130", AMBER, "hull within 50 m of a hazard"),
                                  ("ELSE", "51,71,91,110", "#33475b", "hull")):
    sym = QgsFillSymbol.createSimple({"color": fill, "outline_color": colour, "outline_width": "0.4", "style": "solid",
                                      "outline_style": "dot" if colour == NO_CHART else "solid"})
    rule = QgsRuleBasedRenderer.Rule(sym, 0, 0, "" if expr == "ELSE" else expr, label)
    if expr == "ELSE":
        rule.setIsElse(True)
    root.appendChild(rule)
poses.setRenderer(QgsRuleBasedRenderer(root))
# A pose holds from its time until the next pose's, which takes over at that instant: the end
# not included, so at a fix's instant the ship is drawn once, not by the pose ending there too.
temporal(poses, "time", "until", end_included=False)
poses.setScaleBasedVisibility(True)
poses.setMinimumScale(POSES_SCALE)  # the most zoomed-out scale at which the layer is drawn
poses.setMaximumScale(0)
save(poses, "poses")

# coast: the chart under the run, coloured as on a paper chart: land buff, drying green,
# shallow water in blues (darker the shallower), dangers purple hatched. Not temporal. No
# outlines: the layer is cut into tiles, and outlined tiles would draw their seams. The depth is
# read with to_real(): beside a GeoJSON report, a coast of land only has depth_m all null,
# which OGR types as text (a filter comparing it with a number would fail in OGR).
coast = QgsVectorLayer("MultiPolygon?crs=EPSG:4326&field=tile:string&field=kind:string&field=danger:string&field=depth_m:double",
                       "coast", "memory")
root = QgsRuleBasedRenderer.Rule(None)
for expr, fill, colour, style, label in (
        ("\"kind\" = 'land'", "#f3e3b5", "#9c8650", "solid", "land"),
        ("\"kind\" = 'shallow' AND to_real(\"depth_m\") < 0", "#b9d3a0", "#6f8f5a", "solid", "dries"),
        ("\"kind\" = 'shallow' AND to_real(\"depth_m\") < 2", "#6fa8d6", "#4a7fa8", "solid", "shallow, under 2 m"),
        ("\"kind\" = 'shallow' AND to_real(\"depth_m\") < 5", "#98c2e4", "#4a7fa8", "solid", "shallow, 2 to 5 m"),
        ("\"kind\" = 'shallow' AND to_real(\"depth_m\") >= 5", "#c3dcf0", "#4a7fa8", "solid", "shallow, 5 m or more (under the limiting depth)"),
        ("\"kind\" = 'shallow'", "#98c2e4", "#4a7fa8", "dense4", "shallow, depth not charted"),
        ("\"kind\" IN ('danger', 'structure')", "#6a3d9a", "#3f1f66", "bdiagonal", "danger (rock, wreck, obstruction) or structure (pier, wharf, pontoon, dolphin, hulk)")):
    sym = QgsFillSymbol.createSimple({"color": fill, "outline_color": colour, "outline_style": "no", "style": style})
    root.appendChild(QgsRuleBasedRenderer.Rule(sym, 0, 0, expr, label))
coast.setRenderer(QgsRuleBasedRenderer(root))
save(coast, "coast")
# learned (--world real): what the run's traffic teaches: places where vessels stay (learned
# berths, blue circles) and cells where vessels under way pass over charted land (water the chart
# lacks, teal squares): a chart correction to open beside the chart. Not temporal.
learned = QgsVectorLayer("Point?crs=EPSG:4326&field=kind:string&field=vessels:integer&field=label:string", "learned", "memory")
root = QgsRuleBasedRenderer.Rule(None)
for expr, colour, shape, size, label in (
        ("\"kind\" = 'learned_berth'", "31,120,180,170", "circle", "4.0", "learned berth: vessels stay here"),
        ("\"kind\" = 'chart_lacks_water'", "23,190,207,150", "square", "3.0", "water the chart lacks: vessels under way on charted land")):
    sym = QgsMarkerSymbol.createSimple({"name": shape, "color": colour, "outline_color": "#0b3c5d", "outline_width": "0.2", "size": size})
    root.appendChild(QgsRuleBasedRenderer.Rule(sym, 0, 0, expr, label))
learned.setRenderer(QgsRuleBasedRenderer(root))
save(learned, "learned")
app.exitQgis()
