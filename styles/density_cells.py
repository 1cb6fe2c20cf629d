#!/usr/bin/python3
"""Density cells (thesis Fig. 5.4c): density varies inside a face. A coarse jittered grid
is laid over the face and each of its cells is hatched with the density read at its centre.

Design iteration (c), on top of (b) (ridge_triangles.py): the fill of (a) becomes two
scales, a coarse noisy grid and fine hatching in each of its cells (the thesis's
multiscale density variations).

Parameters (--param NAME=VALUE; "mm" are millimetres on paper at --scale):
    spacing_min    0.35 mm     hatch spacing in the darkest faces
    spacing_max    1.5  mm     hatch spacing in the lightest faces
    length         2.0  mm     length of a hatch between two jittered break points
    jitter         0.5  ratio  jitter of the break points (fraction of spacing and length)
    contrast       1.0  ratio  how much height pushes dark faces darker, light faces lighter
    cell_spacing   3.0  mm     width of the coarse jittered cells that carry local density
    cell_jitter    1.0  ratio  jitter of the coarse cells
    ridge_spacing  3.0  mm     spacing of the triangle grid along the ridges
    ridge_length   1.5  mm     side of the triangles falling from the ridges

    /usr/bin/python3 styles/density_cells.py --dem DEM.tif --partition faces.gpkg -o out.svg
"""
import math
import sys

from noisy import emit, fill_params, spacing_for
from ridge_triangles import TRIANGLES, ridge_triangles
from rockhatch import Points
from rockhatch.carto import (Family, Hatches, RegionClipper, clip_to_convex, face_controls, jittered_lines,
                             ring_centroid)
from rockhatch.tex import BBox, signed_area

NAME = "density-cells"
FIGURE = "5.4c"
TITLE = "density varying inside faces: a coarse jittered grid, each cell hatched"

COARSE = [
    ("cell_spacing", 3.0, "mm", "width of the coarse jittered cells that carry local density"),
    ("cell_jitter", 1.0, "ratio", "jitter of the coarse cells"),
]
PARAMS = fill_params(2.0, 0.5) + COARSE + TRIANGLES


def grid_cells(rows, within):
    """The quadrilaterals between consecutive jittered lines (counter-clockwise) whose box
    meets `within`, with their boxes."""
    for r in range(len(rows) - 1):
        lo, hi = rows[r], rows[r + 1]
        for k in range(min(len(lo), len(hi)) - 1):
            # A C++ vector, so the calls below do not convert a Python list each time.
            quad = Points([lo[k], lo[k + 1], hi[k + 1], hi[k]])
            if signed_area(quad) < 0:
                quad = quad[::-1]
            box = BBox()
            for q in quad:
                box.add(q)
            if box.intersects(within):
                yield quad, box


def fill_cells(out, p, face, c, seed, linear, gap):
    """Coarse jittered cells along the hatch direction (4 hatch lengths long), each hatched
    with the spacing its centre's height asks for."""
    region = face.region
    length, cj, theta, j = p["length"], p["cell_jitter"], c.orientation, p["jitter"]
    rows = jittered_lines(region.bbox(), theta, p["cell_spacing"], 4 * length, cj * 0.5, cj * 0.5, seed, 2)
    clip = RegionClipper(region)
    height = c.height_field
    for quad, box in grid_cells(rows, region.bbox()):
        h = height(ring_centroid(quad))
        if math.isnan(h):
            h = c.height
        s = spacing_for(p, c.density, h, linear)
        for line in jittered_lines(box, theta, s, length, j, j, seed, 3):
            for piece in clip_to_convex(line, quad):
                emit(out, clip.clip(piece), Family.FILL, gap)


def style(fields, params, seed):
    def hatch(face):
        c = face_controls(face, fields)
        out = Hatches()
        fill_cells(out, params, face, c, seed, linear=False, gap=1.0)
        ridge_triangles(out, params, face, c)
        return out

    return hatch


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
