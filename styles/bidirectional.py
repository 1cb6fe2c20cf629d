#!/usr/bin/python3
"""Bidirectional hatching (thesis Fig. 5.4g, the final design and the default style):
cross hatches where the terrain is rough.

Design iteration (g), on top of (f) (high_ridges.py). Cells of a coarse grid whose
roughness (read at the cell's centre) exceeds roughness_min get hatches in the second
direction, denser as the roughness reaches roughness_max.

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/bidirectional.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/bidirectional.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/bidirectional.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import (BALANCED, COARSE, CROSS, HIGH, PEAKS, cell_hatching, cross_hatching, fill_params,
                                    per_face, ridge_peaks)
from rockhatch.tex import Union

NAME = "bidirectional"
FIGURE = "5.4g"
TITLE = "bidirectional hatching: cross hatches where the terrain is rough"
PARAMS = fill_params(1.5, 0.5) + COARSE + PEAKS + BALANCED + HIGH + CROSS
__doc__ += params_help(PARAMS)


def fill(f, p, face):
    return Union(Union(cell_hatching(f, p, face, True, p["gap"]), ridge_peaks(f, p, face, p["peak_height_gain"])),
                 cross_hatching(f, p, face))


def style(fields, params):
    return per_face(fields, params, fill, with_valleys=True)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
