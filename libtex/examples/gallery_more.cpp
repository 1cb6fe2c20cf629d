// "Regular result", "Non regular result" and "Script edition" of the thesis's Appendix A in
// C++ (see gallery_more.hpp for what each one draws). bindings/examples/gallery.py holds
// their Python twins, which must write the same bytes: keep both in step.
#include "gallery_more.hpp"

#include <cmath>

#include "gallery.hpp"

namespace gallery::more {
using namespace tex;

namespace {

Curves load(const std::string& dir, const char* name) { return gallery::element(dir + "/" + name); }

// The stroke `c` stretched from the edge's source to its target ("start" on the source).
Curves stroke_along(const Curves& c, const Edge& e) {
    return MatchPoints(c, PointLabeled(c, "start"), PointLabeled(c, "end"), Location(SourceVertex(e)),
                       Location(TargetVertex(e)));
}
// The same, laid the other way ("end" on the source).
Curves stroke_against(const Curves& c, const Edge& e) {
    return MatchPoints(c, PointLabeled(c, "end"), PointLabeled(c, "start"), Location(SourceVertex(e)),
                       Location(TargetVertex(e)));
}

Curves shrink(const Face& f, double s) { return Scale(Contour(f), s); }

Arrangement square_grid(double a1, double a2, double width, Border b) {
    return GridPartition(StripesProperties(a1, width), StripesProperties(a2, width), b);
}

}  // namespace

// ---- Regular result a ----

Arrangement tilted_tiles() {
    auto turn = [](const Face& f) { return Rotate(Contour(f), pi / 4); };
    auto reduce = [](const Face& f) { return shrink(f, 0.8); };
    return MapToFaces(reduce, MapToFaces(turn, square_grid(0, pi / 2, 200, KEEP_OUTSIDE)));
}

Arrangement regular_a(const std::string&) {
    return Outside(StripesPartition(StripesProperties(0, 15)), tilted_tiles(), CROP);
}

// ---- Regular result b ----

Stripes chevron_lines(double angle, const char* label) {
    Stripes s = StripesProperties(angle, 200);
    const std::string l(label);
    SetEdgeLabels(s, {l + "1", l + "2", l + "3", l + "4"});
    return s;
}

Curves chevron_rule(const Edge& e) {
    // An edge goes when the lines meeting at its target carry a given label: "vi" edges
    // ending on an "hi" line, "hi" edges ending on an "v(i+2)" line.
    const std::vector<Edge> around = IncidentEdges(TargetVertex(e));
    for (int i = 0; i < 4; ++i) {
        const std::string h = "h" + std::to_string(i + 1), v = "v" + std::to_string(i + 1);
        const std::string v2 = "v" + std::to_string((i + 2) % 4 + 1);
        if (HasLabel(e, v) && HasLabel(around, h)) return Nothing();
        if (HasLabel(e, h) && HasLabel(around, v2)) return Nothing();
    }
    return ToCurve(e);
}

Curves chevron_shrink(const Face& f) { return shrink(f, 0.8); }

Curves hatch_tile(const Face& f, double spacing) { return StripesPartition(StripesProperties(0, spacing))(f); }

Curves wobble_stroke(const Curves& wobble, const Edge& e) {
    return IsBoundary(e) ? Nothing() : stroke_along(wobble, e);
}

Arrangement chevron_grid() {
    return MapToEdges(chevron_rule,
                      GridPartition(chevron_lines(pi / 4, "h"), chevron_lines(-pi / 4, "v"), KEEP_OUTSIDE));
}

Arrangement chevron_tiles() { return MapToFaces(chevron_shrink, chevron_grid()); }

Arrangement regular_b(const std::string& dir) {
    return regular_b_on(GridPartition(chevron_lines(pi / 4, "h"), chevron_lines(-pi / 4, "v"), KEEP_OUTSIDE),
                        load(dir, "wobble.svg"), 40);
}

// ---- Regular result c ----

Arrangement wavy_grid(const std::string& dir) {
    const Curves arch = load(dir, "scallop.svg");
    Stripes rows = StripesProperties(0, 200);
    Stripes columns = StripesProperties(pi / 2, 200);
    SetEdgeLabels(rows, {"h1", "h2"});
    SetEdgeLabels(columns, {"h1", "h2"});
    // The outline stays straight; an "h1" line arches one way, an "h2" line the other.
    auto to_arch = [arch](const Edge& e) {
        if (IsBoundary(e)) return ToCurve(e);
        return HasLabel(e, "h1") ? stroke_along(arch, e) : stroke_against(arch, e);
    };
    return Union(MapToEdges(to_arch, StripesPartition(rows)), MapToEdges(to_arch, StripesPartition(columns)));
}

Arrangement wavy_tiles(const std::string& dir) {
    return MapToFaces([](const Face& f) { return shrink(f, 0.9); }, wavy_grid(dir));
}

Arrangement regular_c(const std::string& dir) {
    const Curves ripple = load(dir, "ripple.svg");
    auto hatch = [](const Face& f) { return StripesPartition(StripesProperties(Random(f, 0, 2 * pi, 0), 30))(f); };
    auto to_ripple = [ripple](const Edge& e) { return IsBoundary(e) ? Nothing() : stroke_along(ripple, e); };
    return MapToEdges(to_ripple, MapToFaces(hatch, wavy_tiles(dir)));
}

// ---- Regular result d ----

Arrangement hoop_lattice(const std::string& dir) {
    const Curves hoop = load(dir, "hoop.svg");
    auto ring = [hoop](const Face& f) { return Scale(MatchFace(hoop, f), 2.5); };
    return MapToFaces(ring, square_grid(pi / 2, pi, 200, KEEP_OUTSIDE));
}

Arrangement hoop_pieces(const std::string& dir) {
    return MapToFaces([](const Face& f) { return shrink(f, 0.65); }, hoop_lattice(dir));
}

Arrangement regular_d(const std::string& dir) {
    auto thin_out = [](const Face& f) { return Random(f, 0, 1, 2) < kDropShare ? Nothing() : Contour(f); };
    return MapToFaces(thin_out, hoop_pieces(dir));
}

// ---- Non regular result a ----

Arrangement uniform_cells_100() { return UniformPartition(IrregularProperties(100 / (kSize * kSize)), KEEP_OUTSIDE); }

Arrangement nonregular_a_left(const std::string& dir) {
    const Curves hoop = load(dir, "hoop.svg");
    auto ring = [hoop](const Face& f) { return Scale(MatchFace(hoop, f), Random(f, 0.2, 2.0, 2)); };
    return MapToFaces(ring, uniform_cells_100());
}

std::vector<Arrangement> nest_levels(const std::string& dir) {
    const Curves kink = load(dir, "kink.svg");
    auto to_kink = [kink](const Edge& e) { return stroke_along(kink, e); };
    auto reduce = [](const Face& f) { return shrink(f, 0.8); };
    std::vector<Arrangement> levels = {
        MapToEdges(to_kink, UniformPartition(IrregularProperties(20 / (kSize * kSize)), KEEP_OUTSIDE))};
    while (levels.size() < std::size_t(kNestLevels)) levels.push_back(MapToFaces(reduce, levels.back()));
    return levels;
}

Arrangement nonregular_a_right(const std::string& dir) {
    const std::vector<Arrangement> levels = nest_levels(dir);
    Arrangement all = levels[0];
    for (std::size_t i = 1; i < levels.size(); ++i) all = Union(all, levels[i]);
    return all;
}

// ---- Non regular result b ----

namespace {
Curves jag_inner(const Curves& jag, const Edge& e) { return IsBoundary(e) ? ToCurve(e) : stroke_against(jag, e); }
}  // namespace

Arrangement jagged_cells(const std::string& dir) {
    const Curves jag = load(dir, "jag.svg");
    return MapToEdges([jag](const Edge& e) { return jag_inner(jag, e); },
                      RandomPartition(IrregularProperties(10 / (kSize * kSize)), KEEP_OUTSIDE));
}

Arrangement nonregular_b(const std::string& dir) {
    const Curves jag = load(dir, "jag.svg");
    // A finer random partition in each cell (its own stream, keyed by the cell), with the
    // cell's outline.
    auto split = [](const Face& f) {
        return RandomPartition(IrregularProperties(100 / (kSize * kSize)), CROP_ADD_BOUNDARY)(f);
    };
    return MapToEdges([jag](const Edge& e) { return jag_inner(jag, e); }, MapToFaces(split, jagged_cells(dir)));
}

// ---- Non regular result c ----

Arrangement shrunk_cells(double cells_per_window) {
    return MapToFaces([](const Face& f) { return shrink(f, 0.8); },
                      UniformPartition(IrregularProperties(cells_per_window / (kSize * kSize)), KEEP_OUTSIDE));
}

Arrangement nonregular_c(const std::string&) {
    const Arrangement coarse = shrunk_cells(20);
    const Arrangement fine = shrunk_cells(90);
    return Union(coarse, Inside(fine, coarse, CROP));
}

// ---- Non regular result d ----

Arrangement random_cells_30() { return RandomPartition(IrregularProperties(30 / (kSize * kSize)), KEEP_OUTSIDE); }

Arrangement stretched_edges() {
    return MapToEdges([](const Edge& e) { return Scale(ToCurve(e), 10.0); }, random_cells_30());
}

Arrangement nonregular_d(const std::string&) {
    return MapToEdges([](const Edge& e) { return Rotate(ToCurve(e), pi / 4); }, stretched_edges());
}

// ---- Script edition ----
//
// The thesis draws these in a 2500 window; here they are in the gallery's 2000 one, with
// the grids' widths taken from the window as in the scripts (a quarter, a sixteenth).

namespace {

// A drawing centred on the face's centroid, turned by the face's random stream n.
Curves turned_on_centroid(const Curves& c, const Face& f, double n) {
    const Curves t = Rotate(c, Random(f, 0, 2 * pi, n));
    return MatchPoint(t, BBoxCenter(t), Centroid(f));
}

// Inner edges as strokes, the outline kept.
EdgeMapper inner_strokes(const Curves& stroke) {
    return [stroke](const Edge& e) { return IsBoundary(e) ? ToCurve(e) : stroke_along(stroke, e); };
}

Arrangement sparse_uniform() { return UniformPartition(IrregularProperties(11 / (kSize * kSize)), KEEP_OUTSIDE); }

}  // namespace

Arrangement cloud_layer(const std::string& dir) {
    const Curves cloud = load(dir, "cloud.svg");
    return MapToFaces([cloud](const Face& f) { return turned_on_centroid(cloud, f, 0); }, sparse_uniform());
}

Arrangement script_edit_a(const std::string& dir) {
    const EdgeMapper to_swirl = inner_strokes(load(dir, "swirl.svg"));
    auto fill = [to_swirl](const Face& f) {
        const double theta = Random(f, 0, 2 * pi, 1), width = BBoxWidth(f) / 5;
        return MapToEdges(to_swirl, square_grid(theta, theta + pi / 2, width, CROP_ADD_BOUNDARY))(f);
    };
    return MapToFaces(fill, cloud_layer(dir));
}

Arrangement cloud_grid_layer(const std::string& dir) {
    const Curves cloud = load(dir, "cloud.svg");
    return MapToFaces([cloud](const Face& f) { return turned_on_centroid(cloud, f, 0); },
                      square_grid(0, pi / 2, kSize / 4, KEEP_OUTSIDE));
}

Arrangement script_edit_b(const std::string& dir) {
    const EdgeMapper to_swirl = inner_strokes(load(dir, "swirl.svg"));
    // About 11 cells in each cloud.
    auto fill = [to_swirl](const Face& f) {
        const Arrangement part =
            UniformPartition(IrregularProperties(11 / (BBoxWidth(f) * BBoxHeight(f))), CROP_ADD_BOUNDARY);
        return MapToEdges(to_swirl, part)(f);
    };
    return MapToFaces(fill, cloud_grid_layer(dir));
}

namespace {

// A grid (kEditCell) inside the face, its cells wholly inside it each given `place`.
Curves grid_inside(const Face& f, const FaceMapper& place) {
    return MapToFaces(place, square_grid(0, pi / 2, kEditCell, KEEP_INSIDE))(f);
}

}  // namespace

Arrangement swirled_cells(const std::string& dir) { return MapToEdges(inner_strokes(load(dir, "swirl.svg")), sparse_uniform()); }

Arrangement script_edit_c(const std::string& dir) {
    const Curves pebble = load(dir, "pebble.svg");
    const Arrangement cells = swirled_cells(dir);
    auto fill = [pebble](const Face& f) {
        return grid_inside(f, [pebble](const Face& g) { return turned_on_centroid(pebble, g, 0); });
    };
    return Union(cells, MapToFaces(fill, cells));
}

Arrangement curled_cells(const std::string& dir) { return MapToEdges(inner_strokes(load(dir, "curl.svg")), sparse_uniform()); }

Arrangement script_edit_d(const std::string& dir) {
    const Curves flower = load(dir, "flower.svg"), leaf = load(dir, "leaf.svg");
    const Arrangement cells = curled_cells(dir);
    auto fill = [flower, leaf](const Face& f) {
        return grid_inside(f, [flower, leaf](const Face& g) {
            const Curves fl = Scale(Rotate(flower, Random(g, 0, 2 * pi, 0)), Random(g, 0.7, 1, 1));
            const Curves lf = Scale(Rotate(leaf, Random(g, 0, 2 * pi, 2)), Random(g, 0.7, 1, 3));
            const Curves& pick = Random(g, 0, 1, 4) > 0.5 ? fl : lf;
            return MatchPoint(pick, BBoxCenter(pick), Centroid(g));
        });
    };
    return Union(cells, MapToFaces(fill, cells));
}

// ---- Triangles, Bee hive, wallpaper groups ----

Arrangement lozenges(double a, double b) {
    return GridPartition(StripesProperties(a, 200), StripesProperties(b, 200), KEEP_OUTSIDE);
}

Curves split_diagonal(const Face& f) {
    auto incident = [&f](const Edge& e) { return f == LeftFace(e) || f == RightFace(e); };
    Vertex first, last;
    for (const Vertex& v : IncidentVertices(f)) {
        int starting = 0, ending = 0;
        for (const Edge& e : IncidentEdges(v)) {
            if (v == SourceVertex(e) && incident(e)) ++starting;
            if (v == TargetVertex(e) && incident(e)) ++ending;
        }
        if (starting == 2) first = v;
        if (ending == 2) last = v;
    }
    if (!first.valid() || !last.valid()) return Nothing();
    static const Curves segment = Polyline({{0, 0}, {1, 0}});
    return MatchPoints(segment, {0, 0}, {1, 0}, Location(first), Location(last));
}

namespace {

Arrangement split_lozenges(double a, double b) {
    const Arrangement grid = lozenges(a, b);
    return Union(grid, MapToFaces(split_diagonal, grid));
}

}  // namespace

Arrangement triangles(const std::string&) { return split_lozenges(pi / 3, -pi / 3); }

Arrangement honeycomb(const std::string& dir) {
    auto dual = [](const Edge& e) {
        return IsBoundary(e) ? Nothing() : Polyline({Centroid(LeftFace(e)), Centroid(RightFace(e))});
    };
    return MapToEdges(dual, triangles(dir));
}

Arrangement wallpaper_p6(const std::string& dir) {
    const Curves zee = load(dir, "zee.svg");
    return MapToEdges([zee](const Edge& e) { return stroke_along(zee, e); }, honeycomb(dir));
}

Arrangement wallpaper_p4m(const std::string& dir) {
    const Curves bump = load(dir, "bump.svg");
    const Arrangement grid = lozenges(pi / 4, -pi / 4);
    return Union(MapToEdges([bump](const Edge& e) { return stroke_along(bump, e); }, grid),
                 MapToEdges([bump](const Edge& e) { return stroke_against(bump, e); }, grid));
}

namespace {

// Each triangle cut into three by `bend` (or its mirror image) from its corners to its centroid.
Arrangement subdivided_triangles(const Curves& hook, const Curves& mirror) {
    auto subdivide = [hook, mirror](const Face& f) {
        // Faces with more than one edge running counter-clockwise around them take the
        // mirrored bend.
        int left = 0;
        for (const Edge& e : IncidentEdges(f)) left += f == LeftFace(e);
        const Curves& bend = left > 1 ? mirror : hook;
        Curves out = Nothing();
        for (const Vertex& v : IncidentVertices(f))
            out = Append(out, MatchPoints(bend, PointLabeled(bend, "start"), PointLabeled(bend, "end"), Location(v),
                                          Centroid(f)));
        return out;
    };
    return MapToFaces(subdivide, split_lozenges(pi / 6, pi - pi / 6));
}

}  // namespace

Arrangement wallpaper_p31m(const std::string& dir) {
    return subdivided_triangles(load(dir, "hook.svg"), load(dir, "hook_mirror.svg"));
}

// ---- Escher-like tilings ----

Arrangement fish_outlines(const std::string& dir) {
    const Curves outline = load(dir, "fishline.svg");
    return MapToEdges([outline](const Edge& e) { return stroke_along(outline, e); }, honeycomb(dir));
}

Arrangement fish_insides(const std::string& dir) {
    const Curves inside = load(dir, "fishface.svg");
    // The point 20 to the right of the nose goes on the centroid (the script's
    // `PointLabeled(center_elt, "end") + Point(20.0)`).
    auto place = [inside](const Face& f) {
        return MatchPoint(inside, PointLabeled(inside, "end") + Point(20.0, 0.0), Centroid(f));
    };
    return MapToFaces(place, honeycomb(dir));
}

Arrangement escher_p6(const std::string& dir) { return Union(fish_outlines(dir), fish_insides(dir)); }

Arrangement escher_p4m(const std::string& dir) {
    const Curves octopus = load(dir, "octopus.svg"), guy = load(dir, "guy.svg");
    const Arrangement grid = lozenges(pi / 4, -pi / 4);
    auto on_edge = [octopus](const Edge& e) { return stroke_along(octopus, e); };
    auto on_face = [guy](const Face& f) { return MatchPoint(guy, PointLabeled(guy, "start"), Centroid(f)); };
    return Union(MapToEdges(on_edge, grid), MapToFaces(on_face, grid));
}

Arrangement escher_p31m(const std::string& dir) {
    return subdivided_triangles(load(dir, "wing.svg"), load(dir, "wing_mirror.svg"));
}

}  // namespace gallery::more
