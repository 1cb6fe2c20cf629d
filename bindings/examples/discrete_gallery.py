#!/usr/bin/python3
"""Seed 004's figures 1a-1g as Python programs, twins of libtex/examples/gallery_discrete.cpp.

Each function reads like the seed's pseudo-code: a greedy distribution of a pinning, a
shaping and a check, written with `from rockhatch.discrete import *`. gallery.py lists them
with the other examples (discrete_1a ... discrete_1g) and writes them, and the tests check
that they give the bytes rh_gallery writes:

    /usr/bin/python3 bindings/examples/gallery.py --out DIR --only discrete_1a,discrete_1f
"""
import math
import os

from rockhatch.discrete import *  # noqa: F401,F403
from rockhatch.tex import Constant

SIZE = 2000.0
ELEMENTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "libtex", "examples", "elements")

# Sizes in the 2000 window, as in gallery_discrete.hpp.
HATCH_LENGTH, HATCH_WIDTH = 60.0, 8.0
RECT_WIDTH, RECT_HEIGHT = 300.0, 200.0
CIRCLE_RADIUS = 36.0
CIRCLE_DARTS, RELAX_STEPS = 600, 8
FLOW_STEP, STREAM_LENGTH, STREAM_WIDTH, STREAM_GAP = 5.0, 420.0, 7.0, 4.0


def image():
    return Image(SIZE, SIZE)


def tapered(width):
    """A stroke with thin ends, `width` in the middle."""
    return lambda t: width * (0.25 + 0.75 * math.sin(pi * t))


def in_image():
    return Overlap(RegionSet([image()]))


def outlines(*sets):
    c = Curves()
    for s in sets:
        c.append(ToCurves(s))
    return Constant(c)


def fig_1a():
    hatches = RegionSet()
    greedy_distribution(hatches, CountUpTo(1000), RandomPinning(image()),
                        Translation(BuiltinHatch(HATCH_LENGTH, HATCH_WIDTH)), Not(Overlap(hatches)))
    return hatches


def fig_1b():
    rectangles, hatches = RegionSet(), RegionSet()
    greedy_distribution(rectangles, CountUpTo(25), Sequence(RegularPinning(image(), 5, 5)),
                        Translation(BuiltinRectangle(RECT_WIDTH, RECT_HEIGHT)), Not(Overlap(rectangles)))
    greedy_distribution(hatches, CountUpTo(1000), RandomPinning(image()),
                        Translation(BuiltinHatch(HATCH_LENGTH, HATCH_WIDTH)),
                        And(Not(Overlap(hatches)), Overlap(rectangles)))
    return hatches, rectangles


def fig_1c():
    hatches, _ = fig_1b()
    hatches_orth = RegionSet()
    greedy_distribution(hatches_orth, CountUpTo(3000), RandomPinning(image()),
                        Translation(Rotation(BuiltinHatch(HATCH_LENGTH, HATCH_WIDTH), pi / 2)),
                        And(Not(Overlap(hatches)), Not(Overlap(hatches_orth))))
    return hatches, hatches_orth


def fig_1d(elements):
    user = UserRegion(ImportSVG(os.path.join(elements, "leaf.svg")))
    angle = RandomR(0, 2 * pi)
    size = RandomR(0.3, 1.2)
    shape = Compose(Rotation(angle), Compose(Scale(size), Const(user)))
    shapes = RegionSet()
    greedy_distribution(shapes, CountUpTo(4000), RandomPinning(image()), Translation(shape), Not(Overlap(shapes)))
    return shapes


def circle_distribution():
    circles, relaxed_circles = RegionSet(), RegionSet()
    greedy_distribution(circles, CountUpTo(CIRCLE_DARTS), RandomPinning(image()),
                        Translation(BuiltinCircle(CIRCLE_RADIUS)), Not(Overlap(circles)))
    relaxation(circles, relaxed_circles, CountUpTo(RELAX_STEPS), VoronoiCells(image().bbox()), Centroid)
    return relaxed_circles, circles


def fig_1e():
    relaxed_circles, _ = circle_distribution()
    cells = VoronoiCells(relaxed_circles.regions, image().bbox())
    factor = RandomR(0.55, 0.9)
    return RegionSet([Scale(cell, factor()) for cell in cells])


def fig_1f():
    relaxed_circles, _ = circle_distribution()
    stream_lines = RegionSet()
    free = And(in_image(), And(Not(Overlap(relaxed_circles)),
                               Not(MinimalDistance(stream_lines, STREAM_WIDTH / 2 + STREAM_GAP))))
    shaping = stream_line(TangentFlowField(relaxed_circles, FLOW_STEP), free, STREAM_LENGTH, tapered(STREAM_WIDTH),
                          6 * FLOW_STEP)
    greedy_distribution(stream_lines, CountUpTo(2000), RandomPinning(image()), shaping,
                        And(Not(Overlap(relaxed_circles)), Not(MinimalDistance(stream_lines, STREAM_GAP))))
    return stream_lines, relaxed_circles


def fig_1g():
    relaxed_circles, _ = circle_distribution()
    flow = TangentFlowField(relaxed_circles, FLOW_STEP)
    # First set: from the circles' contours, at 30 degrees to the flow.
    stream_lines = RegionSet()
    pins = RegularPinning1D(Contour(relaxed_circles), 1.0 / 30)
    turned = Compose(Rotation(pi / 6), flow)
    greedy_distribution(stream_lines, CountUpTo(len(pins)), Sequence(pins),
                        stream_line(turned, And(in_image(), Not(MinimalDistance(stream_lines, STREAM_WIDTH))),
                                    STREAM_LENGTH / 2, tapered(STREAM_WIDTH * 0.8), 4 * FLOW_STEP),
                        Not(MinimalDistance(stream_lines, STREAM_GAP)))
    # Second set: from the first set's contours, along the flow, stopping at the first set.
    scnd_strlines = RegionSet()
    pins2 = RegularPinning1D(Contour(stream_lines), 1.0 / 40)
    greedy_distribution(scnd_strlines, CountUpTo(len(pins2)), Sequence(pins2),
                        stream_line(flow, And(in_image(), Not(Overlap(stream_lines))), STREAM_LENGTH / 3,
                                    tapered(STREAM_WIDTH * 0.5), 3 * FLOW_STEP),
                        Not(MinimalDistance(scnd_strlines, STREAM_GAP)))
    return stream_lines, scnd_strlines


# The gallery's entries: elements folder -> arrangement (outlines of what each figure shows).
EXAMPLES = {
    "discrete_1a": lambda elements: outlines(fig_1a()),
    "discrete_1b": lambda elements: outlines(fig_1b()[0]),
    "discrete_1c": lambda elements: outlines(*fig_1c()),
    "discrete_1d": lambda elements: outlines(fig_1d(elements)),
    "discrete_1e": lambda elements: outlines(fig_1e()),
    "discrete_1f": lambda elements: outlines(*fig_1f()),
    "discrete_1g": lambda elements: outlines(*fig_1g()),
}

