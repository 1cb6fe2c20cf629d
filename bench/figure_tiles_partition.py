#!/usr/bin/python3
"""Figure of docs/tiles-partition.md: a tiled `--partition auto` run drawn over its tile
borders, at print scale, to look for seams.

    /usr/bin/python3 bench/figure_tiles_partition.py OUT_DIR [--tile 800] [--workers 2]
    /usr/bin/python3 bench/figure_tiles_partition.py OUT_DIR --dem chamonix_utm.tif --scale 25000 \
        --tile 3000 --crop 2000 --name chamonix

Runs `rockhatch tiles --partition auto` on a local Dask cluster (the bundled sample at
1:10000 by default) and draws the hatches at their stroke widths (mm on paper), the merged
partition's face borders in light blue and the tile borders in red: on the sample the whole
area at 150 dpi and a crop around the corner where four tiles meet at 600 dpi; on another DEM
a crop at 600 dpi around the largest place where the tiled faces leave rock uncovered or
cover it twice against one whole extraction. SVG rendered to PNG with rsvg-convert.
"""
import argparse
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "build" / "python"))

from osgeo import gdal, ogr  # noqa: E402

from rockhatch import carto, tiles  # noqa: E402

gdal.UseExceptions()
ogr.UseExceptions()


def svg(gpkg, partition, grid, box, scale, path):
    """The hatches, face borders and tile borders inside box (xmin, ymin, xmax, ymax), in mm."""
    x0, y0, x1, y1 = box
    mm = 1000.0 / scale  # paper mm per ground metre

    def pts(g):
        return " ".join(f"{(x - x0) * mm:.3f},{(y1 - y) * mm:.3f}" for x, y in g.GetPoints())

    w, h = (x1 - x0) * mm, (y1 - y0) * mm
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w:.2f}mm" height="{h:.2f}mm" '
           f'viewBox="0 0 {w:.3f} {h:.3f}">', f'<rect width="{w:.3f}" height="{h:.3f}" fill="white"/>']
    clip = ogr.CreateGeometryFromWkt(f"POLYGON(({x0} {y0},{x1} {y0},{x1} {y1},{x0} {y1},{x0} {y0}))")
    ds = ogr.Open(str(partition))
    out.append('<g fill="none" stroke="#7fb2e5" stroke-width="0.25">')
    for f in ds.GetLayerByName("faces"):
        g = f.GetGeometryRef()
        if g.Intersects(clip):
            for k in range(g.GetGeometryCount()):
                out.append(f'<polyline points="{pts(g.GetGeometryRef(k))}"/>')
    out.append("</g>")
    hs = ogr.Open(str(gpkg))
    out.append('<g fill="none" stroke="black" stroke-linecap="round" stroke-linejoin="round">')
    for i in range(hs.GetLayerCount()):
        layer = hs.GetLayer(i)
        layer.SetSpatialFilter(clip)
        for f in layer:
            out.append(f'<polyline stroke-width="{f.GetField("width_mm"):.3f}" points="{pts(f.GetGeometryRef())}"/>')
    out.append("</g>")
    out.append('<g stroke="red" stroke-width="0.3" stroke-dasharray="2,1">')
    for b in grid:
        for x in (b.xmin, b.xmax):
            if x0 < x < x1:
                out.append(f'<line x1="{(x - x0) * mm:.3f}" y1="0" x2="{(x - x0) * mm:.3f}" y2="{h:.3f}"/>')
        for y in (b.ymin, b.ymax):
            if y0 < y < y1:
                out.append(f'<line x1="0" y1="{(y1 - y) * mm:.3f}" x2="{w:.3f}" y2="{(y1 - y) * mm:.3f}"/>')
    out.append("</g></svg>")
    pathlib.Path(path).write_text("\n".join(out))


def render(svg_path, dpi):
    subprocess.run(["rsvg-convert", "--dpi-x", str(dpi), "--dpi-y", str(dpi), "-o", str(svg_path.with_suffix(".png")),
                    str(svg_path)], check=True)
    return svg_path.with_suffix(".png")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out", type=pathlib.Path)
    ap.add_argument("--tile", type=float, default=800)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--dem", type=pathlib.Path, help="a projected DEM instead of the sample; then the figure is "
                    "a crop around the largest place where the tiled partition differs from the whole one")
    ap.add_argument("--scale", type=float, default=10000)
    ap.add_argument("--crop", type=float, default=600, help="side of the crop, ground metres")
    ap.add_argument("--name", default="sample")
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    dem = a.dem or ROOT / "data" / "sample_montblanc" / "dem.tif"
    work = pathlib.Path(tempfile.mkdtemp(prefix="rh_fig_tp_"))
    gpkg = work / "tiled.gpkg"
    tiles.run(dem, "auto", a.tile, [gpkg], scale=a.scale, workers=a.workers, workdir=work / "tiles", keep_tiles=True)
    partition = work / "tiles" / "partition.gpkg"
    info = carto.raster_info(str(dem))
    grid = carto.tile_grid(info, a.tile)
    b = info.bounds()
    made = []
    if a.dem is None:
        full = a.out / f"tiles-partition-{a.name}.svg"
        svg(gpkg, partition, grid, (b.xmin, b.ymin, b.xmax, b.ymax), a.scale, full)
        made.append(render(full, 150))
        # Around the corner where four tiles meet (the north-west one's south-east corner).
        cx, cy = grid[0].xmax, grid[0].ymin
    else:
        whole = work / "whole.gpkg"
        subprocess.run([str(ROOT / "build" / "carto" / "rockhatch"), "partition", "--dem", str(dem), "--scale",
                        str(a.scale), "-o", str(whole), "-q"], check=True)
        places = tiles.partition_difference(whole, partition)["places"]
        for area, x, y in places[:5]:
            print(f"differs over {area:.0f} m2 around {x:.0f}, {y:.0f}")
        _, cx, cy = places[0]
    h = a.crop / 2
    crop = a.out / f"tiles-partition-{a.name}-crop.svg"
    svg(gpkg, partition, grid, (cx - h, cy - h, cx + h, cy + h), a.scale, crop)
    made.append(render(crop, 600))
    print(*made)


if __name__ == "__main__":
    main()
