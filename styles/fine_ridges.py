#!/usr/bin/python3
"""Fine ridges (thesis Fig. 5.4d): the ridge triangles become finer, sparser ridge shapes
hanging down the slope, filled with sub-scale hatching.

Design iteration (d), on top of (c) (density_cells.py). Shapes are placed where a dark
ridge crosses the lines of a stripes family at the hatch direction (anchored to the
plane, so a ridge shared by two faces places them once), pointing into the face.

Parameters (--param NAME=VALUE; "mm" are millimetres on paper at --scale):
    spacing_min   0.35 mm     hatch spacing in the darkest faces
    spacing_max   1.5  mm     hatch spacing in the lightest faces
    length        2.0  mm     length of a hatch between two jittered break points
    jitter        0.5  ratio  jitter of the break points (fraction of spacing and length)
    contrast      1.0  ratio  how much height pushes dark faces darker, light faces lighter
    cell_spacing  3.0  mm     width of the coarse jittered cells that carry local density
    cell_jitter   1.0  ratio  jitter of the coarse cells
    peak_spacing  2.0  mm     distance between two ridge shapes
    peak_length   2.0  mm     length of a ridge shape down the slope
    peak_width    0.8  mm     width of a ridge shape at its base
    peak_fill     0.2  mm     spacing of the fine hatching inside ridge shapes

    /usr/bin/python3 styles/fine_ridges.py --dem DEM.tif --partition faces.gpkg -o out.svg
"""
import math
import sys

from density_cells import COARSE, fill_cells
from noisy import emit, fill_params
from ridge_triangles import dark_ridges
from rockhatch import Points
from rockhatch.carto import (Family, Hatch, Hatches, RegionClipper, clip_polygon_convex, clip_to_convex,
                             face_controls, jitter_at, jittered_lines)
from rockhatch.tex import BBox, Point, cos, dot, signed_area, sin

NAME = "fine-ridges"
FIGURE = "5.4d"
TITLE = "finer, sparser ridge shapes filled with sub-scale hatching"

PEAKS = [
    ("peak_spacing", 2.0, "mm", "distance between two ridge shapes"),
    ("peak_length", 2.0, "mm", "length of a ridge shape down the slope"),
    ("peak_width", 0.8, "mm", "width of a ridge shape at its base"),
    ("peak_fill", 0.2, "mm", "spacing of the fine hatching inside ridge shapes"),
]
PARAMS = fill_params(2.0, 0.5) + COARSE + PEAKS


def ridge_peaks(out, p, face, c, seed, height_gain):
    """Triangles hanging from the dark ridges along the hatch direction; height_gain makes
    them larger on high ground (iteration f)."""
    boundary = face.boundary
    ridges = dark_ridges(boundary, c)
    if not ridges:
        return
    region = face.region
    outer = region.outer
    height = c.height_field
    theta = c.orientation
    d = Point(cos(theta), sin(theta))
    n = Point(-d.y, d.x)
    spacing, fill = p["peak_spacing"], p["peak_fill"]
    probe = 0.05 * spacing
    clip = None
    for ri in ridges:
        seg = boundary[ri]
        ta, tb = dot(seg.a, n), dot(seg.b, n)
        if ta == tb:
            continue
        lo, hi = min(ta, tb), max(ta, tb)
        for k in range(math.ceil(lo / spacing), math.floor(hi / spacing) + 1):
            t = float(k) * spacing
            if t == hi and t != lo:
                continue  # half-open: a point shared by two segments is placed once
            apex = seg.a + (seg.b - seg.a) * ((t - ta) / (tb - ta))
            if region.contains(apex + d * probe):
                down = d
            elif region.contains(apex - d * probe):
                down = -d
            else:
                continue
            h = height(apex)
            if math.isnan(h):
                h = c.height
            jt = jitter_at(apex, seed, 4)
            length = p["peak_length"] * (1 + height_gain * h) * (0.85 + 0.15 * jt.x)
            half = p["peak_width"] / 2 * (1 + 0.5 * height_gain * h)
            tri = Points([apex, apex + down * length + n * half, apex + down * length - n * half])
            if signed_area(tri) < 0:
                tri = tri[::-1]
            shape = clip_polygon_convex(outer, tri)
            if len(shape) < 3 or abs(signed_area(shape)) < 1e-9:
                continue
            if signed_area(shape) < 0:
                shape = shape[::-1]
            out.append(Hatch(shape, True, Family.RIDGE))
            box = BBox()
            for q in shape:
                box.add(q)
            # The fine hatching stays inside the shape: the triangle and the face.
            clip = clip or RegionClipper(region)
            for line in jittered_lines(box, theta, fill, 4 * fill, 0.2, 0.2, seed, 5):
                for piece in clip_to_convex(line, tri):
                    emit(out, clip.clip(piece), Family.RIDGE)


def style(fields, params, seed):
    def hatch(face):
        c = face_controls(face, fields)
        out = Hatches()
        fill_cells(out, params, face, c, seed, linear=False, gap=1.0)
        ridge_peaks(out, params, face, c, seed, 0.0)
        return out

    return hatch


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
