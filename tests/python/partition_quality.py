"""Precision and recall of extracted ridge and thalweg lines against the synthetic sample's
true lines (data/sample_montblanc/truth.gpkg), shared by the tests and bench/bench_carto.py.

Measured where the generator knows the truth: inside the extracted rock mask and inside the
convex hull of the true lines (they stop 1200 m from the summit, the DEM's corners go on).
Precision: share of the extracted length there within `tol` of a true line of its kind;
recall: share of the true length there within `tol` of an extracted line of that kind.
"""
from osgeo import ogr

ogr.UseExceptions()

TRUE_LAYERS = {"ridge": "ridges", "valley": "thalwegs"}


def _lines(layer, where=None):
    if where:
        layer.SetAttributeFilter(where)
    out = ogr.Geometry(ogr.wkbMultiLineString)
    for f in layer:
        out.AddGeometry(f.GetGeometryRef())
    return out


def precision_recall(partition_gpkg, truth_gpkg, layer="network", tol=10.0):
    """{kind: (precision, recall, extracted metres, true metres)} for ridge and valley."""
    out_ds, truth_ds = ogr.Open(str(partition_gpkg)), ogr.Open(str(truth_gpkg))
    mask_feature = out_ds.GetLayerByName("mask").GetNextFeature()
    mask = mask_feature.GetGeometryRef().Clone()
    everything = ogr.Geometry(ogr.wkbMultiLineString)
    for name in TRUE_LAYERS.values():
        for g in _lines(truth_ds.GetLayerByName(name)):
            everything.AddGeometry(g)
    zone = mask.Intersection(everything.ConvexHull())
    result = {}
    for kind, name in TRUE_LAYERS.items():
        extracted = _lines(out_ds.GetLayerByName(layer), f"kind = '{kind}'").Intersection(zone)
        truth = _lines(truth_ds.GetLayerByName(name))
        truth_in = truth.Intersection(zone)
        p = extracted.Intersection(truth.Buffer(tol)).Length() / max(extracted.Length(), 1e-9)
        r = truth_in.Intersection(extracted.Buffer(tol)).Length() / max(truth_in.Length(), 1e-9)
        result[kind] = (p, r, extracted.Length(), truth_in.Length())
    return result
