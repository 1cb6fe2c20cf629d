#!/usr/bin/python3
"""The thesis's Appendix A examples as Python scripts, twins of libtex/examples/gallery.cpp.

Each function builds one arrangement with the operators of `rockhatch.tex`, in the style
of the thesis's scripts; run on its own, the file writes the SVGs the way rh_gallery
does, and the tests check that both give the same bytes.

    /usr/bin/python3 bindings/examples/gallery.py --out DIR [--only NAME,...] [--threads N] [--seed N]
"""
import argparse
import math
import os
import sys
import time

from rockhatch.tex import *  # noqa: F401,F403

SIZE = 2000.0
ELEMENTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "libtex", "examples", "elements")


def load(elements, name):
    return ImportSVG(os.path.join(elements, name))


def stripes(elements):
    # Stripes at 45 degrees, widths 200 and 67 in turn.
    return StripesPartition(StripesProperties(pi / 4, SIZE / 10, SIZE / 30))


def grid(elements):
    h = StripesProperties(0, SIZE / 10, SIZE / 25)
    v = StripesProperties(pi / 2, SIZE / 8)
    return GridPartition(h, v, KEEP_OUTSIDE)


def uniform(elements):
    return UniformPartition(IrregularProperties(50 / (SIZE * SIZE)), KEEP_OUTSIDE)


def random_(elements):
    return RandomPartition(IrregularProperties(50 / (SIZE * SIZE)), KEEP_OUTSIDE)


def puzzle(elements):
    zig = load(elements, "zig2.svg")
    l1 = StripesProperties(0.0, SIZE / 16)
    l2 = StripesProperties(pi / 2, SIZE / 16)
    SetEdgeLabels(l1, "h1", "h2")
    SetEdgeLabels(l2, "v1", "v2")
    grid_tex = GridPartition(l1, l2, KEEP_OUTSIDE)

    def grid_to_wall(e):
        # Every other vertical edge goes, staggered from row to row.
        around = IncidentEdges(TargetVertex(e))
        if (HasLabel(e, "v1") and HasLabel(around, "h1")) or (HasLabel(e, "v2") and HasLabel(around, "h2")):
            return Nothing()
        return ToCurve(e)

    def edge_to_curve(e):
        sc, dc = PointLabeled(zig, "start"), PointLabeled(zig, "end")
        sv, dv = Location(SourceVertex(e)), Location(TargetVertex(e))
        if Random(e, 0, 1, 0) < 0.5:
            return MatchPoints(zig, sc, dc, sv, dv)
        return MatchPoints(zig, sc, dc, dv, sv)

    return MapToEdges(edge_to_curve, MapToEdges(grid_to_wall, grid_tex))


def rosettes(elements):
    line = load(elements, "line.svg")
    circle = load(elements, "circle.svg")
    part = UniformPartition(IrregularProperties(70 / (SIZE * SIZE)), KEEP_OUTSIDE)

    def face_to_star(f):
        rot = Random(f, 0.0, 2 * pi, 0)
        e1 = MatchPoint(line, BBoxCenter(line), Centroid(f))
        e2 = Append(Rotate(e1, rot), Rotate(e1, rot + pi / 2))
        return Append(e2, Rotate(e2, pi / 4))

    def vertex_to_circle(v):
        if len(IncidentEdges(v)) > 1:
            return Nothing()
        return MatchPoint(circle, BBoxCenter(circle), Location(v))

    return MapToVertices(vertex_to_circle, MapToFaces(face_to_star, part))


def cracks(elements):
    lines = [load(elements, n) for n in ("line1.svg", "line2.svg", "line3.svg")]
    part = RandomPartition(IrregularProperties(200 / (SIZE * SIZE)), KEEP_OUTSIDE)

    def rescale_face(f):
        return Scale(Contour(f), 0.8)

    def edge_to_curve(e):
        l = lines[int(math.floor(Random(e, 0, len(lines), 0)))]
        return MatchPoints(l, PointLabeled(l, "start"), PointLabeled(l, "end"),
                           Location(SourceVertex(e)), Location(TargetVertex(e)))

    return MapToEdges(edge_to_curve, MapToFaces(rescale_face, part))


def one_face_in_two(f):
    return (HasLabel(f, "v1") and HasLabel(f, "h1")) or (HasLabel(f, "v2") and HasLabel(f, "h2"))


def labelled_grid(w1, w2):
    l1 = StripesProperties(0, w1)
    l2 = StripesProperties(pi / 2, w2)
    SetFaceLabels(l1, "h1", "h2")
    SetFaceLabels(l2, "v1", "v2")
    return GridPartition(l1, l2, KEEP_OUTSIDE)


def bimodal(elements):
    hatch = load(elements, "hatch.svg")

    def face_to_hatches(f):
        if not one_face_in_two(f):
            return Nothing()
        e1 = Scale(hatch, Random(f, 2.6, 2.7, 1))
        e2 = Rotate(e1, pi / 7 + Random(f, -pi / 12, pi / 12, 2))
        e3 = Rotate(e1, pi / 2 + Random(f, -pi / 12, pi / 12, 3))
        e4 = Append(e2, e3)
        w, h = BBoxWidth(f) / 7, BBoxHeight(f) / 7
        pos = Centroid(f) + Point(Random(f, -w, w, 4), Random(f, -h, h, 5))
        return MatchPoint(e4, BBoxCenter(e4), pos)

    return MapToFaces(face_to_hatches, labelled_grid(SIZE / 10, SIZE / 20))


def crosses(elements):
    cross = load(elements, "cross.svg")

    def face_to_cross(f):
        if not one_face_in_two(f):
            return Nothing()
        e1 = Scale(cross, Random(f, 1.35, 1.45, 2))
        e2 = Rotate(e1, Random(f, -pi / 20, pi / 20, 4))
        return MatchPoint(e2, BBoxCenter(e2), BBoxCenter(f))

    return MapToFaces(face_to_cross, labelled_grid(SIZE / 10, SIZE / 18))


def curves(elements):
    hatch = load(elements, "hatch.svg")
    grid_tex = GridPartition(StripesProperties(pi / 4, SIZE / 10), StripesProperties(pi / 2 + pi / 4, SIZE / 10),
                             KEEP_OUTSIDE)

    def face_to_hatch(f):
        e1 = Scale(hatch, Random(f, 1.3, 1.4, 0))
        e2 = Rotate(e1, pi / 4 + Random(f, -pi / 12, pi / 12, 1))
        return MatchPoint(e2, BBoxCenter(hatch), Centroid(f))

    return MapToFaces(face_to_hatch, grid_tex)


def clusters(elements):
    circle = load(elements, "dot.svg")
    lines = StripesProperties(pi / 2, SIZE / 10)
    SetFaceLabels(lines, "v1", "v2")
    stripes_tex = StripesPartition(lines)

    def face_to_circle(f):
        return Scale(MatchPoint(circle, BBoxCenter(circle), Centroid(f)), 0.02)

    def face_to_circles(f):
        # A sub-scale uniform partition in one band of two, a dot in each of its cells.
        if not HasLabel(f, "v2"):
            return Nothing()
        part = UniformPartition(IrregularProperties(100 / (BBoxWidth(f) * BBoxHeight(f))), CROP_ADD_BOUNDARY)
        return MapToFaces(face_to_circle, part)(f)

    return MapToFaces(face_to_circles, stripes_tex)


def overview(elements):
    blob = load(elements, "blob.svg")
    zig = load(elements, "zig.svg")

    def map_blob_to(f):
        b = Rotate(blob, Random(f, 0, 2 * pi, 0))
        return MatchPoint(b, BBoxCenter(b), Centroid(f))

    def map_curve_to(e):
        if IsBoundary(e):
            return ToCurve(e)
        return MatchPoints(zig, PointLabeled(zig, "start"), PointLabeled(zig, "end"),
                           Location(SourceVertex(e)), Location(TargetVertex(e)))

    def map_arrangement_to(f):
        # A randomly oriented grid inside each blob, inner edges drawn as strokes.
        theta = Random(f, 0, 2 * pi, 1)
        width = BBoxWidth(f) / 5
        init = GridPartition(StripesProperties(theta, width), StripesProperties(theta + pi / 2, width),
                             CROP_ADD_BOUNDARY)
        return MapToEdges(map_curve_to, init)(f)

    init_tex = UniformPartition(IrregularProperties(10 / (SIZE * SIZE)), KEEP_OUTSIDE)
    return MapToFaces(map_arrangement_to, MapToFaces(map_blob_to, init_tex))


def squares(elements, theta, width):
    square = load(elements, "square.svg")
    grid_tex = GridPartition(StripesProperties(theta, width), StripesProperties(theta + pi / 2, width), KEEP_OUTSIDE)

    def face_to_square(f):
        # Fitted to the face's box, halved so that turned squares never overlap.
        return Rotate(Scale(MatchFace(square, f), 0.45), Random(f, 0.0, 2 * pi, 1))

    return MapToFaces(face_to_square, grid_tex)


def waves(elements, theta, width):
    wave = load(elements, "wave.svg")

    def line_to_curve(e):
        if IsBoundary(e):
            return Nothing()
        return MatchPoints(wave, PointLabeled(wave, "start"), PointLabeled(wave, "end"),
                           Location(SourceVertex(e)), Location(TargetVertex(e)))

    return MapToEdges(line_to_curve, StripesPartition(StripesProperties(theta, width)))


def circles(elements, density):
    circle = load(elements, "circle.svg")

    def face_to_circle(f):
        return Scale(MatchPoint(circle, BBoxCenter(circle), Centroid(f)), Random(f, 0.5, 1.5, 0))

    return MapToFaces(face_to_circle, UniformPartition(IrregularProperties(density), KEEP_OUTSIDE))


CIRCLES = 8.5e-5


def combine_a(elements):
    return squares(elements, pi / 4, 400)


def combine_b(elements):
    return waves(elements, pi / 6, 80)


def combine_c(elements):
    return circles(elements, CIRCLES)


def combine_d(elements):
    return Union(squares(elements, pi / 4, 400), waves(elements, pi / 6, 80))


def combine_e(elements):
    return Inside(waves(elements, pi / 6, 80), squares(elements, pi / 4, 400), CROP)


def combine_f(elements):
    return Inside(circles(elements, CIRCLES), squares(elements, pi / 4, 400), KEEP_OUTSIDE)


def combine_g(elements):
    return Outside(circles(elements, CIRCLES), squares(elements, pi / 4, 400), CROP)


def combine_h(elements):
    return Outside(circles(elements, CIRCLES), squares(elements, pi / 4, 400), KEEP_INSIDE)


EXAMPLES = {
    "stripes": stripes, "grid": grid, "uniform": uniform, "random": random_, "puzzle": puzzle,
    "rosettes": rosettes, "cracks": cracks, "bimodal": bimodal, "crosses": crosses, "curves": curves,
    "clusters": clusters, "overview": overview,
    "combine_a": combine_a, "combine_b": combine_b, "combine_c": combine_c, "combine_d": combine_d,
    "combine_e": combine_e, "combine_f": combine_f, "combine_g": combine_g, "combine_h": combine_h,
}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="gallery_out")
    ap.add_argument("--only", default="")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--elements", default=ELEMENTS)
    a = ap.parse_args(argv)
    SetThreads(a.threads)
    SetSeed(a.seed)
    names = a.only.split(",") if a.only else list(EXAMPLES)
    unknown = [n for n in names if n not in EXAMPLES]
    if unknown:
        sys.stderr.write(f"gallery.py: unknown example(s) {', '.join(unknown)} (known: {', '.join(EXAMPLES)})\n")
        return 2
    os.makedirs(a.out, exist_ok=True)
    for n in names:
        t0 = time.perf_counter()
        c = ExportSVG(EXAMPLES[n](a.elements), SIZE, os.path.join(a.out, n + ".svg"))
        print("%-10s %7d curves  %8.3f s" % (n, len(c), time.perf_counter() - t0))
    return 0


if __name__ == "__main__":
    sys.exit(main())
