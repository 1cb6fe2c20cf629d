#!/usr/bin/python3
"""Balanced density (thesis Fig. 5.4e): height acts linearly on the spacing (no longer
squared), and hatches are broken into strokes with small gaps.

Design iteration (e), on top of (d) (fine_ridges.py).

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
    gap           0.95 ratio  each hatch is shortened to this fraction, leaving gaps

    /usr/bin/python3 styles/balanced.py --dem DEM.tif --partition faces.gpkg -o out.svg
"""
import sys

from density_cells import COARSE, fill_cells
from fine_ridges import PEAKS, ridge_peaks
from noisy import fill_params
from rockhatch.carto import Hatches, face_controls

NAME = "balanced"
FIGURE = "5.4e"
TITLE = "balanced density: linear height term, hatches broken into strokes"

BALANCED = [("gap", 0.95, "ratio", "each hatch is shortened to this fraction, leaving gaps between strokes")]
PARAMS = fill_params(2.0, 0.5) + COARSE + PEAKS + BALANCED


def style(fields, params, seed):
    def hatch(face):
        c = face_controls(face, fields)
        out = Hatches()
        fill_cells(out, params, face, c, seed, linear=True, gap=params["gap"])
        ridge_peaks(out, params, face, c, seed, 0.0)
        return out

    return hatch


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
