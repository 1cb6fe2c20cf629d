#!/usr/bin/python3
"""High ridges (thesis Fig. 5.4f): ridge shapes grow on higher ground, and valleys
(thalwegs) are drawn as strokes.

Design iteration (f), on top of (e) (balanced.py). A valley between two faces is drawn
once, by the face with the smaller id.

Parameters (--param NAME=VALUE; "mm" are millimetres on paper at --scale):
    spacing_min       0.35 mm     hatch spacing in the darkest faces
    spacing_max       1.5  mm     hatch spacing in the lightest faces
    length            2.0  mm     length of a hatch between two jittered break points
    jitter            0.5  ratio  jitter of the break points (fraction of spacing and length)
    contrast          1.0  ratio  how much height pushes dark faces darker, light faces lighter
    cell_spacing      3.0  mm     width of the coarse jittered cells that carry local density
    cell_jitter       1.0  ratio  jitter of the coarse cells
    peak_spacing      2.0  mm     distance between two ridge shapes
    peak_length       2.0  mm     length of a ridge shape down the slope
    peak_width        0.8  mm     width of a ridge shape at its base
    peak_fill         0.2  mm     spacing of the fine hatching inside ridge shapes
    gap               0.95 ratio  each hatch is shortened to this fraction, leaving gaps
    peak_height_gain  1.0  ratio  ridge shapes grow by this fraction on the highest ground

    /usr/bin/python3 styles/high_ridges.py --dem DEM.tif --partition faces.gpkg -o out.svg
"""
import sys

from balanced import BALANCED
from density_cells import COARSE, fill_cells
from fine_ridges import PEAKS, ridge_peaks
from noisy import fill_params
from rockhatch.carto import Family, Hatch, Hatches, LineKind, face_controls

NAME = "high-ridges"
FIGURE = "5.4f"
TITLE = "ridge shapes enhanced on higher ground, valleys drawn"

HIGH = [("peak_height_gain", 1.0, "ratio", "ridge shapes grow by this fraction on the highest ground")]
PARAMS = fill_params(2.0, 0.5) + COARSE + PEAKS + BALANCED + HIGH


def valleys(out, face):
    """The face's valley segments as strokes, runs of consecutive segments joined."""
    run = []
    for i, seg in enumerate(face.boundary):
        other = face.neighbour_id(i)
        if seg.kind == LineKind.VALLEY and (other < 0 or face.id < other):
            if not run or run[-1] != seg.a:
                if len(run) >= 2:
                    out.append(Hatch(run, False, Family.VALLEY))
                run = [seg.a]
            run.append(seg.b)
        elif run:
            if len(run) >= 2:
                out.append(Hatch(run, False, Family.VALLEY))
            run = []
    if len(run) >= 2:
        out.append(Hatch(run, False, Family.VALLEY))


def style(fields, params, seed):
    def hatch(face):
        c = face_controls(face, fields)
        out = Hatches()
        fill_cells(out, params, face, c, seed, linear=True, gap=params["gap"])
        ridge_peaks(out, params, face, c, seed, params["peak_height_gain"])
        valleys(out, face)
        return out

    return hatch


if __name__ == "__main__":
    from rockhatch.cli import main

    sys.exit(main(style=sys.modules[__name__]))
