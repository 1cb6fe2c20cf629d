"""The previews of docs/terrain-styles.md: scree and slope hachures side by side, at print
size (10 pixels per millimetre on paper), on the bundled sample (1:10000) and on a crop of
the shared Chamonix DEM (1:25000, its rock extracted with --partition auto).

    /usr/bin/python3 scripts/terrain_previews.py build/carto/rockhatch docs/

The Chamonix DEM is read in place from ../shared/data/montblanc (skipped when absent).
"""
import pathlib
import subprocess
import sys
import tempfile

import numpy as np
from osgeo import gdal

gdal.UseExceptions()
ROOT = pathlib.Path(__file__).resolve().parents[1]
CHAMONIX = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"
PX_PER_MM = 10


def render(exe, dem, partition, style, scale, ground_width, out, extra=()):
    pixels = int(round(ground_width / scale * 1000 * PX_PER_MM))
    subprocess.run([str(exe), "--dem", str(dem), "--partition", str(partition), "--style", style,
                    "--scale", str(scale), "--png-size", str(pixels), "-q", "--overwrite", "-o", str(out),
                    *extra], check=True)
    return gdal.Open(str(out)).ReadAsArray()


def side_by_side(images, window, out):
    c, r, w, h = window
    gap = np.full((h, 20), 255, np.uint8)
    parts = []
    for i, a in enumerate(images):
        parts += ([gap] if i else []) + [a[r:r + h, c:c + w]]
    row = np.hstack(parts)
    ds = gdal.GetDriverByName("MEM").Create("", row.shape[1], row.shape[0], 1, gdal.GDT_Byte)
    ds.GetRasterBand(1).WriteArray(row)
    gdal.GetDriverByName("PNG").CreateCopy(str(out), ds)
    print(f"{out}: {row.shape[1]} x {row.shape[0]} px")


def main():
    exe, docs = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    sample = ROOT / "data" / "sample_montblanc"
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        imgs = [render(exe, sample / "dem.tif", sample / "partition.gpkg", s, 10000, 2400, tmp / f"{s}.png")
                for s in ("scree", "slope-hachures")]
        # 60 x 45 mm south of the summit: rock, the scree band below it, the open slope.
        side_by_side(imgs, (700, 1750, 600, 450), docs / "terrain-sample.png")
        if CHAMONIX.exists():
            crop = tmp / "chamonix_crop.tif"
            gdal.Translate(str(crop), str(CHAMONIX), srcWin=[300, 250, 200, 200])
            # The drawing covers the DEM reprojected to UTM 32N: its larger side sets the pixels.
            utm = gdal.Warp("", str(crop), format="MEM", dstSRS="EPSG:32632")
            gt = utm.GetGeoTransform()
            side = max(utm.RasterXSize * gt[1], utm.RasterYSize * -gt[5])
            imgs = [render(exe, crop, "auto", s, 25000, side, tmp / f"c_{s}.png", ("--param", "interval=50")
                           if s == "slope-hachures" else ()) for s in ("scree", "slope-hachures")]
            side_by_side(imgs, (500, 500, 600, 450), docs / "terrain-chamonix.png")
        else:
            print(f"{CHAMONIX} is absent: no Chamonix preview")


if __name__ == "__main__":
    main()
