#!/usr/bin/python3
"""Rock: the structure first, then the tone, and no drawn outline.

The crests (ridge lines and the strokes on their shadow side) and the tops of the cliff
bands (where the slope passes cliff_slope, with rows of strokes hanging from them down the
fall line) are drawn first; the fill and cross strokes of print.py take the ink they leave
under the tone curve. Where rock meets scree, grass or ice, the fill and cross strokes are drawn back from the
face's border by an irregular length between fray_min and fray_max (libtex's FrayedCrop):
the rock ends where its strokes end, in a ragged band, not along one smooth line. A border
with another rock face across it, or with a ridge or cliff on it, keeps its strokes to the
line.

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/rock.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/rock.py --dem DEM.tif --partition auto -o out.svg
    rockhatch --script styles/rock.py --dem DEM.tif --partition auto -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import (BALANCED, CLIFF, CREST, CROSS, FRAY, TONE, TONE_CELLS, check_fray, check_tone,
                                    cliff_strokes, cliff_tops, crest_lines, crest_strokes, frayed, read_face,
                                    toned_hatching, valleys)
from rockhatch.tex import CROP, Arrangement, Constant, Crop

NAME = "rock"
FIGURE = "after 5.4g"
TITLE = "rock drawing: crests and cliff tops with strokes hanging from them, the print tone, no drawn outline"
PARAMS = TONE + TONE_CELLS + BALANCED + CREST + CLIFF + CROSS + FRAY
__doc__ += params_help(PARAMS)


def style(fields, params):
    check_tone(params)
    check_fray(params)

    def draw(region):
        face = read_face(fields, region)
        spent = Crop(crest_strokes(fields, params, face, region), CROP)(region)
        spent.append(crest_lines(params)(region))
        spent.append(valleys()(region))
        tops = cliff_tops(fields, params, region)
        spent.append(Crop(Constant(cliff_strokes(fields, params, face, tops)), CROP)(region))
        spent.append(tops)
        out = frayed(fields, params, toned_hatching(fields, params, face, region, spent))(region)
        out.append(spent)
        return out

    return Arrangement(draw)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
