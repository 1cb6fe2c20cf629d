#!/usr/bin/python3
"""The figure of docs/tiled.md for the last gaps of issue 12 (docs/tiled-queries.png).

    PYTHONPATH=build/python scripts/tiled_queries_figure.py docs/tiled-queries.png

Three panels of 400 x 400 pixels, y up:
  (a) FaceLabelsAt and DistanceToCurves at every pixel of a 1800 x 1800 window a million
      periods from the origin, on the union of tiled stripes (120 and 300 wide, face labels
      a, b, c) with small squares (a grid of 210 x 180, cells shrunk to 30 %): one hue per
      set of face labels, darker near a curve (distance under 3 units: black);
  (b) regular result (a)'s script on tiled maps (horizontal hatching 15 apart Outside the
      tiles turned 45 degrees and shrunk), converted over [100, 1900]^2 with CROP and drawn in
      the window [700, 1300]^2, each curve in its own colour (a colour change along a run
      would be a cut);
  (c) the same script on the planar-map engine (gallery.py's tilted_tiles, hatching with CROP
      as in (b)), drawn the same way.

Needs Pillow (python3-pil).
"""
import colorsys
import math
import pathlib
import sys
import zlib

from PIL import Image, ImageDraw

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "bindings" / "examples"))
import gallery  # noqa: E402  (the gallery's Python twins: tilted_tiles)
from rockhatch.tex import *  # noqa: E402,F401,F403

PX = 400


def hue_of(labels):
    return (zlib.crc32(",".join(sorted(labels)).encode()) % 360) / 360.0


def queries_panel():
    bands = StripesProperties(0, 120, 300)
    SetFaceLabels(bands, "a", "b", "c")
    rows = StripesProperties(0, 210)
    SetFaceLabels(rows, "r1", "r2")
    squares = MapToFaces(lambda f: Scale(Contour(f), 0.3), GridPartition(rows, StripesProperties(pi / 2, 180), Tiled()))
    both = Union(StripesPartition(bands, Tiled()), squares)
    p1, p2 = both.period1, both.period2
    base = Point(1e6 * p1.x - 1e6 * p2.x, 1e6 * p1.y - 1e6 * p2.y)
    size = 1800.0
    img = Image.new("RGB", (PX, PX))
    pix = img.load()
    kinds = set()
    for row in range(PX):
        for col in range(PX):
            p = Point(base.x + (col + 0.5) * size / PX, base.y + (PX - row - 0.5) * size / PX)
            labels = both.FaceLabelsAt(p)
            kinds.add(tuple(labels))
            d = both.DistanceToCurves(p)
            value = 0.0 if d < 3 else 0.45 + 0.55 * (1 - math.exp(-d / 40))
            r, g, b = colorsys.hsv_to_rgb(hue_of(labels), 0.55, value)
            pix[col, row] = (int(255 * r), int(255 * g), int(255 * b))
    return img, kinds


def curves_panel(curves, window):
    img = Image.new("RGB", (PX, PX), "white")
    draw = ImageDraw.Draw(img)
    x0, y0, size = window
    for k, c in enumerate(curves.curves):
        r, g, b = colorsys.hsv_to_rgb((k * 0.618034) % 1.0, 0.9, 0.8)
        pts = [((p.x - x0) * PX / size, PX - (p.y - y0) * PX / size) for p in c.points]
        if c.closed:
            pts.append(pts[0])
        draw.line(pts, fill=(int(255 * r), int(255 * g), int(255 * b)), width=2)
    return img


def main(out):
    a, kinds = queries_panel()
    # Both evaluated over [100, 1900]^2 and drawn in the window [700, 1300]^2, 600 units from
    # the evaluated region's border: the engine's finite map shapes the tiles near its border
    # otherwise (the gallery test keeps the same margin).
    window = (700.0, 700.0, 600.0)
    region = Region.rectangle(100, 100, 1900, 1900)

    def turn(f):
        return Rotate(Contour(f), pi / 4)

    tiles = MapToFaces(lambda f: Scale(Contour(f), 0.8),
                       MapToFaces(turn, GridPartition(StripesProperties(0, 200), StripesProperties(pi / 2, 200), Tiled())))
    tiled = Outside(StripesPartition(StripesProperties(0, 15), Tiled()), tiles, CROP).Convert(region, CROP)
    # gallery.regular_a with CROP stripes (its default, CROP_ADD_BOUNDARY, adds the region's
    # outline pieces between the tiles).
    engine = Outside(StripesPartition(StripesProperties(0, 15), CROP), gallery.tilted_tiles(), CROP)(region)
    b = curves_panel(tiled, window)
    c = curves_panel(engine, window)
    sheet = Image.new("RGB", (3 * PX + 40, PX + 40), "white")
    draw = ImageDraw.Draw(sheet)
    for k, (panel, name) in enumerate([(a, "(a)"), (b, "(b)"), (c, "(c)")]):
        sheet.paste(panel, (10 + k * (PX + 10), 30))
        draw.text((10 + k * (PX + 10), 8), name, fill="black")
    sheet.save(out)
    def in_view(curves):
        x0, y0, size = window
        return sorted(tuple((round(p.x, 4), round(p.y, 4)) for p in c.points) for c in curves.curves
                      if all(x0 <= p.x <= x0 + size and y0 <= p.y <= y0 + size for p in c.points))

    tv, ev = in_view(tiled), in_view(engine)
    print("%s: %d kinds of faces in (a); curves wholly in the view: (b) %d, (c) %d, %d only in (b), %d only in (c)"
          % (out, len(kinds), len(tv), len(ev), len(set(tv) - set(ev)), len(set(ev) - set(tv))))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "tiled-queries.png")
