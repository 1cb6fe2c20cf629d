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


# ---- The "Teaser" scripts (a to h); twins of libtex/examples/gallery_teasers.cpp ----

def load_numbered(elements, stem, n):
    return [load(elements, f"{stem}{i}.svg") for i in range(1, n + 1)]


def pick(items, cell, n):
    # One of the items, chosen by the cell's random stream n.
    return items[floor(Random(cell, 0, len(items), n))]


def hatching(angle, width):
    # Stripes `width` apart at `angle`, cropped to whatever face they are evaluated on.
    return StripesPartition(StripesProperties(angle, width))


def lozenge_lattice():
    return GridPartition(StripesProperties(pi / 3, 150), StripesProperties(-pi / 3, 150), KEEP_OUTSIDE)


def lattice_strokes(elements):
    strokes = load_numbered(elements, "tcurve", 4)

    def edge_to_stroke(e):
        # A wavy stroke stretched from the edge's source ("bottom") to its target ("top").
        s = pick(strokes, e, 0)
        return MatchPoints(s, PointLabeled(s, "bottom"), PointLabeled(s, "top"),
                           Location(SourceVertex(e)), Location(TargetVertex(e)))

    return MapToEdges(edge_to_stroke, lozenge_lattice())


def lattice_beads(elements):
    blobs = load_numbered(elements, "tblob", 4)

    def vertex_to_bead(v):
        # A blob centred on the vertex, turned at random.
        b = Rotate(pick(blobs, v, 0), Random(v, 0, 2 * pi, 1))
        return MatchPoint(b, BBoxCenter(b), Location(v))

    return MapToVertices(vertex_to_bead, lozenge_lattice())


def teaser_a(elements):
    # Beads on a curvy lattice: the strokes are cut away under the beads.
    beads = lattice_beads(elements)
    return Union(beads, Outside(lattice_strokes(elements), beads, CROP))


RING_LAYERS = 10


def ring_layer(elements):
    rings = load_numbered(elements, "tring", 3)

    def cell_to_nest(f):
        # Rings nested in the cell, from a random fraction of its box down to nothing.
        nest = Nothing()
        scale = Random(f, 0.3, 0.8, 0)
        i = 0
        while scale > 0:
            ring = Scale(MatchFace(pick(rings, f, 1 + 3 * i), f), scale)
            nest = Append(nest, Rotate(ring, Random(f, 0, 2 * pi, 2 + 3 * i)))
            scale -= Random(f, 0.09, 0.2, 3 + 3 * i)
            i += 1
        return nest

    # Every layer's partition draws its own sites (its own random stream).
    density = 15 / (SIZE * SIZE)
    return MapToFaces(cell_to_nest, UniformPartition(IrregularProperties(density), KEEP_OUTSIDE))


def teaser_b(elements):
    # Stacked tree rings: each new layer hides what lies under its discs.
    stack = ring_layer(elements)
    for _ in range(1, RING_LAYERS):
        top = ring_layer(elements)
        stack = Union(top, Outside(stack, top, CROP))
    return stack


def labelled_bricks_grid():
    rows = StripesProperties(0, 200)
    columns = StripesProperties(pi / 2, 120)
    SetEdgeLabels(rows, "h1", "h2")
    SetEdgeLabels(columns, "v1", "v2", "v3", "v4")
    return GridPartition(rows, columns, KEEP_OUTSIDE)


def keep_brick_joints(e):
    # Horizontal edges stay; below an "h1" line only "v1" joints stay, elsewhere "v2" and "v4".
    if HasLabel(e, "h1") or HasLabel(e, "h2"):
        return ToCurve(e)
    if HasLabel(IncidentEdges(TargetVertex(e)), "h1"):
        kept = HasLabel(e, "v1")
    else:
        kept = HasLabel(e, "v2") or HasLabel(e, "v4")
    return ToCurve(e) if kept else Nothing()


def shrink_brick(f):
    # Long bricks shrink to 90 %, short ones to 80 %.
    return Scale(Contour(f), 0.9 if HasLabel(IncidentEdges(f), "v1") else 0.8)


def brick_courses():
    return MapToEdges(keep_brick_joints, labelled_bricks_grid())


def teaser_c(elements):
    # A wall of long and short bricks.
    return MapToFaces(shrink_brick, brick_courses())


def hatch_cells():
    return UniformPartition(IrregularProperties(1000 / (SIZE * SIZE)), KEEP_OUTSIDE)


def teaser_d(elements):
    groups = load_numbered(elements, "tbighatch", 4)

    def cell_to_group(f):
        # A group of parallel strokes on the cell's centroid, upright one time in two.
        g = pick(groups, f, 0)
        if Random(f, 0, 1, 1) > 0.5:
            g = Rotate(g, pi / 2)
        return MatchPoint(g, BBoxCenter(g), Centroid(f))

    return MapToFaces(cell_to_group, hatch_cells())


def wheels(elements):
    wheel = load(elements, "twheel.svg")

    def cell_to_wheel(f):
        w = Scale(Rotate(wheel, Random(f, 0, 2 * pi, 0)), Random(f, 0.8, 1, 1))
        return MatchPoint(w, BBoxCenter(w), Centroid(f))

    return MapToFaces(cell_to_wheel, UniformPartition(IrregularProperties(100 / (SIZE * SIZE)), KEEP_OUTSIDE))


def stipples(elements):
    stipple = load(elements, "tstipple.svg")

    def cell_to_stipple(f):
        s = Scale(Rotate(stipple, Random(f, 0, 2 * pi, 0)), Random(f, 0.9, 1, 1))
        return MatchPoint(s, BBoxCenter(s), Centroid(f))

    return MapToFaces(cell_to_stipple, RandomPartition(IrregularProperties(1200 / (SIZE * SIZE)), KEEP_OUTSIDE))


def teaser_e(elements):
    # Wheels, and the stipple's pieces lying wholly outside them.
    w = wheels(elements)
    return Union(w, Outside(stipples(elements), w, KEEP_INSIDE))


def shards():
    def shrink(f):
        return Scale(Contour(f), 0.95)

    return MapToFaces(shrink, RandomPartition(IrregularProperties(30 / (SIZE * SIZE)), KEEP_OUTSIDE))


def teaser_f(elements):
    def fill(f):
        # Stripes at the shard's own random angle, closed by its outline...
        return hatching(Random(f, 0, 2 * pi, 1), 40)(f)

    def drop_outline(e):
        # ...whose edges, on the outer face, then go.
        return Nothing() if IsBoundary(e) else ToCurve(e)

    return MapToEdges(drop_outline, MapToFaces(fill, shards()))


def basket_cells():
    rows = StripesProperties(0, 200)
    columns = StripesProperties(pi / 2, 200)
    SetFaceLabels(rows, "h1", "h2")
    SetFaceLabels(columns, "v1", "v2")
    return GridPartition(rows, columns, KEEP_OUTSIDE)


def teaser_g(elements):
    cracks = [load(elements, "line1.svg"), load(elements, "line2.svg")]

    def line_to_crack(e):
        # The cell's outline stays straight; inner lines become cracks, laid either way.
        if IsBoundary(e):
            return ToCurve(e)
        c = pick(cracks, e, 0)
        src, dst = PointLabeled(c, "start"), PointLabeled(c, "end")
        if Random(e, 0, 1, 1) >= 0.5:
            src, dst = dst, src
        return MatchPoints(c, src, dst, Location(SourceVertex(e)), Location(TargetVertex(e)))

    def cell_to_weave(f):
        # Four to six stripes, horizontal or vertical like a checkerboard.
        width = BBoxWidth(f) / Random(f, 4, 6, 0)
        upright = (HasLabel(f, "h1") and HasLabel(f, "v1")) or (HasLabel(f, "h2") and HasLabel(f, "v2"))
        return MapToEdges(line_to_crack, hatching(pi / 2 if upright else 0, width))(f)

    return MapToFaces(cell_to_weave, basket_cells())


def teaser_h(elements):
    rows = StripesProperties(0, 300)
    SetFaceLabels(rows, "h1", "h2")
    columns = StripesProperties(pi / 2, 300)
    SetFaceLabels(columns, "v1", "v2")
    fine_rows = StripesProperties(0, 100, 100, 100, 300)
    SetFaceLabels(fine_rows, "h1", "h2", "h3", "h4")
    fine_columns = StripesProperties(pi / 2, 100, 100, 100, 300)
    SetFaceLabels(fine_columns, "v1", "v2", "v3", "v4")

    def rows_hatch(f):
        return hatching(-pi / 4, 30)(f) if HasLabel(f, "h1") else Nothing()

    def columns_hatch(f):
        return hatching(pi / 4, 30)(f) if HasLabel(f, "v1") else Nothing()

    def grid_hatch(f):
        # Fine vertical hatching in the first narrow row and column of every period.
        return hatching(pi / 2, 10)(f) if HasLabel(f, "h1") or HasLabel(f, "v1") else Nothing()

    bands = Union(MapToFaces(rows_hatch, StripesPartition(rows)), MapToFaces(columns_hatch, StripesPartition(columns)))
    return Union(bands, MapToFaces(grid_hatch, GridPartition(fine_rows, fine_columns, KEEP_OUTSIDE)))



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


# ---- "Regular result", "Non regular result", "Script edition"; twins of libtex/examples/gallery_more.cpp ----

def stroke_along(c, e):
    return MatchPoints(c, PointLabeled(c, "start"), PointLabeled(c, "end"), Location(SourceVertex(e)),
                       Location(TargetVertex(e)))


def stroke_against(c, e):
    return MatchPoints(c, PointLabeled(c, "end"), PointLabeled(c, "start"), Location(SourceVertex(e)),
                       Location(TargetVertex(e)))


def shrink(f, s):
    return Scale(Contour(f), s)


def square_grid(a1, a2, width, border):
    return GridPartition(StripesProperties(a1, width), StripesProperties(a2, width), border)


def tilted_tiles():
    # Each 200 grid cell turned by 45 degrees, then every face of that drawing shrunk.
    def turn(f):
        return Rotate(Contour(f), pi / 4)

    return MapToFaces(lambda f: shrink(f, 0.8), MapToFaces(turn, square_grid(0, pi / 2, 200, KEEP_OUTSIDE)))


def regular_a(elements):
    return Outside(StripesPartition(StripesProperties(0, 15)), tilted_tiles(), CROP)


def chevron_rule(e):
    # "vi" edges ending on an "hi" line go, and "hi" edges ending on a "v(i+2)" line.
    around = IncidentEdges(TargetVertex(e))
    for i in range(4):
        h, v, v2 = "h%d" % (i + 1), "v%d" % (i + 1), "v%d" % ((i + 2) % 4 + 1)
        if HasLabel(e, v) and HasLabel(around, h):
            return Nothing()
        if HasLabel(e, h) and HasLabel(around, v2):
            return Nothing()
    return ToCurve(e)


def chevron_grid():
    rising = StripesProperties(pi / 4, 200)
    falling = StripesProperties(-pi / 4, 200)
    SetEdgeLabels(rising, "h1", "h2", "h3", "h4")
    SetEdgeLabels(falling, "v1", "v2", "v3", "v4")
    return MapToEdges(chevron_rule, GridPartition(rising, falling, KEEP_OUTSIDE))


def chevron_tiles():
    return MapToFaces(lambda f: shrink(f, 0.8), chevron_grid())


def regular_b(elements):
    wobble = load(elements, "wobble.svg")

    def hatch(f):
        return StripesPartition(StripesProperties(0, 40))(f)

    def to_stroke(e):
        return Nothing() if IsBoundary(e) else stroke_along(wobble, e)

    return MapToEdges(to_stroke, MapToFaces(hatch, chevron_tiles()))


def wavy_grid(elements):
    arch = load(elements, "scallop.svg")
    rows = StripesProperties(0, 200)
    columns = StripesProperties(pi / 2, 200)
    SetEdgeLabels(rows, "h1", "h2")
    SetEdgeLabels(columns, "h1", "h2")

    def to_arch(e):
        if IsBoundary(e):
            return ToCurve(e)
        return stroke_along(arch, e) if HasLabel(e, "h1") else stroke_against(arch, e)

    return Union(MapToEdges(to_arch, StripesPartition(rows)), MapToEdges(to_arch, StripesPartition(columns)))


def wavy_tiles(elements):
    return MapToFaces(lambda f: shrink(f, 0.9), wavy_grid(elements))


def regular_c(elements):
    ripple = load(elements, "ripple.svg")

    def hatch(f):
        return StripesPartition(StripesProperties(Random(f, 0, 2 * pi, 0), 30))(f)

    def to_ripple(e):
        return Nothing() if IsBoundary(e) else stroke_along(ripple, e)

    return MapToEdges(to_ripple, MapToFaces(hatch, wavy_tiles(elements)))


def hoop_lattice(elements):
    hoop = load(elements, "hoop.svg")
    return MapToFaces(lambda f: Scale(MatchFace(hoop, f), 2.5), square_grid(pi / 2, pi, 200, KEEP_OUTSIDE))


def hoop_pieces(elements):
    return MapToFaces(lambda f: shrink(f, 0.65), hoop_lattice(elements))


def regular_d(elements):
    def thin_out(f):
        return Nothing() if Random(f, 0, 1, 2) < 0.3 else Contour(f)

    return MapToFaces(thin_out, hoop_pieces(elements))


def nonregular_a_left(elements):
    hoop = load(elements, "hoop.svg")
    cells = UniformPartition(IrregularProperties(100 / (SIZE * SIZE)), KEEP_OUTSIDE)
    return MapToFaces(lambda f: Scale(MatchFace(hoop, f), Random(f, 0.2, 2.0, 2)), cells)


def nonregular_a_right(elements):
    kink = load(elements, "kink.svg")
    # Level 1: kinked cells; each next level: the faces of the previous one shrunk.
    levels = [MapToEdges(lambda e: stroke_along(kink, e),
                         UniformPartition(IrregularProperties(20 / (SIZE * SIZE)), KEEP_OUTSIDE))]
    while len(levels) < 10:
        levels.append(MapToFaces(lambda f: shrink(f, 0.8), levels[-1]))
    out = levels[0]
    for level in levels[1:]:
        out = Union(out, level)
    return out


def jag_inner(jag, e):
    return ToCurve(e) if IsBoundary(e) else stroke_against(jag, e)


def nonregular_b(elements):
    jag = load(elements, "jag.svg")
    cells = MapToEdges(lambda e: jag_inner(jag, e),
                       RandomPartition(IrregularProperties(10 / (SIZE * SIZE)), KEEP_OUTSIDE))

    def split(f):
        return RandomPartition(IrregularProperties(100 / (SIZE * SIZE)), CROP_ADD_BOUNDARY)(f)

    return MapToEdges(lambda e: jag_inner(jag, e), MapToFaces(split, cells))


def shrunk_cells(cells_per_window):
    return MapToFaces(lambda f: shrink(f, 0.8),
                      UniformPartition(IrregularProperties(cells_per_window / (SIZE * SIZE)), KEEP_OUTSIDE))


def nonregular_c(elements):
    coarse = shrunk_cells(20)
    fine = shrunk_cells(90)
    return Union(coarse, Inside(fine, coarse, CROP))


def nonregular_d(elements):
    cells = RandomPartition(IrregularProperties(30 / (SIZE * SIZE)), KEEP_OUTSIDE)
    stretched = MapToEdges(lambda e: Scale(ToCurve(e), 10.0), cells)
    return MapToEdges(lambda e: Rotate(ToCurve(e), pi / 4), stretched)


def turned_on_centroid(c, f, n):
    t = Rotate(c, Random(f, 0, 2 * pi, n))
    return MatchPoint(t, BBoxCenter(t), Centroid(f))


def inner_strokes(stroke):
    return lambda e: ToCurve(e) if IsBoundary(e) else stroke_along(stroke, e)


def sparse_uniform():
    return UniformPartition(IrregularProperties(11 / (SIZE * SIZE)), KEEP_OUTSIDE)


def script_edit_a(elements):
    cloud = load(elements, "cloud.svg")
    to_swirl = inner_strokes(load(elements, "swirl.svg"))
    clouds = MapToFaces(lambda f: turned_on_centroid(cloud, f, 0), sparse_uniform())

    def fill(f):
        theta, width = Random(f, 0, 2 * pi, 1), BBoxWidth(f) / 5
        return MapToEdges(to_swirl, square_grid(theta, theta + pi / 2, width, CROP_ADD_BOUNDARY))(f)

    return MapToFaces(fill, clouds)


def script_edit_b(elements):
    cloud = load(elements, "cloud.svg")
    to_swirl = inner_strokes(load(elements, "swirl.svg"))
    clouds = MapToFaces(lambda f: turned_on_centroid(cloud, f, 0), square_grid(0, pi / 2, SIZE / 4, KEEP_OUTSIDE))

    def fill(f):
        part = UniformPartition(IrregularProperties(11 / (BBoxWidth(f) * BBoxHeight(f))), CROP_ADD_BOUNDARY)
        return MapToEdges(to_swirl, part)(f)

    return MapToFaces(fill, clouds)


def grid_inside(f, place):
    return MapToFaces(place, square_grid(0, pi / 2, 125, KEEP_INSIDE))(f)


def script_edit_c(elements):
    pebble = load(elements, "pebble.svg")
    cells = MapToEdges(inner_strokes(load(elements, "swirl.svg")), sparse_uniform())

    def fill(f):
        return grid_inside(f, lambda g: turned_on_centroid(pebble, g, 0))

    return Union(cells, MapToFaces(fill, cells))


def script_edit_d(elements):
    flower, leaf = load(elements, "flower.svg"), load(elements, "leaf.svg")
    cells = MapToEdges(inner_strokes(load(elements, "curl.svg")), sparse_uniform())

    def place(g):
        fl = Scale(Rotate(flower, Random(g, 0, 2 * pi, 0)), Random(g, 0.7, 1, 1))
        lf = Scale(Rotate(leaf, Random(g, 0, 2 * pi, 2)), Random(g, 0.7, 1, 3))
        pick = fl if Random(g, 0, 1, 4) > 0.5 else lf
        return MatchPoint(pick, BBoxCenter(pick), Centroid(g))

    return Union(cells, MapToFaces(lambda f: grid_inside(f, place), cells))


def lozenges(a, b):
    return GridPartition(StripesProperties(a, 200), StripesProperties(b, 200), KEEP_OUTSIDE)


SEGMENT = Polyline([Point(0, 0), Point(1, 0)])


def split_diagonal(face):
    # A segment from the vertex where both of the face's edges start to the one where both
    # end (MatchPoints lands exactly on the two vertices, so the bar splits the face).
    def incident(e):
        return face == LeftFace(e) or face == RightFace(e)

    first = last = None
    for v in IncidentVertices(face):
        starting = ending = 0
        for e in IncidentEdges(v):
            if v == SourceVertex(e) and incident(e):
                starting += 1
            if v == TargetVertex(e) and incident(e):
                ending += 1
        if starting == 2:
            first = v
        if ending == 2:
            last = v
    if first is None or last is None:
        return Nothing()
    return MatchPoints(SEGMENT, Point(0, 0), Point(1, 0), Location(first), Location(last))


def split_lozenges(a, b):
    grid = lozenges(a, b)
    return Union(grid, MapToFaces(split_diagonal, grid))


def triangles(elements):
    return split_lozenges(pi / 3, -pi / 3)


def bee_hive(elements):
    def dual(e):
        return Nothing() if IsBoundary(e) else Polyline([Centroid(LeftFace(e)), Centroid(RightFace(e))])

    return MapToEdges(dual, triangles(elements))


def wallpaper_p6(elements):
    zee = load(elements, "zee.svg")
    return MapToEdges(lambda e: stroke_along(zee, e), bee_hive(elements))


def wallpaper_p4m(elements):
    bump = load(elements, "bump.svg")
    grid = lozenges(pi / 4, -pi / 4)
    return Union(MapToEdges(lambda e: stroke_along(bump, e), grid), MapToEdges(lambda e: stroke_against(bump, e), grid))


def subdivided_triangles(hook, mirror):
    def subdivide(f):
        # Faces with more than one edge running counter-clockwise around them take the mirror.
        left = sum(1 for e in IncidentEdges(f) if f == LeftFace(e))
        bend = mirror if left > 1 else hook
        out = Nothing()
        for v in IncidentVertices(f):
            out = Append(out, MatchPoints(bend, PointLabeled(bend, "start"), PointLabeled(bend, "end"), Location(v),
                                          Centroid(f)))
        return out

    return MapToFaces(subdivide, split_lozenges(pi / 6, pi - pi / 6))


def wallpaper_p31m(elements):
    return subdivided_triangles(load(elements, "hook.svg"), load(elements, "hook_mirror.svg"))


def escher_p6(elements):
    outline, inside = load(elements, "fishline.svg"), load(elements, "fishface.svg")
    outlines = MapToEdges(lambda e: stroke_along(outline, e), bee_hive(elements))

    def place(f):
        # The point 20 to the right of the nose on the centroid.
        return MatchPoint(inside, PointLabeled(inside, "end") + Point(20.0, 0.0), Centroid(f))

    return Union(outlines, MapToFaces(place, bee_hive(elements)))


def escher_p4m(elements):
    octopus, guy = load(elements, "octopus.svg"), load(elements, "guy.svg")
    grid = lozenges(pi / 4, -pi / 4)
    return Union(MapToEdges(lambda e: stroke_along(octopus, e), grid),
                 MapToFaces(lambda f: MatchPoint(guy, PointLabeled(guy, "start"), Centroid(f)), grid))


def escher_p31m(elements):
    return subdivided_triangles(load(elements, "wing.svg"), load(elements, "wing_mirror.svg"))


# ---- Filling an outline (ExportSVGinDomain): the texture cut to a frame in the window ----

PARQUET_RULES = [
    ("v1", "v2", "h1"), ("v2", "v3", "h1"), ("v3", "v4", "h1"), ("v4", "v1", "h1"),
    ("v1", "v2", "h3"), ("v2", "v3", "h3"), ("v3", "v4", "h3"), ("v4", "v1", "h3"),
    ("h1", "h2", "v1"), ("h2", "h3", "v1"), ("h3", "h4", "v3"), ("h4", "h1", "v3"),
    ("v2", "v3", "h2"), ("v3", "v4", "h2"), ("v4", "v1", "h4"), ("v1", "v2", "h4"),
]


def parquetry(elements):
    def parquetry_structure(e):
        faces = [LeftFace(e), RightFace(e)]
        if not faces[0].is_bounded_face() or not faces[1].is_bounded_face():
            return ToCurve(e)
        for rule in PARQUET_RULES:
            if all(HasLabel(faces, l) for l in rule):
                return Nothing()
        return ToCurve(e)

    scale = 50
    gap = 0.2 * scale
    lines1 = StripesProperties(0.0, scale, gap, scale, gap)
    SetFaceLabels(lines1, "h1", "h2", "h3", "h4")
    lines2 = StripesProperties(pi / 6 + pi / 32 + pi / 100, 8 * scale, gap, 8 * scale, gap)
    SetFaceLabels(lines2, "v1", "v2", "v3", "v4")
    part = GridPartition(lines1, lines2, KEEP_OUTSIDE)
    return InDomain(MapToEdges(parquetry_structure, part), load(elements, "carpet_outline.svg"))


def place_jittered(items, v, angle, dx, dy):
    loc = Location(v) + Point(Random(v, -dx, dx, 1), Random(v, -dy, dy, 2))
    elem = Rotate(items[min(len(items) - 1, int(math.floor(Random(v, 0.0, float(len(items)), 3))))], angle)
    return MatchPoint(elem, BBoxCenter(elem), loc)


def table(elements):
    grains = [load(elements, "table_grain%d.svg" % i) for i in (1, 2, 3)]
    side = 0.0
    part = GridPartition(StripesProperties(side + pi / 3, 60), StripesProperties(side + 2 * pi / 3, 150), KEEP_OUTSIDE)
    texture = MapToVertices(lambda v: place_jittered(grains, v, side, 20, 80), part)
    return InDomain(texture, load(elements, "table_top.svg"))


def bottle(elements):
    bubbles = [load(elements, "fizz%d.svg" % i) for i in (1, 2, 3, 4)]
    side = pi / 2
    part = GridPartition(StripesProperties(side + pi / 3, 60), StripesProperties(side + 2 * pi / 3, 60), KEEP_OUTSIDE)
    texture = MapToVertices(lambda v: place_jittered(bubbles, v, side, 20, 40), part)
    return InDomain(texture, load(elements, "bottle_outline.svg"))


def teapot(elements):
    ring = load(elements, "pot_ring.svg")

    def face_to_ring(f):
        return Scale(MatchPoint(ring, BBoxCenter(ring), Centroid(f)), Random(f, 0.05, 0.15, 0))

    part = UniformPartition(IrregularProperties(3.0e-4), KEEP_OUTSIDE)
    return InDomain(MapToFaces(face_to_ring, part), load(elements, "teapot_outline.svg"))


# ---- Microprocessor: traces, chips and solder joints ----

MP_STEP = 50.0
# The thesis's densities, thinned out 100 times (at its values every grid point of the
# window would get nearly every trace); the density index of each of the twelve traces.
MP_DENSITIES = [0.002, 0.00175, 0.00125, 0.00225, 0.001]
MP_THINNING = 100.0
MP_TRACE_DENSITY = [0, 0, 1, 0, 1, 1, 2, 1, 0, 3, 3, 4]


def mp_snap(p):
    return Point(MP_STEP * math.floor(p.x / MP_STEP), MP_STEP * math.floor(p.y / MP_STEP))


def microprocessor(elements):
    def trace_layer(i):
        trace = load(elements, "mp_net%d.svg" % i)
        start = PointLabeled(trace, "start")
        density = MP_DENSITIES[MP_TRACE_DENSITY[i - 1]] / MP_THINNING
        return MapToFaces(lambda f: MatchPoint(trace, start, mp_snap(Centroid(f))),
                          RandomPartition(IrregularProperties(density), KEEP_OUTSIDE))

    level1 = trace_layer(1)
    for i in range(2, 13):
        level1 = Merge(level1, trace_layer(i))

    kinds = [load(elements, "mp_ship%d.svg" % k) for k in range(1, 7)]

    def face_to_chip(f):
        k = min(len(kinds) - 1, int(math.floor(Random(f, 0.0, float(len(kinds)), 0))))
        s = 1 + math.floor(Random(f, 0.0, 4.0, 1))  # the thesis: floor(Random(f, 0, 4, 0)), 0 for no chip
        chip = Scale(kinds[k], s)
        return MatchPoint(chip, BBoxCenter(chip), mp_snap(Centroid(f)))

    level2 = MapToFaces(face_to_chip, UniformPartition(IrregularProperties(8.0 / (2000.0 * 2000.0)), KEEP_OUTSIDE))

    connector = load(elements, "mp_connector.svg")
    joint = load(elements, "mp_joint.svg")

    def pads(v):
        if len(IncidentEdges(v)) == 3 and HasLabel(IncidentFaces(v), "ship"):
            return MatchPoint(connector, BBoxCenter(connector), Location(v))
        if len(IncidentEdges(v)) == 1:
            return MatchPoint(joint, BBoxCenter(joint), Location(v))
        return Nothing()

    board = Outside(level1, level2, CROP_ADD_BOUNDARY)
    return Outside(board, MapToVertices(pads, board), CROP_ADD_BOUNDARY)


def oriented_darts(elements):
    # The control field: at every point, the direction of the image's centre.
    centre = Point(SIZE / 2, SIZE / 2)
    to_centre = Angle(VectorField(lambda p: centre - p))

    # Controlled mapper: a face mapper for a given orientation field.
    def turned_element(element):
        def with_field(angle):
            def place(face):
                c = Centroid(face)
                turned = Rotate(element, angle(c))
                return MatchPoint(turned, BBoxCenter(turned), c)
            return place
        return with_field

    # Controlled arrangement: the mapper on each face of a uniform partition.
    def turned_elements(element, density):
        mapper = turned_element(element)
        return lambda angle: MapToFaces(mapper(angle), UniformPartition(IrregularProperties(density), KEEP_OUTSIDE))

    return turned_elements(load(elements, "dart.svg"), 1e-4)(to_centre)


# ---- Tiled planar maps (Fig. 4.5): one period of a wall, made semi-regular by ghost mappers ----

def tiled_wall(elements):
    pebble = load(elements, "pebble.svg")
    rows = StripesProperties(0, 200)
    columns = StripesProperties(pi / 2, 120)
    SetEdgeLabels(rows, "h1", "h2")
    SetEdgeLabels(columns, "v1", "v2", "v3", "v4")

    def brick(f):
        # Teaser c's brick, a pebble in each long one.
        c = shrink_brick(f)
        if HasLabel(IncidentEdges(f), "v1"):
            c = Append(c, Scale(MatchFace(pebble, f), 0.35))
        return c

    return MapToFaces(brick, MapToEdges(keep_brick_joints, GridPartition(rows, columns, Tiled(CROP))))


def tiled_a(elements):
    return tiled_wall(elements)


def tiled_b(elements):
    def jitter(e):
        turned = Rotate(Scale(e.curves, Random(e, 0.75, 1.0, 0)), Random(e, -0.12, 0.12, 1))
        return Translate(turned, Point(Random(e, -18, 18, 2), Random(e, -12, 12, 3)))

    return GhostMap(jitter, tiled_wall(elements))


def tiled_c(elements):
    return GhostMap(lambda e: Nothing() if Random(e, 0, 1, 0) < 0.35 else e.curves, tiled_wall(elements))


def cluster_field(p):
    return 0.5 + 0.35 * math.sin(p.x / 210.0 + 0.7) * math.sin(p.y / 160.0 + 1.9) + 0.1 * math.sin((p.x + 2 * p.y) / 390.0)


def tiled_d(elements):
    def cluster(e):
        v = cluster_field(e.anchor) + Random(e, -0.08, 0.08, 0)
        if v < 0.45:
            return Nothing()
        return Scale(e.curves, min(1.0, 0.5 + (v - 0.45) * 2.5))

    return GhostMap(cluster, tiled_wall(elements))
# ---- Topology-constrained synthesis (seed 002), twins of libtex/examples/gallery_synthesis.cpp ----

SYNTH_RANDOMNESS = 0.3
SYNTH_GROUPING = 0.03


def synth_ring(r, n):
    return Polyline([Point(1000 + r * math.cos(2 * pi * i / n), 1000 + r * math.sin(2 * pi * i / n))
                     for i in range(n)], True)


def synth_wave(y, amplitude, n):
    xs = [150 + 1700.0 * i / n for i in range(n + 1)]
    return Polyline([Point(x, y + amplitude * math.sin(2 * pi * (x - 150) / 850)) for x in xs], False)


def synth_circle(elements):
    vine = load(elements, "synth_vine.svg")
    c = SynthesizeAlongCurve(vine, synth_ring(750, 360), 150, components=1, closed_pattern=True,
                             event_grouping=SYNTH_GROUPING, randomness=SYNTH_RANDOMNESS)
    c.append(SynthesizeAlongCurve(vine, synth_ring(430, 360), 120, components=1, holes=0,
                                  event_grouping=SYNTH_GROUPING, randomness=SYNTH_RANDOMNESS))
    return Constant(c)


def synth_curve(elements):
    vine = load(elements, "synth_vine.svg")
    c = SynthesizeAlongCurve(vine, synth_wave(650, 180, 400), 130, components=1,
                             event_grouping=SYNTH_GROUPING, randomness=SYNTH_RANDOMNESS)
    c.append(SynthesizeAlongCurve(vine, synth_wave(1350, 180, 400), 130, components=1, holes=0,
                                  event_grouping=SYNTH_GROUPING, randomness=SYNTH_RANDOMNESS))
    return Constant(c)


def synth_rectangle(elements):
    ladder = load(elements, "synth_ladder.svg")
    c = SynthesizeInRectangle(ladder, 1600, 1600, 160, components=1, event_grouping=SYNTH_GROUPING,
                              randomness=SYNTH_RANDOMNESS)
    return Constant(Translate(c, Point(200, 200)))


EXAMPLES = {
    "stripes": stripes, "grid": grid, "uniform": uniform, "random": random_, "puzzle": puzzle,
    "rosettes": rosettes, "cracks": cracks, "bimodal": bimodal, "crosses": crosses, "curves": curves,
    "clusters": clusters, "overview": overview,
    "teaser_a": teaser_a, "teaser_b": teaser_b, "teaser_c": teaser_c, "teaser_d": teaser_d,
    "teaser_e": teaser_e, "teaser_f": teaser_f, "teaser_g": teaser_g, "teaser_h": teaser_h,
    "combine_a": combine_a, "combine_b": combine_b, "combine_c": combine_c, "combine_d": combine_d,
    "combine_e": combine_e, "combine_f": combine_f, "combine_g": combine_g, "combine_h": combine_h,
    "regular_a": regular_a, "regular_b": regular_b, "regular_c": regular_c, "regular_d": regular_d,
    "nonregular_a_left": nonregular_a_left, "nonregular_a_right": nonregular_a_right,
    "nonregular_b": nonregular_b, "nonregular_c": nonregular_c, "nonregular_d": nonregular_d,
    "script_edit_a": script_edit_a, "script_edit_b": script_edit_b, "script_edit_c": script_edit_c,
    "script_edit_d": script_edit_d,
    "triangles": triangles, "bee_hive": bee_hive, "wallpaper_p6": wallpaper_p6, "wallpaper_p4m": wallpaper_p4m,
    "wallpaper_p31m": wallpaper_p31m, "escher_p6": escher_p6, "escher_p4m": escher_p4m, "escher_p31m": escher_p31m,
    "parquetry": parquetry, "table": table, "bottle": bottle, "teapot": teapot,
    "microprocessor": microprocessor,
    "tiled_a": tiled_a,
    "tiled_b": tiled_b,
    "tiled_c": tiled_c,
    "tiled_d": tiled_d,
    "oriented_darts": oriented_darts,
}
# Seed 004's figures, written with rockhatch.discrete (discrete_gallery.py).
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import discrete_gallery  # noqa: E402

EXAMPLES.update(discrete_gallery.EXAMPLES)
sys.path.pop(0)
# Seed 002: synthesis along curves and in a rectangle, in the C++ gallery's order.
EXAMPLES.update({"synth_circle": synth_circle, "synth_curve": synth_curve, "synth_rectangle": synth_rectangle})


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
        SetSeed(a.seed)  # each example numbers its partitions' streams from the start
        c = ExportSVG(EXAMPLES[n](a.elements), SIZE, os.path.join(a.out, n + ".svg"))
        print("%-10s %7d curves  %8.3f s" % (n, len(c), time.perf_counter() - t0))
    return 0


if __name__ == "__main__":
    sys.exit(main())
