#!/usr/bin/python3
"""Fine ridges (thesis Fig. 5.4d): the ridge triangles become finer, sparser ridge shapes
hanging down the slope, filled with sub-scale hatching.

Design iteration (d), on top of (c) (density_cells.py). Shapes are placed where a dark
ridge crosses the lines of a stripes family at the hatch direction (anchored to the
plane, so a ridge shared by two faces places them once), pointing into the face.

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/fine_ridges.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/fine_ridges.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/fine_ridges.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import COARSE, PEAKS, cell_hatching, fill_params, per_face, ridge_peaks
from rockhatch.tex import Union

NAME = "fine-ridges"
FIGURE = "5.4d"
TITLE = "finer, sparser ridge shapes filled with sub-scale hatching"
PARAMS = fill_params(2.0, 0.5) + COARSE + PEAKS
__doc__ += params_help(PARAMS)


def fill(f, p, face):
    return Union(cell_hatching(f, p, face, False, 1.0), ridge_peaks(f, p, face, 0.0))


def style(fields, params):
    return per_face(fields, params, fill)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
