"""Cut a small S-57 cell from US4MD81M (updates .001-.003 applied by GDAL on reading):
the features of the chosen layers (default LNDARE, COALNE, SLCONS) meeting a lon/lat box,
whole, with exactly the vector primitives (edges, nodes) they use.
Usage: make_s57_cut.py SRC.000 OUT.000 W S E N [LAYER,LAYER,...]"""
import sys
from osgeo import gdal, ogr

gdal.UseExceptions()
gdal.SetConfigOption("OGR_S57_OPTIONS", "RETURN_PRIMITIVES=ON,RETURN_LINKAGES=ON,LNAM_REFS=ON")
src_path, out_path = sys.argv[1], sys.argv[2]
w, s, e, n = map(float, sys.argv[3:7])
layers = sys.argv[7].split(",") if len(sys.argv) > 7 else ["LNDARE", "COALNE", "SLCONS"]
box = ogr.CreateGeometryFromWkt(f"POLYGON(({w} {s},{e} {s},{e} {n},{w} {n},{w} {s}))")
src = ogr.Open(src_path)
EDGE, CNODE, INODE = 130, 120, 110
want = {EDGE: set(), CNODE: set(), INODE: set()}
kept = {}
for name in layers:
    layer = src.GetLayerByName(name)
    kept[name] = []
    for f in layer:
        g = f.GetGeometryRef()
        if g is None or not g.Intersects(box):
            continue
        kept[name].append(f.GetFID())
        for rcnm, rcid in zip(f.GetFieldAsIntegerList("NAME_RCNM"), f.GetFieldAsIntegerList("NAME_RCID")):
            want[rcnm].add(rcid)
for f in src.GetLayerByName("Edge"):
    if f.GetField("RCID") in want[EDGE]:
        for k in ("0", "1"):
            want[f.GetField("NAME_RCNM_" + k)].add(f.GetField("NAME_RCID_" + k))
drv = ogr.GetDriverByName("S57")
out = drv.CreateDataSource(out_path)
for name, rcnm in (("IsolatedNode", INODE), ("ConnectedNode", CNODE), ("Edge", EDGE)):
    ids = sorted(want[rcnm])
    layer = src.GetLayerByName(name)
    olayer = out.GetLayerByName(name)
    for f in layer:
        if f.GetField("RCID") in want[rcnm]:
            o = ogr.Feature(olayer.GetLayerDefn())
            o.SetFrom(f)
            olayer.CreateFeature(o)
for name, fids in kept.items():
    layer = src.GetLayerByName(name)
    olayer = out.GetLayerByName(name)
    for fid in fids:
        f = layer.GetFeature(fid)
        o = ogr.Feature(olayer.GetLayerDefn())
        o.SetFrom(f)
        olayer.CreateFeature(o)
out = None
print({k: len(v) for k, v in kept.items()}, {k: len(v) for k, v in want.items()})
