"""Cut a small S-57 cell from a NOAA ENC (its updates .001, .002, ... beside it are applied by
GDAL's S57 driver on reading): the features of the chosen layers that meet a lon/lat box,
whole, with exactly the vector primitives (edges, connected and isolated nodes) they use,
written with GDAL's S-57 writer. Each kept feature read back from the cut is then compared
with the original (matched on LNAM): same geometry (OGR Equals) and same attributes; the
script fails when one differs.

Usage: make_s57_cut.py SRC.000 OUT.000 W S E N [LAYER[:WHERE],LAYER[:WHERE],...]

LAYER is an S-57 object class (default LNDARE, COALNE, SLCONS); WHERE an optional OGR
attribute filter that the layer's features must pass as well, e.g. "DEPARE:DRVAL1 < 9".
Point objects (MORFAC dolphins, UWTROC rocks) use isolated nodes and need no edges.
Run with Debian's /usr/bin/python3 (python3-gdal)."""
import sys
from osgeo import gdal, ogr

gdal.UseExceptions()
PRIMITIVES = "RETURN_PRIMITIVES=ON,RETURN_LINKAGES=ON,LNAM_REFS=ON"
EDGE, CNODE, INODE = 130, 120, 110


def parse_layers(arg):
    out = []
    for spec in arg.split(","):
        name, _, where = spec.partition(":")
        out.append((name.strip(), where.strip()))
    return out


def cut(src_path, out_path, box, layers):
    # Text is copied as the chart holds it (ISO 8859-1 at lexical level 1): recoded to UTF-8
    # on reading, the writer would store the UTF-8 bytes, and a degree sign would read back
    # as "Â°".
    gdal.SetConfigOption("OGR_S57_OPTIONS", PRIMITIVES + ",RECODE_BY_DSSI=OFF")
    src = ogr.Open(src_path)
    want = {EDGE: set(), CNODE: set(), INODE: set()}
    kept = {}
    for name, where in layers:
        layer = src.GetLayerByName(name)
        if layer is None:
            sys.exit(f"{src_path} has no layer {name}")
        layer.SetAttributeFilter(where or None)
        kept[name] = []
        for f in layer:
            g = f.GetGeometryRef()
            if g is None or not g.Intersects(box):
                continue
            kept[name].append(f.GetFID())
            for rcnm, rcid in zip(f.GetFieldAsIntegerList("NAME_RCNM"), f.GetFieldAsIntegerList("NAME_RCID")):
                want[rcnm].add(rcid)
        layer.SetAttributeFilter(None)
    for f in src.GetLayerByName("Edge"):
        if f.GetField("RCID") in want[EDGE]:
            for k in ("0", "1"):
                want[f.GetField("NAME_RCNM_" + k)].add(f.GetField("NAME_RCID_" + k))
    drv = ogr.GetDriverByName("S57")
    # The cell's compilation scale (DSPM CSCALE) is kept: it is the chart's positional
    # tolerance (shoal check reads it); GDAL's writer would put its default, 1:52,000.
    dsid = src.GetLayerByName("DSID").GetNextFeature()
    out = drv.CreateDataSource(out_path, options=["S57_CSCL=%d" % dsid.GetField("DSPM_CSCL")])
    for name, rcnm in (("IsolatedNode", INODE), ("ConnectedNode", CNODE), ("Edge", EDGE)):
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
    return kept, want


def attributes(f, skip=("RCID", "RVER", "NAME_RCNM", "NAME_RCID", "ORNT", "USAG", "MASK", "FFPT_RIND")):
    """The feature's attributes, without the record bookkeeping the writer renews (record id and
    version: a feature an update changed is written as a new record of version 1; its spatial
    references, compared through the geometry)."""
    return {f.GetFieldDefnRef(i).GetName(): f.GetField(i) for i in range(f.GetFieldCount())
            if f.GetFieldDefnRef(i).GetName() not in skip}


def verify(src_path, out_path, kept):
    """Every kept feature, read back from the cut, equals the original (geometry and attributes)."""
    gdal.SetConfigOption("OGR_S57_OPTIONS", PRIMITIVES + ",RECODE_BY_DSSI=ON")
    src, back = ogr.Open(src_path), ogr.Open(out_path)
    bad = 0
    for name, fids in kept.items():
        if not fids:
            continue  # the S-57 reader lists only the classes a cell holds
        by_lnam = {f.GetField("LNAM"): f for f in back.GetLayerByName(name)}
        if len(by_lnam) != len(fids):
            print(f"{name}: {len(fids)} features kept, {len(by_lnam)} read back", file=sys.stderr)
            bad += 1
        layer = src.GetLayerByName(name)
        for fid in fids:
            f = layer.GetFeature(fid)
            o = by_lnam.get(f.GetField("LNAM"))
            g, h = f.GetGeometryRef(), o.GetGeometryRef() if o else None
            if o is None or (g is None) != (h is None) or (g is not None and not g.Equals(h)) or attributes(f) != attributes(o):
                print(f"{name} {f.GetField('LNAM')}: differs in the cut", file=sys.stderr)
                bad += 1
    if bad:
        sys.exit(f"{bad} features differ")


def main():
    src_path, out_path = sys.argv[1], sys.argv[2]
    w, s, e, n = map(float, sys.argv[3:7])
    layers = parse_layers(sys.argv[7]) if len(sys.argv) > 7 else [("LNDARE", ""), ("COALNE", ""), ("SLCONS", "")]
    box = ogr.CreateGeometryFromWkt(f"POLYGON(({w} {s},{e} {s},{e} {n},{w} {n},{w} {s}))")
    kept, want = cut(src_path, out_path, box, layers)
    verify(src_path, out_path, kept)
    print({k: len(v) for k, v in kept.items()}, {k: len(v) for k, v in want.items()}, "verified")


if __name__ == "__main__":
    main()
