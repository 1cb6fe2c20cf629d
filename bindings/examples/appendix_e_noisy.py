#!/usr/bin/python3
"""Noisy hatching written with the libtex operators, the way the thesis's Appendix E
writes it: a controlled arrangement whose grid partition is laid along the face's
orientation, with a jitter mapper moving every vertex, cut to the face by an Inside merge.

The jitter mapper is written out in Python here, as in the appendix: one Python call per
edge. The engine's stock mapper JitterEdges(label, angle, spacing, length, jitter) makes
the same calls to Random natively (styles/noisy.py uses it), and draws the same hatches.

Parameters (--param NAME=VALUE; "mm" are millimetres on paper at --scale):
    spacing_min  0.35 mm     hatch spacing in the darkest faces
    spacing_max  1.5  mm     hatch spacing in the lightest faces
    length       3.0  mm     length of a hatch between two jittered vertices
    jitter       1.0  ratio  jitter of the vertices (fraction of spacing and length)

    build/carto/rockhatch --script bindings/examples/appendix_e_noisy.py --dem DEM.tif --partition P.gpkg -o out.svg
"""
import sys
from math import isnan

from rockhatch.carto import interior_point
from rockhatch.tex import *  # noqa: F401,F403

NAME = "appendix-e-noisy"
TITLE = "noisy hatching with libtex operators (thesis Appendix E)"
PARAMS = [
    ("spacing_min", 0.35, "mm", "hatch spacing in the darkest faces"),
    ("spacing_max", 1.5, "mm", "hatch spacing in the lightest faces"),
    ("length", 3.0, "mm", "length of a hatch between two jittered vertices"),
    ("jitter", 1.0, "ratio", "jitter of the vertices, as a fraction of spacing and length"),
]


def face_controls(fields, region):
    """The hatch direction and spacing of a face, read at a point inside it."""
    inside = interior_point(region)
    angle, density = fields.orientation(inside), fields.density(inside)
    angle = 0.0 if isnan(angle) else angle
    density = 0.5 if isnan(density) else density
    return angle, density


def style(fields, params):
    randomization = params["jitter"]
    length = params["length"]

    def arrangement(region):
        angle, density = face_controls(fields, region)
        spacing = params["spacing_min"] + (params["spacing_max"] - params["spacing_min"]) * (1 - density)
        hatch_lines = StripesProperties(angle, spacing)
        SetEdgeLabels(hatch_lines, "hatches")
        grid = GridPartition(hatch_lines, StripesProperties(angle + pi / 2, length), KEEP_OUTSIDE)
        along, across = Point(cos(angle), sin(angle)), Point(-sin(angle), cos(angle))

        def jitter(v):
            dx = Random(v, -spacing * randomization / 2, spacing * randomization / 2, 0)
            dy = Random(v, -length * randomization / 2, length * randomization / 2, 1)
            return Location(v) + across * dx + along * dy

        def randomize_hatches(e):
            if not HasLabel(e, "hatches"):
                return Nothing()
            s, t = SourceVertex(e), TargetVertex(e)
            return MatchPoints(ToCurve(e), Location(s), Location(t), jitter(s), jitter(t))

        hatches = Inside(MapToEdges(randomize_hatches, grid), Outline(), CROP)
        return hatches(region)

    return Arrangement(arrangement)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
