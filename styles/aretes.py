#!/usr/bin/python3
"""Aretes: the noisy hatching of (a) with a crest ornament along every ridge.

For sharp aretes on a schematic or tourist map: the fill has no ridge emphasis of its own,
and the pipeline draws each ridge line of the partition as one connected band synthesised
from the project's crest exemplar (issue 14; --crest-ornament FILE.svg names another),
crest_band millimetres high on paper. CREST_ORNAMENT = True is what asks for it: the
ornaments are drawn by the pipeline along the partition's lines, not by the per-face
program.

The style is the program of noisy.py; the ornaments come from CREST_ORNAMENT.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/aretes.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/aretes.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import fill_params, per_face
from noisy import fill

NAME = "aretes"
FIGURE = "after 5.4a"
TITLE = "noisy hatching with a crest ornament along every ridge (aretes of a schematic map)"
PARAMS = fill_params(3.0, 1.0) + [("crest_band", 2.0, "mm", "height of the crest ornament band centred on each ridge")]
__doc__ += params_help(PARAMS)
CREST_ORNAMENT = True


def style(fields, params):
    """The controlled arrangement of noisy.py; the crest ornaments come from CREST_ORNAMENT."""
    return per_face(fields, params, fill)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
