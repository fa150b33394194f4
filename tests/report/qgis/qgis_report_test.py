#!/usr/bin/python3
"""The reports in a real QGIS (Debian's python3-qgis, QGIS 3.22, headless).

Usage: qgis_report_test.py SHOAL_BINARY TEST_DATA_DIR WORK_DIR

Runs `shoal check` on the Solent test coast with two ships, twice: to a GeoPackage, whose
stored project (geopackage:REPORT.gpkg?projectName=shoal) QGIS opens, and to GeoJSON, whose
project REPORT.qgz beside it opens the report and the layer files beside it (REPORT.poses.geojson,
...). For each project, as QGIS opens it, it checks: the layers (valid: their relative sources
resolve) and
their order (coast at the bottom, events on top), their styles, the time fields (DateTime),
the temporal properties of each layer and the project's temporal range (the run), the
project CRS (the UTM zone of the run) and extent; then renders the map at two instants and
checks that the picture changed where the ship was and nowhere far from the ships.
Exits 77 (ctest: skipped) with a message when QGIS cannot be imported.
"""
import os
import subprocess
import sys
import tempfile

shoal, data, work = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(work, exist_ok=True)
os.environ["QT_QPA_PLATFORM"] = "offscreen"
os.environ.setdefault("XDG_RUNTIME_DIR", tempfile.mkdtemp(prefix="xdg-"))
try:
    from qgis.core import (Qgis, QgsApplication, QgsProject, QgsMapSettings, QgsMapRendererParallelJob, QgsDateTimeRange,
                           QgsCoordinateTransform, QgsCoordinateReferenceSystem, QgsPointXY, QgsRectangle,
                           QgsVectorLayerTemporalProperties, QgsVectorLayerTemporalContext, QgsFeatureRequest)
    from qgis.PyQt.QtCore import QDateTime, QSize, Qt, QVariant
    from qgis.PyQt.QtGui import QColor
except ImportError as e:
    print(f"SKIPPED: QGIS's Python bindings cannot be imported ({e}): install python3-qgis (scripts/install-deps.sh)")
    sys.exit(77)

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


# Two ships: A southwards along 1.30 W across the Isle of Wight (aground), B eastwards clear of land.
tracks = os.path.join(work, "solent-tracks.csv")
with open(tracks, "w") as f:
    f.write("mmsi,timestamp,lat,lon,sog,cog,heading\n")
    for i in range(21):
        f.write(f"111111111,2024-05-01T10:{i:02d}:00Z,{50.78 - 0.01 * i:.4f},-1.3000,11.9,180,180\n")
    for i in range(11):
        f.write(f"222222222,2024-05-01T10:{i:02d}:00Z,50.7400,{-1.05 + 0.002 * i:.4f},8,90,90\n")


def run_check(report):
    for stale in (report, report[:-len(".geojson")] + ".qgz"):
        if os.path.exists(stale):
            os.remove(stale)
    run = subprocess.run([shoal, "check", "--world", "simulated", "--coast", os.path.join(data, "coast", "uk_solent_land.geojson"), "--dims", "50,10,5,5",
                          tracks, "-o", report], capture_output=True, text=True)
    check(run.returncode == 1, f"shoal check -o {os.path.basename(report)} exits 1 (a grounding): {run.returncode} {run.stderr.strip()[-300:]}")
    if not os.path.exists(report):
        sys.exit("no report written")


gpkg = os.path.join(work, "solent.gpkg")
run_check(gpkg)
geojson = os.path.join(work, "solent.geojson")
run_check(geojson)
qgz = os.path.join(work, "solent.qgz")
check(os.path.exists(qgz), "a GeoJSON report has its QGIS project solent.qgz beside it")

app = QgsApplication([], False)
app.initQgis()
project = QgsProject.instance()


def check_project(uri, tag):
    """The checks of the module's docstring on the project at `uri`; PNGs named after `tag`."""
    project.clear()
    check(project.read(uri), f"QGIS reads the project {uri}")

    names = [l.name() for l in project.layerTreeRoot().layerOrder()]
    check(names == ["events", "hulls", "poses", "tracks", "coast"], f"layers top to bottom: {names}")
    layers = {l.name(): l for l in project.mapLayers().values()}
    for name, layer in layers.items():
        check(layer.isValid() and layer.featureCount() > 0, f"{name}: valid, {layer.featureCount()} features")
        check(layer.crs().authid() == "EPSG:4326", f"{name}: EPSG:4326 ({layer.crs().authid()})")
    renderers = {n: l.renderer().type() for n, l in layers.items()}
    check(renderers == {"events": "RuleRenderer", "hulls": "categorizedSymbol", "poses": "RuleRenderer", "tracks": "RuleRenderer",
                        "coast": "RuleRenderer"}, f"styles: {renderers}")
    coast_rules = [r.label() for r in layers["coast"].renderer().rootRule().children()]
    check("land" in coast_rules, f"coast style rules: {coast_rules}")

    # Time fields are DateTime; each layer's temporal properties.
    for name, field in (("events", "start"), ("events", "end"), ("tracks", "start"), ("poses", "time"), ("poses", "until"), ("hulls", "start")):
        f = layers[name].fields().field(field)
        check(f.type() == QVariant.DateTime, f"{name}.{field} is a DateTime ({f.typeName()})")
    T = QgsVectorLayerTemporalProperties
    expect = {"events": (T.ModeFeatureDateTimeInstantFromField, "start", None, True),
              "hulls": (T.ModeFeatureDateTimeInstantFromField, "start", None, True),
              "poses": (T.ModeFeatureDateTimeStartAndEndFromFields, "time", "until", False),
              "tracks": (T.ModeFeatureDateTimeStartAndEndFromFields, "start", "end", False)}
    for name, (mode, start, end, acc) in expect.items():
        t = layers[name].temporalProperties()
        ok = t.isActive() and t.mode() == mode and t.startField() == start and (end is None or t.endField() == end) and \
            t.accumulateFeatures() == acc
        check(ok, f"{name}: temporal {t.isActive()} mode {t.mode()} start {t.startField()} end {t.endField()} accumulate {t.accumulateFeatures()}")
    check(not layers["coast"].temporalProperties().isActive(), "coast: always drawn (not temporal)")

    iso = lambda s: QDateTime.fromString(s, Qt.ISODate)
    rng = project.timeSettings().temporalRange()
    check(rng.begin() == iso("2024-05-01T10:00:00Z") and rng.end() == iso("2024-05-01T10:20:00Z"),
          f"project temporal range = the run: {rng.begin().toString(Qt.ISODate)} .. {rng.end().toString(Qt.ISODate)}")
    check(project.crs().authid() == "EPSG:32630", f"project CRS: the UTM zone of the chart ({project.crs().authid()})")
    view = project.viewSettings().defaultViewExtent()
    to_utm = QgsCoordinateTransform(QgsCoordinateReferenceSystem("EPSG:4326"), project.crs(), project)
    for lon, lat in ((-1.3, 50.78), (-1.3, 50.58), (-1.03, 50.74)):
        check(view.contains(to_utm.transform(QgsPointXY(lon, lat))), f"map extent holds the run's fix {lat}, {lon}")

    # Events appear at their time: none shown before the first, all by the end.
    ctx = QgsVectorLayerTemporalContext()
    ctx.setLayer(layers["events"])
    def shown(layer, begin, end):
        c = QgsVectorLayerTemporalContext()
        c.setLayer(layer)
        expr = layer.temporalProperties().createFilterString(c, QgsDateTimeRange(begin, end))
        return sum(1 for _ in layer.getFeatures(QgsFeatureRequest().setFilterExpression(expr)))
    first_event = min(f["start"] for f in layers["events"].getFeatures())
    check(shown(layers["events"], iso("2024-05-01T10:00:00Z"), first_event.addSecs(-1)) == 0, "no event shown before the first")
    check(shown(layers["events"], iso("2024-05-01T10:20:00Z"), iso("2024-05-01T10:20:01Z")) == layers["events"].featureCount(),
          "every event shown at the end of the run")
    check(shown(layers["poses"], iso("2024-05-01T10:02:10Z"), iso("2024-05-01T10:02:20Z")) == 2, "one pose per ship at 10:02:10")


    def render(when, centre, half_m, path):
        ms = QgsMapSettings()
        ms.setLayers(project.layerTreeRoot().layerOrder())
        ms.setDestinationCrs(project.crs())
        ms.setTransformContext(project.transformContext())
        c = to_utm.transform(QgsPointXY(*centre))
        ms.setExtent(QgsRectangle(c.x() - half_m, c.y() - half_m, c.x() + half_m, c.y() + half_m))
        ms.setOutputSize(QSize(400, 400))
        ms.setBackgroundColor(QColor("white"))
        ms.setIsTemporal(True)
        ms.setTemporalRange(QgsDateTimeRange(iso(when), iso(when).addSecs(10)))
        job = QgsMapRendererParallelJob(ms)
        job.start()
        job.waitForFinished()
        img = job.renderedImage()
        img.save(path)
        return img, ms


    def differing(a, b, x0, y0, x1, y1):
        return sum(1 for x in range(x0, x1) for y in range(y0, y1) if a.pixel(x, y) != b.pixel(x, y))


    # 600 m around ship A at 10:02: its hull is there at 10:02:05, gone at 10:15:05.
    a_at = (-1.3, 50.76)
    one, ms = render("2024-05-01T10:02:05Z", a_at, 300, os.path.join(work, f"{tag}-1002.png"))
    two, _ = render("2024-05-01T10:15:05Z", a_at, 300, os.path.join(work, f"{tag}-1015.png"))
    check(one.size() == two.size() and not one.isNull(), "rendered two PNGs")
    centre = ms.mapToPixel().transform(to_utm.transform(QgsPointXY(*a_at)))
    cx, cy = int(centre.x()), int(centre.y())
    near = differing(one, two, cx - 20, cy - 20, cx + 20, cy + 20)
    check(near > 50, f"the picture changed where ship A was at 10:02 ({near} pixels of 1600 near it)")
    corner = differing(one, two, 0, 0, 60, 60) + differing(one, two, 340, 340, 400, 400)
    check(corner == 0, f"and not in the corners, far from the ships ({corner} pixels)")
    # The whole run at its end, for a person to look at.
    render("2024-05-01T10:20:00Z", (-1.17, 50.68), 14000, os.path.join(work, f"{tag}-run.png"))



check_project(f"geopackage:{gpkg}?projectName=shoal", "gpkg")
check_project(qgz, "geojson")
# The GeoJSON project's layers are the files beside the report, by relative path.
sources = sorted(os.path.basename(l.source().split("|")[0]) for l in project.mapLayers().values())
check(sources == ["solent.coast.geojson", "solent.geojson", "solent.hulls.geojson", "solent.poses.geojson", "solent.tracks.geojson"],
      f"the .qgz's layers are the files beside the report: {sources}")
# Each layer file opened alone in QGIS gets its style from the .qml beside it.
from qgis.core import QgsVectorLayer
for name, renderer in (("poses", "RuleRenderer"), ("tracks", "RuleRenderer"), ("hulls", "categorizedSymbol"), ("coast", "RuleRenderer")):
    layer = QgsVectorLayer(os.path.join(work, f"solent.{name}.geojson"), name, "ogr")
    msg, ok = layer.loadDefaultStyle()
    check(layer.isValid() and ok and layer.renderer().type() == renderer, f"solent.{name}.geojson: its style solent.{name}.qml ({msg}, {layer.renderer().type()})")
    del layer  # before exitQgis: a layer that outlives QGIS crashes the interpreter at exit
project.clear()

# A run with no event (ship B alone, clear of land): the report's events and the hulls file are
# empty, and still map layers of their geometry (an empty GeoJSON has no geometry type of its own).
clear_tracks = os.path.join(work, "clear-tracks.csv")
with open(clear_tracks, "w") as f:
    f.write("mmsi,timestamp,lat,lon,sog,cog,heading\n")
    for i in range(11):
        f.write(f"222222222,2024-05-01T10:{i:02d}:00Z,50.7000,{-1.05 + 0.002 * i:.4f},8,90,90\n")
clear = os.path.join(work, "clear.geojson")
run = subprocess.run([shoal, "check", "--world", "simulated", "--coast", os.path.join(data, "coast", "uk_solent_land.geojson"), "--dims", "50,10,5,5",
                      clear_tracks, "-o", clear], capture_output=True, text=True)
check(run.returncode == 0, f"shoal check -o clear.geojson exits 0: {run.returncode} {run.stderr.strip()[-300:]}")
check(project.read(os.path.join(work, "clear.qgz")), "QGIS reads clear.qgz")
layers = {l.name(): l for l in project.mapLayers().values()}
check(sorted(layers) == ["coast", "events", "hulls", "poses", "tracks"] and all(l.isValid() for l in layers.values()),
      f"every layer of clear.qgz is valid: {[(n, l.isValid(), l.featureCount()) for n, l in layers.items()]}")
check(layers["events"].featureCount() == 0 and layers["events"].geometryType() == 0 and layers["hulls"].geometryType() == 2,
      f"no event: events a Point layer ({layers['events'].geometryType()}), hulls a Polygon one ({layers['hulls'].geometryType()}), both empty")
del layers
project.clear()
# The real world (the default outside exercise mode): a ferry calling hourly at one pier teaches
# a learned berth; the `learned` layer is in both projects and opens styled, rule by rule.
helsinki = os.path.join(data, "..", "..", "examples", "data", "gof_helsinki_land.geojson")
ferry = os.path.join(data, "tracks", "ais_cases", "ferry_hourly.csv")
for name in ("ferry.geojson", "ferry.gpkg"):
    out = os.path.join(work, name)
    run = subprocess.run([shoal, "check", "--coast", helsinki, "--dims", "100,20,8,8", ferry, "-o", out], capture_output=True, text=True)
    check(run.returncode == 0, f"shoal check -o {name} (real world) exits 0: {run.returncode} {run.stderr.strip()[-300:]}")
check(project.read(os.path.join(work, "ferry.qgz")), "QGIS reads ferry.qgz")
layers = {l.name(): l for l in project.mapLayers().values()}
learned = layers.get("learned")
check(learned is not None and learned.isValid() and learned.featureCount() >= 1 and learned.geometryType() == 0,
      f"ferry.qgz has a valid Point layer learned with the ferry's berth: {sorted(layers)}")
if learned is not None:
    rules = [r.label() for r in learned.renderer().rootRule().children()] if learned.renderer().type() == "RuleRenderer" else []
    check(any("learned berth" in r for r in rules) and any("water the chart lacks" in r for r in rules),
          f"the learned layer beside the GeoJSON is styled by kind: {rules}")
del layers, learned
project.clear()
gl = QgsVectorLayer(os.path.join(work, "ferry.gpkg") + "|layername=learned", "learned", "ogr")
msg, ok = gl.loadDefaultStyle()
check(gl.isValid() and ok and gl.renderer().type() == "RuleRenderer" and gl.featureCount() >= 1,
      f"the GeoPackage's learned layer loads its style from layer_styles: {ok} {msg} {gl.renderer().type() if gl.renderer() else None}")
del gl
# Issue 39: the project's CRS and extent came from every track, so one vessel off Copenhagen in
# a Solent run put the map in another UTM zone at 1:65 million. They come from the chart now (the
# grid's extent): the Solent coast's box, -1.80..-0.90 E, 50.573..50.95 N (its GeoJSON's extent),
# in UTM 30N, whatever the tracks; and a track wholly outside the chart is drawn "no chart", a
# pose outside it too, never "200 m or more".
far_tracks = os.path.join(work, "far-tracks.csv")
with open(far_tracks, "w") as f:
    f.write("mmsi,timestamp,lat,lon,sog,cog,heading\n")
    for i in range(11):
        f.write(f"222222222,2024-05-01T10:{i:02d}:00Z,50.7400,{-1.05 + 0.002 * i:.4f},8,90,90\n")
    for i in range(11):  # off Copenhagen, 1,000 km from the chart
        f.write(f"333333333,2024-05-01T10:{i:02d}:00Z,55.7000,{12.70 + 0.002 * i:.4f},8,90,90\n")
far = os.path.join(work, "far.gpkg")
if os.path.exists(far):
    os.remove(far)
run = subprocess.run([shoal, "check", "--world", "simulated", "--coast", os.path.join(data, "coast", "uk_solent_land.geojson"), "--dims", "50,10,5,5",
                      far_tracks, "-o", far], capture_output=True, text=True)
check(run.returncode == 0, f"shoal check -o far.gpkg exits 0: {run.returncode} {run.stderr.strip()[-300:]}")
check(project.read(f"geopackage:{far}?projectName=shoal"), "QGIS reads far.gpkg's project")
check(project.crs().authid() == "EPSG:32630", f"far: project CRS the UTM zone of the chart, not of the tracks ({project.crs().authid()})")
view = project.viewSettings().defaultViewExtent()
to_utm = QgsCoordinateTransform(QgsCoordinateReferenceSystem("EPSG:4326"), project.crs(), project)
for lon, lat in ((-1.80, 50.58), (-0.90, 50.95), (-1.80, 50.95), (-0.90, 50.58)):
    check(view.contains(to_utm.transform(QgsPointXY(lon, lat))), f"far: map extent holds the chart's corner {lat}, {lon}")
check(not view.contains(to_utm.transform(QgsPointXY(12.7, 55.7))), "far: map extent leaves out the track off Copenhagen")
check(view.width() < 100000 and view.height() < 100000, f"far: map extent about the chart's 64 x 45 km: {view.width():.0f} x {view.height():.0f} m")
layers = {l.name(): l for l in project.mapLayers().values()}


def rules_of(layer, track):
    """The labels of the rules that draw `track`'s features (the ELSE rule when no other does)."""
    from qgis.core import QgsRenderContext, QgsExpressionContextUtils
    ctx = QgsRenderContext()
    ctx.expressionContext().appendScopes(QgsExpressionContextUtils.globalProjectLayerScopes(layer))
    r = layer.renderer().clone()
    r.startRender(ctx, layer.fields())
    labels = set()
    for feat in layer.getFeatures(QgsFeatureRequest().setFilterExpression(f"\"track\" = '{track}'")):
        ctx.expressionContext().setFeature(feat)
        # rulesForFeature lists the ELSE rule with the others (its filter is empty): as QGIS draws,
        # it applies only when no other rule does.
        rules = r.rootRule().rulesForFeature(feat, ctx)
        others = {rule.label() for rule in rules if not rule.isElse()}
        labels |= others or {rule.label() for rule in rules if rule.isElse()}
    r.stopRender(ctx)
    return labels


far_track = rules_of(layers["tracks"], "333333333")
check(len(far_track) == 1 and next(iter(far_track)).startswith("no chart"), f"far: the track outside the chart is drawn 'no chart': {far_track}")
near_track = rules_of(layers["tracks"], "222222222")
check(near_track == {"200 m or more"}, f"far: the covered track clear of land is '200 m or more': {near_track}")
far_poses = rules_of(layers["poses"], "333333333")
check(len(far_poses) == 1 and next(iter(far_poses)).startswith("no chart"), f"far: its poses are drawn 'no chart': {far_poses}")
check(rules_of(layers["poses"], "222222222") == {"hull"}, "far: the covered track's poses are drawn 'hull'")
del layers
project.clear()
app.exitQgis()
if failures:
    print(f"{len(failures)} checks failed")
    sys.exit(1)
print("all checks passed; PNGs in", work)
