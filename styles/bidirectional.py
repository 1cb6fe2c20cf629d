#!/usr/bin/python3
"""Bidirectional hatching (thesis Fig. 5.4g, the final design and the default style):
cross hatches where the terrain is rough.

Design iteration (g), on top of (f) (high_ridges.py). Cells of a coarse grid whose
roughness (read at the cell's centre) exceeds roughness_min get hatches in the second
direction, denser as the roughness reaches roughness_max.

Parameters (--param NAME=VALUE; "mm" are millimetres on paper at --scale):
    spacing_min        0.35 mm     hatch spacing in the darkest faces
    spacing_max        1.5  mm     hatch spacing in the lightest faces
    length             1.5  mm     length of a hatch between two jittered break points
    jitter             0.5  ratio  jitter of the break points (fraction of spacing and length)
    contrast           1.0  ratio  how much height pushes dark faces darker, light faces lighter
    cell_spacing       3.0  mm     width of the coarse jittered cells that carry local density
    cell_jitter        1.0  ratio  jitter of the coarse cells
    peak_spacing       2.0  mm     distance between two ridge shapes
    peak_length        2.0  mm     length of a ridge shape down the slope
    peak_width         0.8  mm     width of a ridge shape at its base
    peak_fill          0.2  mm     spacing of the fine hatching inside ridge shapes
    gap                0.95 ratio  each hatch is shortened to this fraction, leaving gaps
    peak_height_gain   1.0  ratio  ridge shapes grow by this fraction on the highest ground
    roughness_min      0.01 ratio  roughness (0..1) below which no cross hatching is drawn
    roughness_max      0.08 ratio  roughness at which cross hatching is densest
    cross_spacing_min  0.6  mm     cross hatch spacing at the highest roughness
    cross_spacing_max  2.5  mm     cross hatch spacing at the lowest roughness
    cross_angle        90.0 deg    angle between fill and cross hatches

    /usr/bin/python3 styles/bidirectional.py --dem DEM.tif --partition faces.gpkg -o out.svg
"""
import sys

from balanced import BALANCED
from density_cells import COARSE, fill_cells, grid_cells
from fine_ridges import PEAKS, ridge_peaks
from high_ridges import HIGH, valleys
from noisy import clamp01, emit, fill_params
from rockhatch.carto import (Family, Hatches, RegionClipper, clip_to_convex, face_controls, jittered_lines,
                             ring_centroid)

NAME = "bidirectional"
FIGURE = "5.4g"
TITLE = "bidirectional hatching: cross hatches where the terrain is rough"

CROSS = [
    ("roughness_min", 0.01, "ratio", "roughness (0..1) below which no cross hatching is drawn"),
    ("roughness_max", 0.08, "ratio", "roughness at which cross hatching is densest"),
    ("cross_spacing_min", 0.6, "mm", "cross hatch spacing at the highest roughness"),
    ("cross_spacing_max", 2.5, "mm", "cross hatch spacing at the lowest roughness"),
    ("cross_angle", 90.0, "deg", "angle between fill and cross hatches"),
]
PARAMS = fill_params(1.5, 0.5) + COARSE + PEAKS + BALANCED + HIGH + CROSS


def cross_hatch(out, p, face, c, seed):
    r0 = p["roughness_min"]
    r1 = max(p["roughness_max"], r0 + 1e-9)
    cs = p["cell_spacing"]
    angle = c.orientation + p["cross_angle"]
    region = face.region
    rows = jittered_lines(region.bbox(), c.orientation, cs, cs, 0, 0, seed, 6)
    clip = RegionClipper(region)
    roughness = c.roughness_field
    s_min, s_max = p["cross_spacing_min"], p["cross_spacing_max"]
    for quad, box in grid_cells(rows, region.bbox()):
        rough = roughness(ring_centroid(quad))
        if not rough > r0:
            continue
        s = s_max - (s_max - s_min) * clamp01((rough - r0) / (r1 - r0))
        for line in jittered_lines(box, angle, s, p["length"], 0.5, 0.5, seed, 7):
            for piece in clip_to_convex(line, quad):
                emit(out, clip.clip(piece), Family.CROSS, p["gap"])


def style(fields, params, seed):
    def hatch(face):
        c = face_controls(face, fields)
        out = Hatches()
        fill_cells(out, params, face, c, seed, linear=True, gap=params["gap"])
        ridge_peaks(out, params, face, c, seed, params["peak_height_gain"])
        valleys(out, face)
        cross_hatch(out, params, face, c, seed)
        return out

    return hatch


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
