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
    slope_min     0.0  %      no fill hatch where the slope is below this (percent; 0: everywhere)
    cell_spacing  3.0  mm     width of the coarse jittered cells that carry local density
    cell_jitter   1.0  ratio  jitter of the coarse cells
    peak_spacing  2.0  mm     distance between two ridge shapes
    peak_length   2.0  mm     length of a ridge shape down the slope
    peak_width    0.8  mm     width of a ridge shape at its base
    peak_fill     0.2  mm     spacing of the fine hatching inside ridge shapes

The style is a program of libtex operators (carto/src/styles/fine_ridges.cpp in Python, its
blocks in _blocks.py): style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/fine_ridges.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/fine_ridges.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from _blocks import COARSE, PEAKS, cell_hatching, fill_params, per_face, ridge_peaks
from rockhatch.tex import Union

NAME = "fine-ridges"
FIGURE = "5.4d"
TITLE = "finer, sparser ridge shapes filled with sub-scale hatching"
PARAMS = fill_params(2.0, 0.5) + COARSE + PEAKS


def fill(f, p, face):
    return Union(cell_hatching(f, p, face, False, 1.0), ridge_peaks(f, p, face, 0.0))


def style(fields, params):
    return per_face(fields, params, fill)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
