#!/usr/bin/python3
"""Ridge triangles (thesis Fig. 5.4b): noisy hatching plus triangles falling from the
ridges into the darker face.

Design iteration (b), on top of (a) (noisy.py). A grid at the hatch direction and at 45
degrees from it is laid over the face; its cells cut by the face are drawn as closed
shapes when they touch a ridge on which the face is the darker side (the face across is
lighter: the thesis's must_provide_coulis).

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/ridge_triangles.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/ridge_triangles.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/ridge_triangles.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import TRIANGLES, fill_params, noisy_lines, per_face, ridge_triangles, spacing_for
from rockhatch.tex import Union

NAME = "ridge-triangles"
FIGURE = "5.4b"
TITLE = "noisy hatching plus triangles falling from ridges into the darker face"
PARAMS = fill_params(3.0, 1.0) + TRIANGLES
__doc__ += params_help(PARAMS)


def fill(f, p, face):
    return Union(noisy_lines("fill", face.theta, spacing_for(p, face.density, face.height, False), p["length"],
                             p["jitter"], 1.0, f.slope, p["slope_min"]),
                 ridge_triangles(f, p, face))


def style(fields, params):
    return per_face(fields, params, fill)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
