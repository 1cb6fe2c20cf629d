#!/usr/bin/python3
"""Benchmark of tiled runs (rockhatch tiles) on a large synthetic area.

The area is made with the sample generator: rh_make_sample writes one massif (the bundled
sample's, 2.4 km square at 5 m), and a VRT mosaic repeats it on a grid to cover SIZE x SIZE
metres (GDAL reads the mosaic window by window, as it would a national mosaic of many files);
the partition is the massif's faces and lines translated to every copy. Nothing is written
into the repository but the Markdown table.

    /usr/bin/python3 bench/bench_tiles.py --size 20000 --workers 1 2 [--markdown FILE]

Per run: tiles, faces, hatches, wall time, tiles/s, hatches/s, and the peak resident memory
of a worker process (its ru_maxrss, the whole process: the Python interpreter and the
module included).
"""
import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time
from xml.sax.saxutils import escape

ROOT = pathlib.Path(__file__).resolve().parents[1]
BUILD = pathlib.Path(os.environ.get("RH_BUILD_DIR", ROOT / "build"))
sys.path.insert(0, str(BUILD / "python"))

from osgeo import gdal, ogr  # noqa: E402

gdal.UseExceptions()
ogr.UseExceptions()

MASSIF = 2400.0  # metres: the generator's default square


def make_area(work, size):
    """DEM (VRT mosaic) and partition covering size x size metres; returns their paths."""
    src = work / "massif"
    subprocess.run([str(BUILD / "carto" / "rh_make_sample"), "-o", str(src), "--overwrite"], check=True,
                   stdout=subprocess.DEVNULL)
    n = int(round(size / MASSIF))
    dem = gdal.Open(str(src / "dem.tif"))
    gt = dem.GetGeoTransform()
    w, h = dem.RasterXSize, dem.RasterYSize
    band = dem.GetRasterBand(1)
    nodata = band.GetNoDataValue()
    srs = dem.GetProjectionRef()
    # The mosaic: one simple source per copy (the same file, placed on a grid).
    lines = [f'<VRTDataset rasterXSize="{w * n}" rasterYSize="{h * n}">',
             f"  <SRS>{escape(srs)}</SRS>",
             f"  <GeoTransform>{gt[0]}, {gt[1]}, 0, {gt[3]}, 0, {gt[5]}</GeoTransform>",
             '  <VRTRasterBand dataType="Float32" band="1">',
             f"    <NoDataValue>{nodata}</NoDataValue>"]
    for j in range(n):
        for i in range(n):
            lines += ["    <SimpleSource>",
                      f'      <SourceFilename relativeToVRT="0">{src / "dem.tif"}</SourceFilename>',
                      "      <SourceBand>1</SourceBand>",
                      f'      <SrcRect xOff="0" yOff="0" xSize="{w}" ySize="{h}"/>',
                      f'      <DstRect xOff="{i * w}" yOff="{j * h}" xSize="{w}" ySize="{h}"/>',
                      "    </SimpleSource>"]
    lines += ["  </VRTRasterBand>", "</VRTDataset>"]
    vrt = work / "mosaic.vrt"
    vrt.write_text("\n".join(lines) + "\n")
    # The partition: every feature of every layer, translated to each copy.
    sp = ogr.Open(str(src / "partition.gpkg"))
    out = ogr.GetDriverByName("GPKG").CreateDataSource(str(work / "faces.gpkg"))
    for k in range(sp.GetLayerCount()):
        lin = sp.GetLayer(k)
        lout = out.CreateLayer(lin.GetName(), lin.GetSpatialRef(), lin.GetGeomType())
        d = lin.GetLayerDefn()
        for f in range(d.GetFieldCount()):
            lout.CreateField(d.GetFieldDefn(f))
        lout.StartTransaction()
        for j in range(n):
            for i in range(n):
                lin.ResetReading()
                for feat in lin:
                    g = feat.GetGeometryRef().Clone()
                    _translate(g, i * w * gt[1], j * h * gt[5])
                    nf = ogr.Feature(lout.GetLayerDefn())
                    for f in range(d.GetFieldCount()):
                        nf.SetField(f, feat.GetField(f))
                    nf.SetGeometry(g)
                    lout.CreateFeature(nf)
        lout.CommitTransaction()
    out = None
    return vrt, work / "faces.gpkg", n


def _translate(g, dx, dy):
    if g.GetGeometryCount():
        for k in range(g.GetGeometryCount()):
            _translate(g.GetGeometryRef(k), dx, dy)
        return
    for p in range(g.GetPointCount()):
        x, y = g.GetX(p), g.GetY(p)
        g.SetPoint_2D(p, x + dx, y + dy)


def run(vrt, faces, work, tile, workers, scale):
    from rockhatch import tiles

    out = work / f"out_{workers}.gpkg"
    if out.exists():
        out.unlink()
    t0 = time.monotonic()
    s = tiles.run(vrt, faces, tile, [out], scale=scale, workers=workers, restart=True)
    wall = time.monotonic() - t0
    return {"workers": workers, "tiles": s.tiles, "faces": s.faces, "hatches": s.hatches, "wall": wall,
            "tiles_s": s.tiles / wall, "hatches_s": s.hatches / wall, "peak_mb": s.peak_mb,
            "tile_median": sorted(s.tile_seconds)[len(s.tile_seconds) // 2] if s.tile_seconds else 0,
            "merge": s.merge_seconds}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=float, default=20000, help="side of the area (metres)")
    ap.add_argument("--tile", type=float, default=5000, help="tile side (metres)")
    ap.add_argument("--scale", type=float, default=25000)
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--markdown", help="append the table to this file")
    ap.add_argument("--keep", help="keep the work folder here")
    a = ap.parse_args()
    work = pathlib.Path(a.keep or tempfile.mkdtemp(prefix="rh_bench_tiles_"))
    work.mkdir(parents=True, exist_ok=True)
    try:
        t0 = time.monotonic()
        vrt, faces, n = make_area(work, a.size)
        made = time.monotonic() - t0
        side = n * MASSIF / 1000
        rows = [run(vrt, faces, work, a.tile, w, a.scale) for w in a.workers]
        head = (f"Area {side:g} km x {side:g} km at 5 m ({n}x{n} copies of the generated massif, a VRT mosaic of "
                f"{n * n} sources; made in {made:.0f} s), tiles of {a.tile / 1000:g} km, 1:{a.scale:g}, "
                f"{os.cpu_count()} cores.")
        table = [head, "",
                 "| workers | tiles | faces | hatches | wall (s) | tiles/s | hatches/s | median tile (s) | merge (s) | peak per worker (MB) |",
                 "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
        for r in rows:
            table.append(f"| {r['workers']} | {r['tiles']} | {r['faces']} | {r['hatches']} | {r['wall']:.1f} | "
                         f"{r['tiles_s']:.3f} | {r['hatches_s']:.0f} | {r['tile_median']:.2f} | {r['merge']:.1f} | {r['peak_mb']:.0f} |")
        text = "\n".join(table) + "\n"
        print(text)
        if a.markdown:
            with open(a.markdown, "a") as f:
                f.write(text + "\n")
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
