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

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/print.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/print.py --dem DEM.tif --partition auto -o out.svg
    rockhatch --script styles/print.py --dem DEM.tif --partition auto -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import (BALANCED, CREST, CROSS, TONE, TONE_CELLS, check_tone, crest_lines, crest_strokes,
                                    read_face, toned_hatching, valleys)
from rockhatch.tex import CROP, Arrangement, Crop

NAME = "print"
FIGURE = "after 5.4g"
TITLE = "print tone: ink follows the shade under a ceiling, strokes along the fall line, crests"
PARAMS = TONE + TONE_CELLS + BALANCED + CREST + CROSS
__doc__ += params_help(PARAMS)


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
