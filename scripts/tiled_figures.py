#!/usr/bin/python3
"""The figure of docs/tiled.md for the second part of issue 12 (docs/tiled-part2.png).

    PYTHONPATH=build/python scripts/tiled_figures.py docs/tiled-part2.png

Three panels of 600 x 600 pixels: (a) and (b) 2000 x 2000 units, (c) 450 x 450 units:
  (a) regular result (b)'s script (gallery.py's chevron rules, shrink, hatch, wobbly strokes)
      on a tiled grid, with the hatching 200 * sqrt(2) / 7 apart (so that it repeats with the
      lattice): rasterised by the tiled map and written by rockhatch.tex.WriteImage;
  (b) the same script on the planar-map engine, exported to SVG, drawn by rsvg-convert and
      flipped so that y points up as in (a);
  (c) horizontal hatching 40 apart (two edge labels) cut to the cells of a 90 x 50 grid, with
      the cells shrunk to 90 % drawn over it, a million periods from the origin: the tiled map
      maps the hatching on the coarser lattice of 720 on which hatching and grid both repeat.

Needs rsvg-convert (librsvg2-bin) and Pillow (python3-pil).
"""
import math
import pathlib
import subprocess
import sys
import tempfile

from PIL import Image, ImageDraw, ImageOps

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "bindings" / "examples"))
import gallery  # noqa: E402  (the gallery's Python twins: stroke_along, shrink, load, chevron_rule)
from rockhatch.tex import *  # noqa: E402,F401,F403

SIZE, PX, LABEL = 2000.0, 600, 18
ELEMENTS = str(pathlib.Path(__file__).resolve().parents[1] / "libtex" / "examples" / "elements")


def chevron_lines(angle, name):
    s = StripesProperties(angle, 200)
    SetEdgeLabels(s, *["%s%d" % (name, k) for k in range(1, 5)])
    return s


def regular_b_on(border, spacing):
    """Regular result (b) over a grid asked with `border` (a border mode, or Tiled())."""
    wobble = gallery.load(ELEMENTS, "wobble.svg")
    grid = GridPartition(chevron_lines(pi / 4, "h"), chevron_lines(-pi / 4, "v"), border)
    tiles = MapToFaces(lambda f: gallery.shrink(f, 0.8), MapToEdges(gallery.chevron_rule, grid))
    hatched = MapToFaces(lambda f: StripesPartition(StripesProperties(0, spacing))(f), tiles)
    return MapToEdges(lambda e: Nothing() if IsBoundary(e) else gallery.stroke_along(wobble, e), hatched)


def panel_tiled(tiled, window, path, side=SIZE, width=4.0):
    image = Rasterize(tiled, window, side / PX, width)
    WriteImage(image, path)
    return Image.open(path).convert("L")


def panel_engine(arrangement, path, tmp):
    svg = tmp / "engine.svg"
    ExportSVG(arrangement, SIZE, str(svg), SvgStyle(4.0 * 1000 / SIZE))
    subprocess.run(["rsvg-convert", "-w", str(PX), "-h", str(PX), "-b", "white", "-o", str(path), str(svg)],
                   check=True)
    # ExportSVG keeps the coordinates as they are (y down on screen); Rasterize puts y up.
    return ImageOps.flip(Image.open(path).convert("L"))


def main():
    out = pathlib.Path(sys.argv[1])
    spacing = 200 * math.sqrt(2) / 7
    with tempfile.TemporaryDirectory() as d:
        tmp = pathlib.Path(d)
        a = panel_tiled(regular_b_on(Tiled(), spacing), Region.rectangle(0, 0, SIZE, SIZE), str(tmp / "a.png"))
        b = panel_engine(regular_b_on(KEEP_OUTSIDE, spacing), tmp / "b.png", tmp)
        lines = StripesProperties(0, 40)
        SetEdgeLabels(lines, "a", "b")
        rows, columns = StripesProperties(0, 90), StripesProperties(pi / 2, 50)

        hatched = Union(MapToFaces(lambda f: StripesPartition(lines, CROP)(f), GridPartition(rows, columns, Tiled())),
                        MapToFaces(lambda f: Scale(Contour(f), 0.9), GridPartition(rows, columns, Tiled())))
        far = hatched.period1 * 1e6 + hatched.period2 * 1e6
        c = panel_tiled(hatched, Region.rectangle(far.x, far.y, far.x + 450, far.y + 450), str(tmp / "c.png"), 450, 1.5)
    canvas = Image.new("L", (3 * PX + 4 * 8, PX + LABEL + 16), 255)
    draw = ImageDraw.Draw(canvas)
    for k, (img, text) in enumerate([(a, "(a) regular (b), hatching 40.4 apart: tiled map"),
                                     (b, "(b) the same script: planar-map engine"),
                                     (c, "(c) hatched cells, 1e6 periods away (period 720)")]):
        x = 8 + k * (PX + 8)
        canvas.paste(img, (x, 8))
        draw.rectangle([x - 1, 7, x + PX, 8 + PX], outline=0)
        draw.text((x, PX + 12), text, fill=0)
    canvas.save(out)
    print(out, canvas.size)


if __name__ == "__main__":
    main()
