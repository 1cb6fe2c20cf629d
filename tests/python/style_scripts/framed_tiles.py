"""A style that is none of the seven (tests only): each face is tiled at its orientation,
every tile's outline shrunk about its centre and drawn as a ridge, with fill hatching
across the whole face. Written with libtex operators only (no loop over strokes).

Parameters:
    tile     4.0  mm  side of the tiles
    hatch    0.8  mm  spacing of the fill hatching
    shrink   0.6  ratio  size of a drawn tile outline, as a fraction of the tile
"""
from math import pi

from rockhatch.carto import interior_point
from rockhatch.tex import (CROP, KEEP_OUTSIDE, Arrangement, Contour, Crop, GridPartition, HasLabel, Labelled,
                           MapToEdges, MapToFaces, Nothing, Scale, SetEdgeLabels, StripesPartition,
                           StripesProperties, ToCurve, Union)

NAME = "framed-tiles"
TITLE = "tile outlines shrunk about their centres, over fill hatching"
PARAMS = [("tile", 4.0, "mm", "side of the tiles"), ("hatch", 0.8, "mm", "spacing of the fill hatching"),
          ("shrink", 0.6, "ratio", "size of a drawn tile outline, as a fraction of the tile")]


def style(fields, params):
    def in_face(region):
        theta = fields.orientation(interior_point(region))
        tiles = GridPartition(StripesProperties(theta, params["tile"]),
                              StripesProperties(theta + pi / 2, params["tile"]), KEEP_OUTSIDE)
        frames = MapToFaces(lambda cell: Labelled(Scale(Contour(cell), params["shrink"]), "ridge"), tiles)
        fill = StripesProperties(theta, params["hatch"])
        SetEdgeLabels(fill, "fill")
        hatching = MapToEdges(lambda e: ToCurve(e) if HasLabel(e, "fill") else Nothing(), StripesPartition(fill))
        return Crop(Union(frames, hatching), CROP)(region)

    return Arrangement(in_face)
