#!/usr/bin/env python3
"""Draws the crest-ornament figures of docs/synthesis.md at print scale: the project's
exemplar, the bundled sample and a window of the Chamonix DEM in ../shared (when present),
each run through the rockhatch command and its SVG rendered at 300 dpi (rsvg-convert), so
that one pixel of the PNG is one printer dot at the map scale.

usage: /usr/bin/python3 scripts/crest_figures.py [BUILD_DIR]   (default: build)
"""
import pathlib
import re
import subprocess
import sys
import tempfile

from PIL import Image, ImageDraw

ROOT = pathlib.Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "data" / "sample_montblanc"
CHAMONIX = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"
DOCS = ROOT / "docs"
DPI = 300
# A window of Chamonix.tif (UTM 32N) around a few ridges of its automatic partition.
CHAMONIX_WINDOW = "332000,5087500,333800,5089300"


def rockhatch(build, out, *args):
    subprocess.run([str(build / "carto" / "rockhatch"), "-q", "--overwrite", *map(str, args), "-o", str(out)],
                   check=True)


def render(svg, png, *size):
    subprocess.run(["rsvg-convert", "--dpi-x", str(DPI), "--dpi-y", str(DPI), *size, "-b", "white", str(svg), "-o",
                    str(png)], check=True)
    return Image.open(png).convert("L")


def crest_only(svg, out):
    """The drawing with its hatch groups removed: the crest group alone, same frame."""
    text = re.sub(r'<g id="(fill|ridge|valley|cross)".*?</g>\n', "", svg.read_text(), flags=re.S)
    out.write_text(text)
    return out


def side_by_side(images, labels, gap=24):
    """The images in a row, each with its label above it."""
    head = 34
    w = sum(i.width for i in images) + gap * (len(images) - 1)
    h = max(i.height for i in images) + head
    out = Image.new("L", (w, h), 255)
    draw = ImageDraw.Draw(out)
    x = 0
    for im, label in zip(images, labels):
        draw.text((x + 4, 8), label, fill=0)
        out.paste(im, (x, head))
        x += im.width + gap
    return out


def crop_mm(im, left_mm, top_mm, size_mm):
    px = DPI / 25.4
    x, y, s = int(left_mm * px), int(top_mm * px), int(size_mm * px)
    return im.crop((x, y, x + s, y + s))


def main():
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build")
    sys.path.insert(0, str(build / "python"))
    from rockhatch import carto
    with tempfile.TemporaryDirectory() as d:
        tmp = pathlib.Path(d)
        # The exemplar, 600 x 100 units, drawn 150 mm wide.
        (tmp / "exemplar.svg").write_text(carto.default_crest_svg())
        ex = render(tmp / "exemplar.svg", tmp / "exemplar.png", "-w", "1200")
        ex.save(DOCS / "crest-exemplar.png")
        print(f"crest-exemplar.png {ex.size}")

        # The sample at 1:10000: the default style with crests 2 mm high, and crests alone at
        # 2 and 3 mm, over the same 60 mm square (north-east ridge and the summit).
        common = ["--dem", SAMPLE / "dem.tif", "--partition", SAMPLE / "partition.gpkg"]
        rockhatch(build, tmp / "s2.svg", *common, "--crest-ornament", "default")
        rockhatch(build, tmp / "s3.svg", *common, "--crest-ornament", "default", "--crest-height", "3")
        crops = [crop_mm(render(tmp / "s2.svg", tmp / "s2.png"), 115, 60, 60),
                 crop_mm(render(crest_only(tmp / "s2.svg", tmp / "s2c.svg"), tmp / "s2c.png"), 115, 60, 60),
                 crop_mm(render(tmp / "s3.svg", tmp / "s3.png"), 115, 60, 60)]
        fig = side_by_side(crops, ["sample 1:10000, bidirectional + crest 2 mm", "the crest layer alone",
                                   "crest 3 mm"])
        fig.save(DOCS / "crest-sample.png")
        print(f"crest-sample.png {fig.size}")

        if CHAMONIX.exists():
            rockhatch(build, tmp / "c.svg", "--dem", CHAMONIX, "--partition", "auto", "--crest-ornament", "default",
                      "--window", CHAMONIX_WINDOW)
            full = render(tmp / "c.svg", tmp / "c.png")
            alone = render(crest_only(tmp / "c.svg", tmp / "cc.svg"), tmp / "cc.png")
            fig = side_by_side([crop_mm(full, 45, 85, 70), crop_mm(alone, 45, 85, 70)],
                               ["Chamonix.tif, --partition auto, 1:10000, crest 2 mm", "the crest layer alone"])
            fig.save(DOCS / "crest-chamonix.png")
            print(f"crest-chamonix.png {fig.size}")
        else:
            print(f"{CHAMONIX} is absent: no Chamonix figure")


if __name__ == "__main__":
    main()
