#!/usr/bin/python3
"""Balanced density (thesis Fig. 5.4e): height acts linearly on the spacing (no longer
squared), and hatches are broken into strokes with small gaps.

Design iteration (e), on top of (d) (fine_ridges.py).

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/balanced.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/balanced.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/balanced.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import BALANCED, COARSE, PEAKS, cell_hatching, fill_params, per_face, ridge_peaks
from rockhatch.tex import Union

NAME = "balanced"
FIGURE = "5.4e"
TITLE = "balanced density: linear height term, hatches broken into strokes"
PARAMS = fill_params(2.0, 0.5) + COARSE + PEAKS + BALANCED
__doc__ += params_help(PARAMS)


def fill(f, p, face):
    return Union(cell_hatching(f, p, face, True, p["gap"]), ridge_peaks(f, p, face, 0.0))


def style(fields, params):
    return per_face(fields, params, fill)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
