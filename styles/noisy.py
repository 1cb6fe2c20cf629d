#!/usr/bin/python3
"""Noisy hatching (thesis Fig. 5.4a): each face is filled with one axis of a jittered grid.

Design iteration (a). The hatches run along the face's orientation; their spacing follows
the face's density, pushed further by the height of the face (the higher, the more
contrast); every break point of a hatch line is jittered across and along.

Parameters (--param NAME=VALUE; "mm" are millimetres on paper at --scale):
    spacing_min  0.35 mm     hatch spacing in the darkest faces
    spacing_max  1.5  mm     hatch spacing in the lightest faces
    length       3.0  mm     length of a hatch between two jittered break points
    jitter       1.0  ratio  jitter of the break points (fraction of spacing and length)
    contrast     1.0  ratio  how much height pushes dark faces darker, light faces lighter

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/noisy.py --dem DEM.tif --partition faces.gpkg -o out.svg
    rockhatch --script styles/noisy.py --dem DEM.tif --partition faces.gpkg -o out.gpkg
"""
import sys

from rockhatch.carto import Family, Hatches, RegionClipper, face_controls, jittered_lines, split_strokes

NAME = "noisy"
FIGURE = "5.4a"
TITLE = "noisy hatching: one axis of a jittered grid per face"


def fill_params(length, jitter):
    """The parameters of the fill hatching, shared by every iteration."""
    return [
        ("spacing_min", 0.35, "mm", "hatch spacing in the darkest faces"),
        ("spacing_max", 1.5, "mm", "hatch spacing in the lightest faces"),
        ("length", length, "mm", "length of a hatch between two jittered break points"),
        ("jitter", jitter, "ratio", "jitter of the break points, as a fraction of spacing and length"),
        ("contrast", 1.0, "ratio", "how much height pushes dark faces darker and light faces lighter"),
    ]


PARAMS = fill_params(3.0, 1.0)


def clamp01(v):
    return min(max(v, 0.0), 1.0)


def spacing_for(p, density, height, linear):
    """Hatch spacing from density and height (the thesis's stripes_cycle); `linear` is the
    balanced variant (e), where height acts linearly instead of squared."""
    h = height if linear else height * height
    d = clamp01(0.5 + (density - 0.5) * (1 + p["contrast"] * h))
    return p["spacing_min"] + (p["spacing_max"] - p["spacing_min"]) * (1 - d)


def emit(out, lines, family, gap=1.0):
    """Appends lines as hatches; gap < 1 breaks every segment into a shorter stroke."""
    if gap < 1:
        for line in lines:
            out.add_lines(split_strokes(line, gap), family)
    else:
        out.add_lines(lines, family)


def fill_face(out, p, face, c, seed):
    """One axis of a jittered grid over the face, clipped to it."""
    region = face.region
    s = spacing_for(p, c.density, c.height, False)
    j = p["jitter"]
    clip = RegionClipper(region)
    for line in jittered_lines(region.bbox(), c.orientation, s, p["length"], j, j, seed, 1):
        emit(out, clip.clip(line), Family.FILL)


def style(fields, params, seed):
    """The controlled arrangement: from the control fields to the hatches of one face."""

    def hatch(face):
        c = face_controls(face, fields)
        out = Hatches()
        fill_face(out, params, face, c, seed)
        return out

    return hatch


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
