#!/usr/bin/python3
"""Noisy hatching (thesis Fig. 5.4a): each face is filled with one axis of a jittered grid.

Design iteration (a). The hatches run along the face's orientation; their spacing follows
the face's density, pushed further by the height of the face (the higher, the more
contrast); every break point of a hatch line is jittered across and along.
The program: a GridPartition of lines labelled "fill" every `spacing` at the face's
orientation, broken every `length`, each piece moved by the native JitterEdges mapper
(noisy_lines), cut to the face.

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/noisy.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/noisy.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/noisy.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import fill_params, noisy_lines, per_face, spacing_for

NAME = "noisy"
FIGURE = "5.4a"
TITLE = "noisy hatching: one axis of a jittered grid per face"
PARAMS = fill_params(3.0, 1.0)
__doc__ += params_help(PARAMS)


def fill(f, p, face):
    """One axis of a jittered grid, its spacing from the face's density and height."""
    return noisy_lines("fill", face.theta, spacing_for(p, face.density, face.height, False), p["length"],
                       p["jitter"], 1.0, f.slope, p["slope_min"])


def style(fields, params):
    """The controlled arrangement: the control fields to the arrangement drawn in each face."""
    return per_face(fields, params, fill)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
