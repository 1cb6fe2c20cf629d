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
    slope_min      0.0  %      no fill hatch where the slope is below this (percent; 0: everywhere)
    cell_spacing   3.0  mm     width of the coarse jittered cells that carry local density
    cell_jitter    1.0  ratio  jitter of the coarse cells
    ridge_spacing  3.0  mm     spacing of the triangle grid along the ridges
    ridge_length   1.5  mm     side of the triangles falling from the ridges

The style is a program of libtex operators (carto/src/styles/density_cells.cpp in Python, its
blocks in _blocks.py): style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/density_cells.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/density_cells.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from _blocks import COARSE, TRIANGLES, cell_hatching, fill_params, per_face, ridge_triangles
from rockhatch.tex import Union

NAME = "density-cells"
FIGURE = "5.4c"
TITLE = "density varying inside faces: a coarse jittered grid, each cell hatched"
PARAMS = fill_params(2.0, 0.5) + COARSE + TRIANGLES


def fill(f, p, face):
    return Union(cell_hatching(f, p, face, False, 1.0), ridge_triangles(f, p, face))


def style(fields, params):
    return per_face(fields, params, fill)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
