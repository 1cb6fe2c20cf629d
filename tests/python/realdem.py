"""A partition for the real DEM: a grid of square faces over its steep blocks.

Shared by the tests and bench/bench_carto.py; the DEM itself stays in ../shared.
"""
import numpy as np
from osgeo import gdal, ogr, osr

gdal.UseExceptions()
ogr.UseExceptions()


def grid_partition(dem_path, out_path, min_slope=90.0, step=16):
    """Writes faces (EPSG:4326) over the step x step cell blocks whose mean slope (percent)
    reaches min_slope and that hold no NoData, plus one "other" line; returns the count."""
    ds = gdal.Open(str(dem_path))
    gt = ds.GetGeoTransform()
    band = ds.GetRasterBand(1)
    a = band.ReadAsArray().astype(float)
    a[a == band.GetNoDataValue()] = np.nan
    # Ground cell sizes of a 1 arc-second grid at 45.9 N.
    gy, gx = np.gradient(a, 30.9, 21.5)
    slope = np.hypot(gx, gy) * 100
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(4326)
    out = ogr.GetDriverByName("GPKG").CreateDataSource(str(out_path))
    faces = out.CreateLayer("faces", srs, ogr.wkbPolygon)
    lines = out.CreateLayer("lines", srs, ogr.wkbLineString)
    lines.CreateField(ogr.FieldDefn("kind", ogr.OFTString))
    n = 0
    for r in range(0, a.shape[0] - step, step):
        for c in range(0, a.shape[1] - step, step):
            block = slope[r:r + step, c:c + step]
            if np.isnan(block).any() or np.nanmean(block) < min_slope:
                continue
            x0, y0 = gt[0] + c * gt[1], gt[3] + r * gt[5]
            x1, y1 = x0 + step * gt[1], y0 + step * gt[5]
            f = ogr.Feature(faces.GetLayerDefn())
            f.SetGeometry(ogr.CreateGeometryFromWkt(f"POLYGON(({x0} {y0},{x1} {y0},{x1} {y1},{x0} {y1},{x0} {y0}))"))
            faces.CreateFeature(f)
            n += 1
    mid = gt[0] + a.shape[1] / 2 * gt[1]
    f = ogr.Feature(lines.GetLayerDefn())
    f.SetField("kind", "ridge")
    f.SetGeometry(ogr.CreateGeometryFromWkt(f"LINESTRING({mid} 45.85,{mid} 45.95)"))
    lines.CreateFeature(f)
    out = None
    return n
