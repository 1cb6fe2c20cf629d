#!/usr/bin/python3
"""Density cells (thesis Fig. 5.4c): density varies inside a face. A coarse jittered grid
is laid over the face and each of its cells is hatched with the density read at its centre.

Design iteration (c), on top of (b) (ridge_triangles.py): the fill of (a) becomes two
scales, a coarse noisy grid and fine hatching in each of its cells (the thesis's
multiscale density variations).

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/density_cells.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/density_cells.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/density_cells.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import COARSE, TRIANGLES, cell_hatching, fill_params, per_face, ridge_triangles
from rockhatch.tex import Union

NAME = "density-cells"
FIGURE = "5.4c"
TITLE = "density varying inside faces: a coarse jittered grid, each cell hatched"
PARAMS = fill_params(2.0, 0.5) + COARSE + TRIANGLES
__doc__ += params_help(PARAMS)


def fill(f, p, face):
    return Union(cell_hatching(f, p, face, False, 1.0), ridge_triangles(f, p, face))


def style(fields, params):
    return per_face(fields, params, fill)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
