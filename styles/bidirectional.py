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
    slope_min          0.0  %      no fill hatch where the slope is below this (percent; 0: everywhere)
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

The style is a program of libtex operators (carto/src/styles/bidirectional.cpp in Python, its
blocks in _blocks.py): style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/bidirectional.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/bidirectional.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from _blocks import (BALANCED, COARSE, CROSS, HIGH, PEAKS, cell_hatching, cross_hatching, fill_params, per_face,
                     ridge_peaks)
from rockhatch.tex import Union

NAME = "bidirectional"
FIGURE = "5.4g"
TITLE = "bidirectional hatching: cross hatches where the terrain is rough"
PARAMS = fill_params(1.5, 0.5) + COARSE + PEAKS + BALANCED + HIGH + CROSS


def fill(f, p, face):
    return Union(Union(cell_hatching(f, p, face, True, p["gap"]), ridge_peaks(f, p, face, p["peak_height_gain"])),
                 cross_hatching(f, p, face))


def style(fields, params):
    return per_face(fields, params, fill, with_valleys=True)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
