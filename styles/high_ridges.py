#!/usr/bin/python3
"""High ridges (thesis Fig. 5.4f): ridge shapes grow on higher ground, and valleys
(thalwegs) are drawn as strokes.

Design iteration (f), on top of (e) (balanced.py). A valley between two faces is drawn
once, by the face with the smaller id.

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/high_ridges.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/high_ridges.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/high_ridges.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import BALANCED, COARSE, HIGH, PEAKS, cell_hatching, fill_params, per_face, ridge_peaks
from rockhatch.tex import Union

NAME = "high-ridges"
FIGURE = "5.4f"
TITLE = "ridge shapes enhanced on higher ground, valleys drawn"
PARAMS = fill_params(2.0, 0.5) + COARSE + PEAKS + BALANCED + HIGH
__doc__ += params_help(PARAMS)


def fill(f, p, face):
    return Union(cell_hatching(f, p, face, True, p["gap"]), ridge_peaks(f, p, face, p["peak_height_gain"]))


def style(fields, params):
    return per_face(fields, params, fill, with_valleys=True)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
