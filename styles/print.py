#!/usr/bin/python3
"""Print: the drawing of issue 16 after Fig. 5.4g, and the default style. Ink follows the
shade through a tone curve under a ceiling, strokes follow the fall line, crests are drawn
as a smooth line with strokes falling from it on its dark side.

The face is drawn in two steps: the crest lines, the strokes hanging from them and the
valleys first, then the fill and cross hatching of coarse jittered cells, each cell given
the ink of the tone curve at its shade (1 - hillshade smoothed at map scale) less what the
crests and valleys already put in it under ink_max. Fill strokes keep min_gap of white
paper between them. Where the partition gives no orientation, the strokes of each cell run
along the fall line at its centre and each stroke is turned to the fall line at its middle
(follow_fall_line=0: one direction per face, the face's orientation).

Parameters (--param NAME=VALUE; "mm" are millimetres on paper at --scale):
    length             1.5  mm     length of a hatch between two jittered break points
    jitter             0.5  ratio  jitter of the break points (fraction of spacing and length)
    slope_min          0.0  %      no fill hatch where the slope is below this (percent; 0: everywhere)
    tone_min           0.05 ratio  ink coverage of fill and cross strokes on fully lit ground
    tone_max           0.36 ratio  ink coverage of fill and cross strokes in full shade
    tone_gamma         1.0  ratio  exponent of the tone curve (above 1: mid-tones lighter)
    ink_max            0.4  ratio  ceiling of the ink coverage of every cell, crests and valleys included
    min_gap            0.15 mm     least white paper between two neighbouring fill strokes
    follow_fall_line   1.0  ratio  1: strokes follow the local fall line; 0: one direction per face
    cell_spacing       2.0  mm     width of the coarse jittered cells that carry local tone
    cell_jitter        1.0  ratio  jitter of the coarse cells
    gap                0.95 ratio  each hatch is shortened to this fraction, leaving gaps
    crest_spacing      0.4  mm     distance between two shadow-side strokes along a crest line
    crest_length       0.8  mm     longest shadow-side stroke on low ground
    crest_height_gain  0.5  ratio  shadow-side strokes grow by this fraction on the highest ground
    crest_smoothing    0.8  mm     crest lines are drawn smooth at this length (shorter bends and steps go)
    roughness_min      0.01 ratio  roughness (0..1) below which no cross hatching is drawn
    roughness_max      0.08 ratio  roughness at which cross hatching is densest
    cross_spacing_min  0.6  mm     cross hatch spacing at the highest roughness
    cross_spacing_max  2.5  mm     cross hatch spacing at the lowest roughness
    cross_angle        90.0 deg    angle between fill and cross hatches

The style is a program of libtex operators (carto/src/styles/print.cpp in Python, its
blocks in _blocks.py): style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/print.py --dem DEM.tif --partition auto -o out.svg
    rockhatch --script styles/print.py --dem DEM.tif --partition auto -o out.gpkg
"""
import sys

from _blocks import (BALANCED, CREST, CROSS, TONE, TONE_CELLS, crest_lines, crest_strokes, read_face, toned_hatching,
                     valleys)
from rockhatch.tex import CROP, Arrangement, Crop

NAME = "print"
FIGURE = "after 5.4g"
TITLE = "print tone: ink follows the shade under a ceiling, strokes along the fall line, crests"
PARAMS = TONE + TONE_CELLS + BALANCED + CREST + CROSS


def check_tone(p):
    """The tone parameters must describe a curve under its ceiling."""
    if p["tone_min"] > p["tone_max"]:
        raise ValueError(f"style 'print': --param tone_min={p['tone_min']} is above tone_max={p['tone_max']}")
    if not 0 < p["ink_max"] <= 1:
        raise ValueError(f"style 'print': --param ink_max={p['ink_max']} is not a coverage in (0, 1]")
    if not 0 < p["gap"] <= 1:
        raise ValueError(f"style 'print': --param gap={p['gap']} is not a fraction in (0, 1]")


def style(fields, params):
    check_tone(params)

    def draw(region):
        face = read_face(fields, region)
        spent = Crop(crest_strokes(fields, params, face, region), CROP)(region)
        spent.append(crest_lines(params)(region))
        spent.append(valleys()(region))
        out = Crop(toned_hatching(fields, params, face, region, spent), CROP)(region)
        out.append(spent)
        return out

    return Arrangement(draw)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
