#!/usr/bin/env python3
"""Crops of the drawing at true print scale, for docs/print.md: the sample and
../shared/data/montblanc/Chamonix.tif and ../shared/data/nordkette/nordkette_5m.tif at 1:10000, 1:25000 and 1:50000, each a square of SIZE mm on
paper around the same ground point, rendered at 300 dpi (rsvg-convert) so that one pixel
is 1/300 inch on paper when the PNG is printed at 300 dpi.

    /usr/bin/python3 bench/print_crops.py BUILD_DIR OUT_DIR [--style print] [--size 60] [--scales 10000 25000 50000]
    /usr/bin/python3 bench/print_crops.py BUILD_DIR docs --compare print,rock --scales 10000 25000 --size 60
    /usr/bin/python3 bench/print_crops.py BUILD_DIR docs --compare rock:band_height=1000:band_ragged=0,rock --name rows

--compare A,B also writes OUT_DIR/B-CASE.png per case: the two styles side by side (A left,
B right), one row per scale (the figures of docs/rock.md).

Only the faces centred near the crop are hatched (--window), so a large DEM stays quick.
"""
import argparse
import pathlib
import re
import subprocess
import sys

from PIL import Image, ImageOps

ROOT = pathlib.Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "data" / "sample_montblanc"
SHARED_DEM = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"
NORDKETTE = ROOT.parent / "shared" / "data" / "nordkette" / "nordkette_5m.tif"
DPI = 300
# Ground points the crops are centred on (working CRS): the sample's summit, and the
# steepest 1.5 km square of Chamonix.tif (72% of it over 90% slope; UTM 32N).
CASES = {
    "sample": (SAMPLE / "dem.tif", SAMPLE / "partition.gpkg", (1004100.0, 6539900.0)),
    "chamonix": (SHARED_DEM, "auto", (343730.0, 5081360.0)),
    # The Nordkette's crest, its cliff bands and couloirs (MGI / Austria Lambert).
    "nordkette": (NORDKETTE, "auto", (256250.0, 380950.0)),
}


def crop(exe, case, scale, style, size_mm, out_png, tmp):
    dem, partition, (cx, cy) = CASES[case]
    half = size_mm / 2 * scale / 1000.0  # ground units
    margin = half * 1.5  # faces centred this far out still reach into the crop
    svg = tmp / f"{case}-{scale}-{style.replace(':', '-')}.svg"
    name, *params = style.split(":")  # a style and its parameters: rock:band_height=100
    cmd = [str(exe), "--dem", str(dem), "--partition", str(partition), "--style", name, "--scale", str(scale),
           "--window", f"{cx - half - margin},{cy - half - margin},{cx + half + margin},{cy + half + margin}",
           "-q", "--overwrite", "-o", str(svg)] + [a for kv in params for a in ("--param", kv)]
    subprocess.run(cmd, check=True)
    text = svg.read_text()
    geo = re.search(r'xmin="([-\d.e+]+)" ymin="([-\d.e+]+)" xmax="([-\d.e+]+)" ymax="([-\d.e+]+)"', text)
    xmin, ymin, xmax, ymax = map(float, geo.groups())
    png = tmp / (svg.stem + ".png")
    subprocess.run(["rsvg-convert", "--dpi-x", str(DPI), "--dpi-y", str(DPI), "-b", "white", str(svg), "-o", str(png)],
                   check=True)
    im = Image.open(png)
    px_per_ground = im.size[0] / (xmax - xmin)
    left = (cx - half - xmin) * px_per_ground
    top = (ymax - (cy + half)) * px_per_ground
    side = 2 * half * px_per_ground
    # One bit per pixel, as a printer lays ink (rsvg-convert's anti-aliasing thresholded at half grey).
    # Paper beyond the drawing's extent is white (a crop larger than the DEM, e.g. at 1:50000).
    pad = round(side) + 1
    im = ImageOps.expand(im.convert("L"), border=pad, fill=255)
    im = im.crop((round(left) + pad, round(top) + pad, round(left + side) + pad, round(top + side) + pad))
    im.point(lambda v: 255 if v >= 128 else 0).convert("1").save(out_png, optimize=True)
    print(f"{out_png}: 1:{scale} {case}, {size_mm} mm square at {DPI} dpi")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build", type=pathlib.Path)
    ap.add_argument("out", type=pathlib.Path)
    ap.add_argument("--style", default="print")
    ap.add_argument("--size", type=float, default=60.0)
    ap.add_argument("--tmp", type=pathlib.Path, default=pathlib.Path("/tmp"))
    ap.add_argument("--scales", type=int, nargs="+", default=[10000, 25000, 50000],
                    help="scale denominators (default: 10000 25000 50000)")
    ap.add_argument("--cases", nargs="+", default=list(CASES), help="cases (default: all)")
    ap.add_argument("--compare", metavar="A,B",
                    help="two styles side by side, a row per scale; a style may carry parameters: rock:band_height=1.5")
    ap.add_argument("--name", help="the side-by-side figure is OUT/NAME-CASE.png (default: the second style's name)")
    args = ap.parse_args()
    exe = args.build / "carto" / "rockhatch"
    styles = args.compare.split(",") if args.compare else [args.style]
    for case in args.cases:
        if not CASES[case][0].exists():
            print(f"print_crops: {CASES[case][0]} absent, {case} skipped")
            continue
        crops = {}
        for scale in args.scales:
            for style in styles:
                out = (args.tmp if args.compare else args.out) / f"print-{case}-{scale}-{style.replace(':', '-')}.png"
                crop(exe, case, scale, style, args.size, out, args.tmp)
                crops[scale, style] = out
        if args.compare:
            side_by_side(crops, args.scales, styles, args.out / f"{args.name or styles[-1]}-{case}.png")


def side_by_side(crops, scales, styles, out, gap=20):
    """The crops in a grid, one row per scale, one column per style, on white paper."""
    tiles = [[Image.open(crops[scale, style]) for style in styles] for scale in scales]
    w, h = tiles[0][0].size
    sheet = Image.new("1", (len(styles) * w + (len(styles) - 1) * gap, len(scales) * h + (len(scales) - 1) * gap), 1)
    for i, row in enumerate(tiles):
        for j, im in enumerate(row):
            sheet.paste(im, (j * (w + gap), i * (h + gap)))
    sheet.save(out, optimize=True)
    print(f"{out}: {' | '.join(styles)}, rows 1:{', 1:'.join(str(s) for s in scales)}")


if __name__ == "__main__":
    sys.exit(main())
