# Writes the seed GeoPackages of fuzz/corpus/partition_raw (small pages, no R-tree):
#   /usr/bin/python3 fuzz/make_partition_seeds.py fuzz/corpus/partition_raw
import os, sqlite3, sys
from osgeo import ogr, osr
ogr.UseExceptions()
def make(path, per_kind=False, orient=False):
    if os.path.exists(path): os.remove(path)
    drv = ogr.GetDriverByName("GPKG")
    ds = drv.CreateDataSource(path)
    srs = osr.SpatialReference(); srs.ImportFromEPSG(2154)
    X0, Y0 = 1004000, 6540000
    fl = ds.CreateLayer("faces", srs, ogr.wkbPolygon, ["SPATIAL_INDEX=NO"])
    fl.CreateField(ogr.FieldDefn("density", ogr.OFTReal))
    fl.CreateField(ogr.FieldDefn("orientation", ogr.OFTReal))
    for i, (x0, x1) in enumerate([(0, 100), (100, 200)]):
        f = ogr.Feature(fl.GetLayerDefn())
        f.SetGeometry(ogr.CreateGeometryFromWkt(f"POLYGON(({X0+x0} {Y0},{X0+x1} {Y0},{X0+x1} {Y0+100},{X0+x0} {Y0+100},{X0+x0} {Y0}))"))
        f.SetField("density", 0.3 + 0.4 * i); f.SetField("orientation", 45.0)
        fl.CreateFeature(f)
    if per_kind:
        for name, x in (("ridges", 100), ("valleys", 50)):
            l = ds.CreateLayer(name, srs, ogr.wkbLineString, ["SPATIAL_INDEX=NO"])
            f = ogr.Feature(l.GetLayerDefn())
            f.SetGeometry(ogr.CreateGeometryFromWkt(f"LINESTRING({X0+x} {Y0},{X0+x} {Y0+100})"))
            l.CreateFeature(f)
    else:
        l = ds.CreateLayer("lines", srs, ogr.wkbLineString, ["SPATIAL_INDEX=NO"])
        l.CreateField(ogr.FieldDefn("kind", ogr.OFTString))
        for x, k in ((100, "ridge"), (50, "valley")):
            f = ogr.Feature(l.GetLayerDefn())
            f.SetGeometry(ogr.CreateGeometryFromWkt(f"LINESTRING({X0+x} {Y0},{X0+x} {Y0+100})"))
            f.SetField("kind", k); l.CreateFeature(f)
    if orient:
        l = ds.CreateLayer("orientation", srs, ogr.wkbLineString, ["SPATIAL_INDEX=NO"])
        f = ogr.Feature(l.GetLayerDefn())
        f.SetGeometry(ogr.CreateGeometryFromWkt(f"LINESTRING({X0+10} {Y0+10},{X0+90} {Y0+90})"))
        l.CreateFeature(f)
    ds = None
    c = sqlite3.connect(path)
    c.execute("PRAGMA page_size=512"); c.execute("VACUUM"); c.close()
make(sys.argv[1] + "/labelled.gpkg")
make(sys.argv[1] + "/per_kind.gpkg", per_kind=True, orient=True)
