// The eight "Teaser" scripts of the thesis's Appendix A in C++ (see gallery_teasers.hpp
// for what each one draws). bindings/examples/gallery.py holds their Python twins, which
// must write the same bytes: keep both in step.
#include "gallery_teasers.hpp"

#include <cmath>
#include <vector>

#include "gallery.hpp"

namespace gallery::teasers {
using namespace tex;

namespace {

std::vector<Curves> load_all(const std::string& dir, const char* stem, int n) {
    std::vector<Curves> out;
    for (int i = 1; i <= n; ++i) out.push_back(gallery::element(dir + "/" + stem + std::to_string(i) + ".svg"));
    return out;
}

// One of `items`, chosen by the cell's random stream n.
template <class C>
const Curves& pick(const std::vector<Curves>& items, const C& cell, double n) {
    return items[std::size_t(std::floor(Random(cell, 0, double(items.size()), n)))];
}

// Stripes at `angle`, `width` apart, cropped to whatever face they are evaluated on.
Arrangement hatching(double angle, double width) { return StripesPartition(StripesProperties(angle, width)); }

}  // namespace

// ---- Teaser a ----

Arrangement lozenge_lattice() {
    return GridPartition(StripesProperties(pi / 3, 150), StripesProperties(-pi / 3, 150), KEEP_OUTSIDE);
}

Arrangement lattice_strokes(const std::string& dir) {
    const std::vector<Curves> strokes = load_all(dir, "tcurve", 4);
    // Every edge of the lattice becomes one of the wavy strokes, stretched from its source
    // vertex ("bottom") to its target vertex ("top").
    auto edge_to_stroke = [strokes](const Edge& e) {
        const Curves& s = pick(strokes, e, 0);
        return MatchPoints(s, PointLabeled(s, "bottom"), PointLabeled(s, "top"), Location(SourceVertex(e)),
                           Location(TargetVertex(e)));
    };
    return MapToEdges(edge_to_stroke, lozenge_lattice());
}

Arrangement lattice_beads(const std::string& dir) {
    const std::vector<Curves> blobs = load_all(dir, "tblob", 4);
    // Every vertex gets one of the blobs, centred on it and turned at random.
    auto vertex_to_bead = [blobs](const Vertex& v) {
        const Curves b = Rotate(pick(blobs, v, 0), Random(v, 0, 2 * pi, 1));
        return MatchPoint(b, BBoxCenter(b), Location(v));
    };
    return MapToVertices(vertex_to_bead, lozenge_lattice());
}

Arrangement beads_on_strokes(const std::string& dir) {
    // The beads over the strokes: what the beads' discs cover is cut away.
    const Arrangement beads = lattice_beads(dir);
    return Union(beads, Outside(lattice_strokes(dir), beads, CROP));
}

// ---- Teaser b ----

Arrangement ring_layer(const std::string& dir) {
    const std::vector<Curves> rings = load_all(dir, "tring", 3);
    // A nest of rings in each cell: the outer one fitted to the cell's box and reduced at
    // random, then smaller and smaller ones, each a random one of the three drawings
    // turned at random, until the scale runs out.
    auto cell_to_nest = [rings](const Face& f) {
        Curves nest = Nothing();
        double scale = Random(f, 0.3, 0.8, 0);
        for (int i = 0; scale > 0; ++i) {
            const Curves ring = Scale(MatchFace(pick(rings, f, 1 + 3 * i), f), scale);
            nest = Append(nest, Rotate(ring, Random(f, 0, 2 * pi, 2 + 3 * i)));
            scale -= Random(f, 0.09, 0.2, 3 + 3 * i);
        }
        return nest;
    };
    // About 15 cells in the window; every layer's partition draws its own sites (its own
    // random stream), so the ten layers differ.
    const double density = 15 / (kSize * kSize);
    return MapToFaces(cell_to_nest, UniformPartition(IrregularProperties(density), KEEP_OUTSIDE));
}

Arrangement stacked_rings(const std::string& dir) {
    // Each new layer on top of the stack, hiding what lies under its discs.
    Arrangement stack = ring_layer(dir);
    for (int layer = 1; layer < kRingLayers; ++layer) {
        const Arrangement top = ring_layer(dir);
        stack = Union(top, Outside(stack, top, CROP));
    }
    return stack;
}

// ---- Teaser c ----

Stripes brick_rows() {
    Stripes rows = StripesProperties(0, 200);
    SetEdgeLabels(rows, {"h1", "h2"});
    return rows;
}

Stripes brick_columns() {
    Stripes columns = StripesProperties(pi / 2, 120);
    SetEdgeLabels(columns, {"v1", "v2", "v3", "v4"});
    return columns;
}

Arrangement labelled_bricks_grid() { return GridPartition(brick_rows(), brick_columns(), KEEP_OUTSIDE); }

// Horizontal edges all stay. A vertical edge whose upper (target) end meets an "h1" line
// stays only on "v1" columns (one in four: long bricks); the others stay only on "v2" and
// "v4" columns (one in two: short bricks).
Curves keep_brick_joints(const Edge& e) {
    if (HasLabel(e, "h1") || HasLabel(e, "h2")) return ToCurve(e);
    const bool long_course = HasLabel(IncidentEdges(TargetVertex(e)), "h1");
    const bool kept = long_course ? HasLabel(e, "v1") : HasLabel(e, "v2") || HasLabel(e, "v4");
    return kept ? ToCurve(e) : Nothing();
}

// Long bricks (bounded by "v1" joints) shrink to 90 %, short ones to 80 %.
Curves shrink_brick(const Face& f) { return Scale(Contour(f), HasLabel(IncidentEdges(f), "v1") ? 0.9 : 0.8); }

Arrangement brick_courses() { return MapToEdges(keep_brick_joints, labelled_bricks_grid()); }

Arrangement shrunk_bricks() { return MapToFaces(shrink_brick, brick_courses()); }

// ---- Teaser d ----

Arrangement hatch_cells() { return UniformPartition(IrregularProperties(1000 / (kSize * kSize)), KEEP_OUTSIDE); }

Arrangement woven_hatching(const std::string& dir) {
    const std::vector<Curves> groups = load_all(dir, "tbighatch", 4);
    // One of the stroke groups on each cell's centroid, turned upright one time in two.
    auto cell_to_group = [groups](const Face& f) {
        Curves g = pick(groups, f, 0);
        if (Random(f, 0, 1, 1) > 0.5) g = Rotate(g, pi / 2);
        return MatchPoint(g, BBoxCenter(g), Centroid(f));
    };
    return MapToFaces(cell_to_group, hatch_cells());
}

// ---- Teaser e ----

Arrangement wheels(const std::string& dir) {
    const Curves wheel = gallery::element(dir + "/twheel.svg");
    // About 100 cells; a wheel on each, turned at random and slightly reduced at random.
    auto cell_to_wheel = [wheel](const Face& f) {
        const Curves w = Scale(Rotate(wheel, Random(f, 0, 2 * pi, 0)), Random(f, 0.8, 1, 1));
        return MatchPoint(w, BBoxCenter(w), Centroid(f));
    };
    return MapToFaces(cell_to_wheel, UniformPartition(IrregularProperties(100 / (kSize * kSize)), KEEP_OUTSIDE));
}

Arrangement stipples(const std::string& dir) {
    const Curves stipple = gallery::element(dir + "/tstipple.svg");
    // About 1200 cells; a dot cluster on each, turned at random.
    auto cell_to_stipple = [stipple](const Face& f) {
        const Curves s = Scale(Rotate(stipple, Random(f, 0, 2 * pi, 0)), Random(f, 0.9, 1, 1));
        return MatchPoint(s, BBoxCenter(s), Centroid(f));
    };
    return MapToFaces(cell_to_stipple, RandomPartition(IrregularProperties(1200 / (kSize * kSize)), KEEP_OUTSIDE));
}

Arrangement wheels_in_stipple(const std::string& dir) {
    // The wheels, and the stipple's pieces lying wholly outside them.
    const Arrangement w = wheels(dir);
    return Union(w, Outside(stipples(dir), w, KEEP_INSIDE));
}

// ---- Teaser f ----

Arrangement shards() {
    // About 30 cells, each shrunk about its box's centre so that gaps open between them.
    auto shrink = [](const Face& f) { return Scale(Contour(f), 0.95); };
    return MapToFaces(shrink, RandomPartition(IrregularProperties(30 / (kSize * kSize)), KEEP_OUTSIDE));
}

Arrangement hatched_shards() {
    // Stripes 40 apart at a random angle in each shard (with the shard's outline, which
    // closes them)...
    auto fill = [](const Face& f) { return hatching(Random(f, 0, 2 * pi, 1), 40)(f); };
    // ...then every edge on the outer face goes: the outlines, not the stripes.
    auto drop_outline = [](const Edge& e) { return IsBoundary(e) ? Nothing() : ToCurve(e); };
    return MapToEdges(drop_outline, MapToFaces(fill, shards()));
}

// ---- Teaser g ----

Arrangement basket_cells() {
    Stripes rows = StripesProperties(0, 200);
    Stripes columns = StripesProperties(pi / 2, 200);
    SetFaceLabels(rows, {"h1", "h2"});
    SetFaceLabels(columns, {"v1", "v2"});
    return GridPartition(rows, columns, KEEP_OUTSIDE);
}

Arrangement cracked_basket(const std::string& dir) {
    const std::vector<Curves> cracks = {gallery::element(dir + "/line1.svg"), element(dir + "/line2.svg")};
    // A cell's outline stays straight; a line inside it becomes a crack stroke, one of
    // two drawings, laid one way or the other.
    auto line_to_crack = [cracks](const Edge& e) {
        if (IsBoundary(e)) return ToCurve(e);
        const Curves& c = pick(cracks, e, 0);
        Point from = PointLabeled(c, "start"), to = PointLabeled(c, "end");
        if (Random(e, 0, 1, 1) >= 0.5) std::swap(from, to);
        return MatchPoints(c, from, to, Location(SourceVertex(e)), Location(TargetVertex(e)));
    };
    // Four to six stripes per cell, horizontal or vertical like a checkerboard.
    auto cell_to_weave = [line_to_crack](const Face& f) {
        const double width = BBoxWidth(f) / Random(f, 4, 6, 0);
        const bool upright = (HasLabel(f, "h1") && HasLabel(f, "v1")) || (HasLabel(f, "h2") && HasLabel(f, "v2"));
        return MapToEdges(line_to_crack, hatching(upright ? pi / 2 : 0, width))(f);
    };
    return MapToFaces(cell_to_weave, basket_cells());
}

// ---- Teaser h ----

Arrangement plaid() {
    Stripes rows = StripesProperties(0, 300);
    SetFaceLabels(rows, {"h1", "h2"});
    Stripes columns = StripesProperties(pi / 2, 300);
    SetFaceLabels(columns, {"v1", "v2"});
    Stripes fine_rows = StripesProperties(0, 100, 100, 100, 300);
    SetFaceLabels(fine_rows, {"h1", "h2", "h3", "h4"});
    Stripes fine_columns = StripesProperties(pi / 2, 100, 100, 100, 300);
    SetFaceLabels(fine_columns, {"v1", "v2", "v3", "v4"});

    // Hatching at -45 degrees in one row band of two, at 45 degrees in one column band of
    // two (crossing where they meet)...
    auto rows_hatch = [](const Face& f) { return HasLabel(f, "h1") ? hatching(-pi / 4, 30)(f) : Nothing(); };
    auto columns_hatch = [](const Face& f) { return HasLabel(f, "v1") ? hatching(pi / 4, 30)(f) : Nothing(); };
    // ...and fine vertical hatching in the first narrow row and column of every period
    // of the uneven grid.
    auto grid_hatch = [](const Face& f) {
        return HasLabel(f, "h1") || HasLabel(f, "v1") ? hatching(pi / 2, 10)(f) : Nothing();
    };
    const Arrangement bands = Union(MapToFaces(rows_hatch, StripesPartition(rows)),
                                    MapToFaces(columns_hatch, StripesPartition(columns)));
    return Union(bands, MapToFaces(grid_hatch, GridPartition(fine_rows, fine_columns, KEEP_OUTSIDE)));
}

}  // namespace gallery::teasers
