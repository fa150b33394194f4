#!/usr/bin/python3
"""Times, for docs/performance.md, QgsProject.read of a shoal report's project and a first render of the whole map (the
project's extent) at the run's middle instant, 1200 x 900, every layer; then a render zoomed
in at 1:40,000 on the map's centre. Headless (QT_QPA_PLATFORM=offscreen).
Usage: scripts/qgis-time.py PROJECT [--unscaled] [--png PREFIX]
PROJECT: geopackage:REPORT.gpkg?projectName=shoal, or REPORT.qgz.
--unscaled: as the styles were before: poses drawn at every scale, track labels at every scale."""
import os, sys, tempfile, time
os.environ["QT_QPA_PLATFORM"] = "offscreen"
os.environ.setdefault("XDG_RUNTIME_DIR", tempfile.mkdtemp(prefix="xdg-"))
from qgis.core import QgsApplication, QgsProject, QgsMapSettings, QgsMapRendererParallelJob, QgsDateTimeRange, QgsRectangle
from qgis.PyQt.QtCore import QSize
from qgis.PyQt.QtGui import QColor
args = sys.argv[1:]
unscaled = "--unscaled" in args
png = args[args.index("--png") + 1] if "--png" in args else None
app = QgsApplication([], False)
app.initQgis()
p = QgsProject.instance()
t0 = time.monotonic()
ok = p.read(args[0])
t1 = time.monotonic()
print(f"read {ok} {t1 - t0:.2f} s, layers {[l.name() for l in p.layerTreeRoot().layerOrder()]}", flush=True)
layers = {l.name(): l for l in p.mapLayers().values()}
if unscaled:
    layers["poses"].setScaleBasedVisibility(False)
    s = layers["tracks"].labeling().settings()
    s.scaleVisibility = False
    s.limitNumLabels = False
    layers["tracks"].labeling().setSettings(s)
r = p.timeSettings().temporalRange()
mid = r.begin().addSecs(r.begin().secsTo(r.end()) // 2)


def render(extent, tag):
    ms = QgsMapSettings()
    ms.setLayers(p.layerTreeRoot().layerOrder())
    ms.setDestinationCrs(p.crs())
    ms.setTransformContext(p.transformContext())
    ms.setOutputSize(QSize(1200, 900))
    ms.setExtent(extent)
    ms.setBackgroundColor(QColor("white"))
    ms.setIsTemporal(True)
    ms.setTemporalRange(QgsDateTimeRange(mid, mid.addSecs(60)))
    t2 = time.monotonic()
    job = QgsMapRendererParallelJob(ms)
    job.start()
    job.waitForFinished()
    t3 = time.monotonic()
    print(f"{tag}: render {t3 - t2:.2f} s at 1:{ms.scale():.0f}", flush=True)
    if png:
        job.renderedImage().save(f"{png}-{tag}.png")
    return ms


whole = render(p.viewSettings().defaultViewExtent(), "whole map")
c = whole.extent().center()
half_w = 40000 * 1200 * 0.0254 / 96 / 2  # 1:40,000 at 96 dpi
render(QgsRectangle(c.x() - half_w, c.y() - half_w * 0.75, c.x() + half_w, c.y() + half_w * 0.75), "zoomed in")
app.exitQgis()
