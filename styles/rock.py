#!/usr/bin/python3
"""Rock: the structure first, then the tone, and no drawn outline.

The structure lines come first: the crests (the partition's ridges and the crease lines of
the elevation), drawn wider above walls on their shadow side, with strokes hanging from them
on that side; the tops of the cliff bands (where the slope passes cliff_slope), with rows of
strokes hanging down to the band's foot, below which the fill starts after a seam of white paper; the couloirs, thin lines the fill strokes keep away
from. The fill and cross strokes of print.py take the ink the structure leaves under the tone
curve, the fill in rows hanging from the level lines of the elevation (band_height apart,
libtex's CutAtLevels), each tone cell's strokes shortened from their lower ends to its ink. Where rock meets scree, grass or ice, the fill and cross strokes end at an irregular
distance between fray_min and fray_max from the face's border, inside it or (for the share
fray_beyond) past it (libtex's FrayedCrop): the rock ends where its strokes end, in a ragged
band across the border, not along one smooth line. A border with another rock face across it, or with a ridge or cliff on it, keeps its
strokes to the line.

The style is a program over the native style blocks (rockhatch.carto.blocks, the
built-in style's own, carto/src/styles/rock.cpp) and libtex operators:
style(fields, params) returns the arrangement drawn in each face.

Run on its own, or through the rockhatch command:
    /usr/bin/python3 styles/rock.py --dem DEM.tif --partition auto -o out.svg
    rockhatch --script styles/rock.py --dem DEM.tif --partition auto -o out.gpkg
"""
import sys

from rockhatch.carto import params_help
from rockhatch.carto.blocks import (BALANCED, CLIFF, CREST, CROSS, FRAY, ROCK_TONE, ROWS, STRUCTURE, TONE_CELLS,
                                    check_fray, check_tone, cliff_strokes, crest_lines, crest_strokes, frayed, given_cliffs,
                                    given_first, read_face, seam_below, shadow_strokes, structure_lines, tapered,
                                    toned_hatching, valleys)
from rockhatch.tex import CROP, Apart, Arrangement, Constant, Crop, Curves, Labelled

NAME = "rock"
FIGURE = "after 5.4g"
TITLE = ("rock drawing: crests, couloirs and cliff tops with strokes hanging from them, the print tone, no drawn "
         "outline")
PARAMS = ROCK_TONE + TONE_CELLS + BALANCED + CREST + CLIFF + STRUCTURE + CROSS + FRAY + ROWS
__doc__ += params_help(PARAMS)


def style(fields, params):
    check_tone(params)
    check_fray(params)

    def cut(curves, region):
        return Crop(Constant(curves), CROP)(region)

    def draw(region):
        face = read_face(fields, region)
        s = given_first(params, structure_lines(fields, params, region), region)
        # The structure lines: crests (the partition's and those around the face), cliff tops,
        # valleys; then the strokes hanging from them, and the couloirs.
        cliffs = given_cliffs(fields, region)
        cliffs.append(s.cliffs)
        lines = tapered(fields, params, Labelled(crest_lines(params)(region), "ridgeline"))
        lines.append(cut(tapered(fields, params, s.ridges), region))
        lines.append(cut(cliffs, region))
        lines.append(valleys()(region))
        spent = Curves()
        spent.append(lines)
        spent.append(Crop(crest_strokes(fields, params, face, region), CROP)(region))
        spent.append(cut(shadow_strokes(fields, params, face, s.ridges), region))
        spent.append(cut(cliff_strokes(fields, params, face, cliffs), region))
        spent.append(cut(s.couloirs, region))
        # The tone's fill and cross strokes: ending at the structure lines (not crossing them),
        # kept off the couloirs, frayed at the rock's edge.
        fill = Apart(toned_hatching(fields, params, face, region, spent), lines, params["structure_gap"])
        if params["couloir_gap"] > 0:
            fill = Apart(fill, s.couloirs, params["couloir_gap"])
        fill = Apart(fill, seam_below(s.feet, params["foot_gap"]), params["foot_gap"] / 2)
        out = frayed(fields, params, fill)(region)
        out.append(spent)
        return out

    return Arrangement(draw)


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
