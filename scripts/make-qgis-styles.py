#!/usr/bin/python3
"""Regenerates the QGIS layer styles shoal writes beside its reports (src/report/styles/*.qml).

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
                       QgsMarkerSymbol, QgsLineSymbol, QgsFillSymbol, QgsWkbTypes)
from qgis.PyQt.QtGui import QColor, QFont

out_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src", "report", "styles")
app = QgsApplication([], False)
app.initQgis()

MAGENTA, VIOLET = "#c51b7d", "#756bb1"
RED, AMBER, GREEN, GREY = "#e31a1c", "#ff9f00", "#33a02c", "#6a7f95"
BLUE, PURPLE = "#1f78b4", "#6a3d9a"
STEEL = "#4a7fa8"
VIOLET_TRACK = "#8a76b8"  # as in the --plot picture


def labels(field, placement):
    s = QgsPalLayerSettings()
    s.fieldName = field
    s.placement = placement
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
events = QgsVectorLayer("Point?crs=EPSG:4326&field=kind:string&field=hit:string&field=label:string", "events", "memory")
root = QgsRuleBasedRenderer.Rule(None)
for expr, colour, shape, size, label in (
        ("\"kind\" = 'grounding' AND (\"hit\" IS NULL OR \"hit\" NOT IN ('shallow', 'danger'))", RED, "circle", "4.2", "aground on land"),
        ("\"kind\" = 'grounding' AND \"hit\" = 'shallow'", BLUE, "square", "4.0", "aground in shallow water"),
        ("\"kind\" = 'grounding' AND \"hit\" = 'danger'", PURPLE, "star", "5.2", "aground on a danger (rock, wreck, obstruction)"),
        ("\"kind\" = 'alongside'", STEEL, "circle", "2.8", "alongside (stopped or berthing: not a grounding)"),
        ("\"kind\" = 'in_contact_at_start'", GREY, "circle", "2.6", "in contact at the first fix (not seen begin)"),
        ("\"kind\" = 'expected_contact'", GREEN, "circle", "2.6", "contact in a berth, harbour or anchorage area"),
        ("\"kind\" = 'close_pass'", AMBER, "triangle", "4.2", "close pass"),
        # a GeoJSON report holds exercise-mode encounters in the same layer: drawn as in `encounters`
        ("\"kind\" = 'collision'", MAGENTA, "diamond", "4.2", "ship-ship collision"),
        ("\"kind\" = 'close_quarters'", VIOLET, "pentagon", "4.2", "ship-ship close quarters")):
    sym = QgsMarkerSymbol.createSimple({"name": shape, "color": colour, "outline_color": "#000000",
                                        "outline_width": "0.4", "size": size})
    root.appendChild(QgsRuleBasedRenderer.Rule(sym, 0, 0, expr, label))
events.setRenderer(QgsRuleBasedRenderer(root))
events.setLabeling(labels("label", QgsPalLayerSettings.OverPoint))
events.setLabelsEnabled(True)
save(events, "events")

# hulls: the hull footprint at each event, outlined in the event's colour
hulls = QgsVectorLayer("Polygon?crs=EPSG:4326&field=kind:string&field=label:string", "hulls", "memory")
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
encounters = QgsVectorLayer("Point?crs=EPSG:4326&field=kind:string&field=label:string", "encounters", "memory")
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

# tracks: coloured by least clearance (NULL: never within the search limit)
tracks = QgsVectorLayer("MultiLineString?crs=EPSG:4326&field=track:string&field=min_clearance_m:double&field=groundings:integer",
                        "tracks", "memory")
root = QgsRuleBasedRenderer.Rule(None)
for expr, colour, label in (('"groundings" > 0', RED, "aground"),
                            ('"min_clearance_m" = 0', VIOLET_TRACK, "in contact, not a grounding (alongside, at the start, expected)"),
                            ('"min_clearance_m" > 0 AND "min_clearance_m" < 50', AMBER, "closer than 50 m"),
                            ('"min_clearance_m" >= 50 AND "min_clearance_m" < 200', GREEN, "50 to 200 m"),
                            ("ELSE", GREY, "200 m or more")):
    sym = QgsLineSymbol.createSimple({"line_color": colour, "line_width": "0.7"})
    rule = QgsRuleBasedRenderer.Rule(sym, 0, 0, "" if expr == "ELSE" else expr, label)
    if expr == "ELSE":
        rule.setIsElse(True)
    root.appendChild(rule)
tracks.setRenderer(QgsRuleBasedRenderer(root))
tracks.setLabeling(labels("track", QgsPalLayerSettings.Line))
tracks.setLabelsEnabled(True)
save(tracks, "tracks")
app.exitQgis()
