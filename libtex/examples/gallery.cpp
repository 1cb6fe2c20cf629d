// Appendix A of the thesis, script by script, in C++. The comments give each script's
// intent; the elements in elements/ are the project's own drawings.
#include "gallery.hpp"

#include <atomic>
#include <cmath>
#include <optional>

#include "gallery_discrete.hpp"
#include "gallery_domain.hpp"
#include "gallery_fields.hpp"
#include "gallery_micro.hpp"
#include "gallery_synthesis.hpp"
#include "gallery_more.hpp"
#include "gallery_teasers.hpp"
#include "gallery_tiled.hpp"

namespace gallery {
using namespace tex;

namespace {

Curves load(const std::string& dir, const std::string& name) { return element(dir + "/" + name); }

std::atomic<int> g_detail{1};

// The points of one curve k times finer (see element()).
std::vector<Point> finer(const std::vector<Point>& p, bool closed, int k) {
    const std::size_t n = p.size();
    if (n < 2 || k < 2) return p;
    auto at = [&](std::ptrdiff_t i) -> std::optional<Point> {
        if (closed) return p[std::size_t((i % std::ptrdiff_t(n) + std::ptrdiff_t(n)) % std::ptrdiff_t(n))];
        if (i < 0 || i >= std::ptrdiff_t(n)) return std::nullopt;
        return p[std::size_t(i)];
    };
    // The unit tangent at vertex i, or none at a corner (or an open curve's end).
    auto tangent = [&](std::ptrdiff_t i) -> std::optional<Point> {
        const auto a = at(i - 1), b = at(i + 1);
        if (!a || !b) return std::nullopt;
        const Point u = p[std::size_t(i % std::ptrdiff_t(n))] - *a, v = *b - p[std::size_t(i % std::ptrdiff_t(n))];
        const double lu = norm(u), lv = norm(v);
        if (lu == 0 || lv == 0 || dot(u, v) < std::cos(40 * pi / 180) * lu * lv) return std::nullopt;
        const Point t = *b - *a;
        return t / norm(t);
    };
    std::vector<Point> out;
    const std::size_t nseg = closed ? n : n - 1;
    out.reserve(nseg * std::size_t(k) + 1);
    for (std::size_t i = 0; i < nseg; ++i) {
        const Point a = p[i], b = p[(i + 1) % n], chord = b - a;
        const double len = norm(chord);
        const auto ta = tangent(std::ptrdiff_t(i)), tb = tangent(std::ptrdiff_t(i + 1));
        const Point m0 = ta ? *ta * len : chord, m1 = tb ? *tb * len : chord;
        out.push_back(a);
        for (int j = 1; j < k; ++j) {
            const double t = double(j) / k, t2 = t * t, t3 = t2 * t;
            out.push_back(a * (2 * t3 - 3 * t2 + 1) + m0 * (t3 - 2 * t2 + t) + b * (-2 * t3 + 3 * t2) +
                          m1 * (t3 - t2));
        }
    }
    if (!closed) out.push_back(p.back());
    return out;
}


Arrangement stripes(const std::string&) {
    // Stripes at 45 degrees with a cycle of two widths (200 and 67).
    return StripesPartition(StripesProperties(pi / 4, kSize / 10, kSize / 30));
}

Arrangement grid(const std::string&) {
    Stripes h = StripesProperties(0, kSize / 10, kSize / 25);
    Stripes v = StripesProperties(pi / 2, kSize / 8);
    return GridPartition(h, v, KEEP_OUTSIDE);
}

Arrangement uniform(const std::string&) {
    return UniformPartition(IrregularProperties(50 / (kSize * kSize)), KEEP_OUTSIDE);
}

Arrangement random_(const std::string&) {
    return RandomPartition(IrregularProperties(50 / (kSize * kSize)), KEEP_OUTSIDE);
}

Arrangement puzzle(const std::string& dir) {
    const Curves zig = load(dir, "zig2.svg");
    Stripes l1 = StripesProperties(0.0, kSize / 16);
    Stripes l2 = StripesProperties(pi / 2, kSize / 16);
    SetEdgeLabels(l1, {"h1", "h2"});
    SetEdgeLabels(l2, {"v1", "v2"});
    Arrangement grid_tex = GridPartition(l1, l2, KEEP_OUTSIDE);
    // Drop every other vertical edge, staggered from row to row: a brick wall.
    auto grid_to_wall = [](const Edge& e) {
        const auto around = IncidentEdges(TargetVertex(e));
        if ((HasLabel(e, "v1") && HasLabel(around, "h1")) || (HasLabel(e, "v2") && HasLabel(around, "h2")))
            return Nothing();
        return ToCurve(e);
    };
    // Replace each edge by the tab curve, facing a random side.
    auto edge_to_curve = [zig](const Edge& e) {
        const Point sc = PointLabeled(zig, "start"), dc = PointLabeled(zig, "end");
        const Point sv = Location(SourceVertex(e)), dv = Location(TargetVertex(e));
        if (Random(e, 0, 1, 0) < 0.5) return MatchPoints(zig, sc, dc, sv, dv);
        return MatchPoints(zig, sc, dc, dv, sv);
    };
    return MapToEdges(edge_to_curve, MapToEdges(grid_to_wall, grid_tex));
}

Arrangement rosettes(const std::string& dir) {
    const Curves line = load(dir, "line.svg");
    const Curves circle = load(dir, "circle.svg");
    Arrangement part = UniformPartition(IrregularProperties(70 / (kSize * kSize)), KEEP_OUTSIDE);
    // A four-line star on each face centroid.
    auto face_to_star = [line](const Face& f) {
        const double rot = Random(f, 0.0, 2 * pi, 0);
        const Curves e1 = MatchPoint(line, BBoxCenter(line), Centroid(f));
        const Curves e2 = Append(Rotate(e1, rot), Rotate(e1, rot + pi / 2));
        return Append(e2, Rotate(e2, pi / 4));
    };
    // A circle on each free end of the star's lines.
    auto vertex_to_circle = [circle](const Vertex& v) {
        if (IncidentEdges(v).size() > 1) return Nothing();
        return MatchPoint(circle, BBoxCenter(circle), Location(v));
    };
    return MapToVertices(vertex_to_circle, MapToFaces(face_to_star, part));
}

Arrangement cracks(const std::string& dir) {
    const std::vector<Curves> lines = {load(dir, "line1.svg"), load(dir, "line2.svg"), load(dir, "line3.svg")};
    Arrangement part = RandomPartition(IrregularProperties(200 / (kSize * kSize)), KEEP_OUTSIDE);
    auto rescale_face = [](const Face& f) { return Scale(Contour(f), 0.8); };
    auto edge_to_curve = [lines](const Edge& e) {
        const Curves& l = lines[std::size_t(std::floor(Random(e, 0, double(lines.size()), 0)))];
        return MatchPoints(l, PointLabeled(l, "start"), PointLabeled(l, "end"),
                           Location(SourceVertex(e)), Location(TargetVertex(e)));
    };
    return MapToEdges(edge_to_curve, MapToFaces(rescale_face, part));
}

// Checkerboard selection shared by the bimodal hatching and regular crosses examples.
bool one_face_in_two(const Face& f) {
    return (HasLabel(f, "v1") && HasLabel(f, "h1")) || (HasLabel(f, "v2") && HasLabel(f, "h2"));
}

Arrangement labelled_grid(double w1, double w2) {
    Stripes l1 = StripesProperties(0, w1);
    Stripes l2 = StripesProperties(pi / 2, w2);
    SetFaceLabels(l1, {"h1", "h2"});
    SetFaceLabels(l2, {"v1", "v2"});
    return GridPartition(l1, l2, KEEP_OUTSIDE);
}

Arrangement bimodal(const std::string& dir) {
    const Curves hatch = load(dir, "hatch.svg");
    // Two crossing hatches in one face of two, jittered.
    auto face_to_hatches = [hatch](const Face& f) {
        if (!one_face_in_two(f)) return Nothing();
        const Curves e1 = Scale(hatch, Random(f, 2.6, 2.7, 1));
        const Curves e2 = Rotate(e1, pi / 7 + Random(f, -pi / 12, pi / 12, 2));
        const Curves e3 = Rotate(e1, pi / 2 + Random(f, -pi / 12, pi / 12, 3));
        const Curves e4 = Append(e2, e3);
        const double w = BBoxWidth(f) / 7, h = BBoxHeight(f) / 7;
        const Point pos = Centroid(f) + Point(Random(f, -w, w, 4), Random(f, -h, h, 5));
        return MatchPoint(e4, BBoxCenter(e4), pos);
    };
    return MapToFaces(face_to_hatches, labelled_grid(kSize / 10, kSize / 20));
}

Arrangement crosses(const std::string& dir) {
    const Curves cross = load(dir, "cross.svg");
    auto face_to_cross = [cross](const Face& f) {
        if (!one_face_in_two(f)) return Nothing();
        const Curves e1 = Scale(cross, Random(f, 1.35, 1.45, 2));
        const Curves e2 = Rotate(e1, Random(f, -pi / 20, pi / 20, 4));
        return MatchPoint(e2, BBoxCenter(e2), BBoxCenter(f));
    };
    return MapToFaces(face_to_cross, labelled_grid(kSize / 10, kSize / 18));
}

Arrangement curves(const std::string& dir) {
    const Curves hatch = load(dir, "hatch.svg");
    Arrangement grid_tex = GridPartition(StripesProperties(pi / 4, kSize / 10),
                                         StripesProperties(pi / 2 + pi / 4, kSize / 10), KEEP_OUTSIDE);
    auto face_to_hatch = [hatch](const Face& f) {
        const Curves e1 = Scale(hatch, Random(f, 1.3, 1.4, 0));
        const Curves e2 = Rotate(e1, pi / 4 + Random(f, -pi / 12, pi / 12, 1));
        return MatchPoint(e2, BBoxCenter(hatch), Centroid(f));
    };
    return MapToFaces(face_to_hatch, grid_tex);
}

Arrangement clusters(const std::string& dir) {
    const Curves circle = load(dir, "dot.svg");
    Stripes lines = StripesProperties(pi / 2, kSize / 10);
    SetFaceLabels(lines, {"v1", "v2"});
    Arrangement stripes_tex = StripesPartition(lines);
    auto face_to_circle = [circle](const Face& f) {
        return Scale(MatchPoint(circle, BBoxCenter(circle), Centroid(f)), 0.02);
    };
    // A sub-scale uniform partition of one stripe in two, a dot in each of its cells.
    auto face_to_circles = [face_to_circle](const Face& f) {
        if (!HasLabel(f, "v2")) return Nothing();
        Arrangement part = UniformPartition(IrregularProperties(100 / (BBoxWidth(f) * BBoxHeight(f))),
                                            CROP_ADD_BOUNDARY);
        return MapToFaces(face_to_circle, part)(f);
    };
    return MapToFaces(face_to_circles, stripes_tex);
}

Arrangement overview(const std::string& dir) {
    const Curves blob = load(dir, "blob.svg");
    const Curves zig = load(dir, "zig.svg");
    auto map_blob_to = [blob](const Face& f) {
        const Curves b = Rotate(blob, Random(f, 0, 2 * pi, 0));
        return MatchPoint(b, BBoxCenter(b), Centroid(f));
    };
    auto map_curve_to = [zig](const Edge& e) {
        if (IsBoundary(e)) return ToCurve(e);
        return MatchPoints(zig, PointLabeled(zig, "start"), PointLabeled(zig, "end"),
                           Location(SourceVertex(e)), Location(TargetVertex(e)));
    };
    // A randomly oriented grid inside each blob, its inner edges replaced by strokes.
    auto map_arrangement_to = [map_curve_to](const Face& f) {
        const double theta = Random(f, 0, 2 * pi, 1);
        const double width = BBoxWidth(f) / 5;
        Arrangement init = GridPartition(StripesProperties(theta, width),
                                         StripesProperties(theta + pi / 2, width), CROP_ADD_BOUNDARY);
        return MapToEdges(map_curve_to, init)(f);
    };
    Arrangement init_tex = UniformPartition(IrregularProperties(10 / (kSize * kSize)), KEEP_OUTSIDE);
    return MapToFaces(map_arrangement_to, MapToFaces(map_blob_to, init_tex));
}

}  // namespace

// The "Combining" examples: three textures and their merges.
Arrangement squares(const std::string& dir, double theta, double width) {
    const Curves square = load(dir, "square.svg");
    Arrangement grid_tex = GridPartition(StripesProperties(theta, width), StripesProperties(theta + pi / 2, width),
                                         KEEP_OUTSIDE);
    // A rounded square in each face (fitted to its box, then halved, so that squares
    // turned at random never overlap), turned at random.
    auto face_to_square = [square](const Face& f) {
        return Rotate(Scale(MatchFace(square, f), 0.45), Random(f, 0.0, 2 * pi, 1));
    };
    return MapToFaces(face_to_square, grid_tex);
}

Arrangement waves(const std::string& dir, double theta, double width) {
    const Curves wave = load(dir, "wave.svg");
    // Each inner line of the stripes becomes a wave; the outline goes.
    auto line_to_curve = [wave](const Edge& e) {
        if (IsBoundary(e)) return Nothing();
        return MatchPoints(wave, PointLabeled(wave, "start"), PointLabeled(wave, "end"), Location(SourceVertex(e)),
                           Location(TargetVertex(e)));
    };
    return MapToEdges(line_to_curve, StripesPartition(StripesProperties(theta, width)));
}

Arrangement circles(const std::string& dir, double density) {
    const Curves circle = load(dir, "circle.svg");
    auto face_to_circle = [circle](const Face& f) {
        return Scale(MatchPoint(circle, BBoxCenter(circle), Centroid(f)), Random(f, 0.5, 1.5, 0));
    };
    return MapToFaces(face_to_circle, UniformPartition(IrregularProperties(density), KEEP_OUTSIDE));
}

namespace {

constexpr double kCircles = 8.5e-5;

// An example that places no element.
template <Arrangement (*F)()>
Arrangement no_elements(const std::string&) {
    return F();
}

// Combining a to c: each of the three textures on its own.
Arrangement combine_squares(const std::string& dir) { return squares(dir, pi / 4, 400); }
Arrangement combine_waves(const std::string& dir) { return waves(dir, pi / 6, 80); }
Arrangement combine_circles(const std::string& dir) { return circles(dir, kCircles); }

Arrangement combine_union(const std::string& dir) { return Union(squares(dir, pi / 4, 400), waves(dir, pi / 6, 80)); }
Arrangement combine_inside_crop(const std::string& dir) {
    return Inside(waves(dir, pi / 6, 80), squares(dir, pi / 4, 400), CROP);
}
Arrangement combine_inside_keep(const std::string& dir) {
    return Inside(circles(dir, kCircles), squares(dir, pi / 4, 400), KEEP_OUTSIDE);
}
Arrangement combine_outside_crop(const std::string& dir) {
    return Outside(circles(dir, kCircles), squares(dir, pi / 4, 400), CROP);
}
Arrangement combine_outside_keep(const std::string& dir) {
    return Outside(circles(dir, kCircles), squares(dir, pi / 4, 400), KEEP_INSIDE);
}

}  // namespace

const std::vector<Example>& examples() {
    static const std::vector<Example> all = {
        {"stripes", "Stripes", 0, stripes},
        {"grid", "Grid", 0, grid},
        {"uniform", "Uniform", 2, uniform},
        {"random", "Random", 0, random_},
        {"puzzle", "Puzzle", 18, puzzle},
        {"rosettes", "Rosettes", 36, rosettes},
        {"cracks", "Cracks", 35, cracks},
        {"bimodal", "By example limitations: bimodal hatching", 7, bimodal},
        {"crosses", "By example limitations: regular crosses", 6, crosses},
        {"curves", "By example limitations: regular curves", 4, curves},
        {"clusters", "By example limitations: clusters", 42, clusters},
        {"overview", "Overview (Fig. 3.1)", -1, overview},
        {"teaser_a", "Teaser a: beads on a curvy lattice", 25, teasers::beads_on_strokes},
        {"teaser_b", "Teaser b: stacked tree rings", 129, teasers::stacked_rings},
        {"teaser_c", "Teaser c: a wall of long and short bricks", 1, no_elements<teasers::shrunk_bricks>},
        {"teaser_d", "Teaser d: woven hatching", 220, teasers::woven_hatching},
        {"teaser_e", "Teaser e: wheels in a stipple field", 20, teasers::wheels_in_stipple},
        {"teaser_f", "Teaser f: hatched shards", 3, no_elements<teasers::hatched_shards>},
        {"teaser_g", "Teaser g: cracked basket weave", 6, teasers::cracked_basket},
        {"teaser_h", "Teaser h: plaid", 26, no_elements<teasers::plaid>},
        {"combine_a", "Combining a: squares", 1, combine_squares},
        {"combine_b", "Combining b: waves", 1, combine_waves},
        {"combine_c", "Combining c: circles", 13, combine_circles},
        {"combine_d", "Combining d: Union(squares, waves)", 4, combine_union},
        {"combine_e", "Combining e: waves Inside squares (CROP)", 3, combine_inside_crop},
        {"combine_f", "Combining f: circles Inside squares (KEEP_OUTSIDE)", 15, combine_inside_keep},
        {"combine_g", "Combining g: circles Outside squares (CROP)", 15, combine_outside_crop},
        {"combine_h", "Combining h: circles Outside squares (KEEP_INSIDE)", 15, combine_outside_keep},
        {"regular_a", "Regular result a: hatching between tilted tiles", 30, more::regular_a},
        {"regular_b", "Regular result b: chevrons of wobbly hatching", 39, more::regular_b},
        {"regular_c", "Regular result c: a wavy grid hatched at random angles", 30, more::regular_c},
        {"regular_d", "Regular result d: pieces of overlapping rings, some missing", 25, more::regular_d},
        {"nonregular_a_left", "Non regular result a (left): rings of random sizes", 6, more::nonregular_a_left},
        {"nonregular_a_right", "Non regular result a (right): nested outlines", 29, more::nonregular_a_right},
        {"nonregular_b", "Non regular result b: random cells within random cells", 12, more::nonregular_b},
        {"nonregular_c", "Non regular result c: fine cells inside coarse cells", 30, more::nonregular_c},
        {"nonregular_d", "Non regular result d: stretched and turned edges", 88, more::nonregular_d},
        {"script_edit_a", "Script edition a: the original script", 25, more::script_edit_a},
        {"script_edit_b", "Script edition b: partitions switched", 52, more::script_edit_b},
        {"script_edit_c", "Script edition c: arrangements switched", 12, more::script_edit_c},
        {"script_edit_d", "Script edition d: mappings varied", 56, more::script_edit_d},
        {"triangles", "Triangles: lozenges split along a diagonal", 4, more::triangles},
        {"bee_hive", "Bee hive: the dual of the triangles", 5, more::honeycomb},
        {"wallpaper_p6", "Wallpaper group P6: a honeycomb of Z-shaped kinks", 48, more::wallpaper_p6},
        {"wallpaper_p4m", "Wallpaper group P4M: bumps laid both ways on a square grid", 24, more::wallpaper_p4m},
        {"wallpaper_p31m", "Wallpaper group P31M: triangles cut into three by S-bends", 50, more::wallpaper_p31m},
        {"escher_p6", "Escher P6: fish on a honeycomb", 38, more::escher_p6},
        {"escher_p4m", "Escher P4M: octopuses and little men", 43, more::escher_p4m},
        {"escher_p31m", "Escher P31M: triangles cut by feathered bends", 35, more::escher_p31m},
        {"parquetry", "Parquetry: slats of a floor filling its outline", 20, domain::parquetry},
        {"table", "Table: wood grain filling an oval table top", 45, domain::table},
        {"bottle", "Bottle: bubbles filling a bottle", 11, domain::bottle},
        {"teapot", "Teapot: dots of random sizes filling a teapot", 22, domain::teapot},
        {"microprocessor", "Microprocessor: traces, chips and solder joints", 54, micro::microprocessor},
        {"tiled_a", "Tiled planar map (Fig. 4.5 a): a regular wall", -1, tiled::regular_wall},
        {"tiled_b", "Tiled planar map (Fig. 4.5 b): bricks jittered by a ghost mapper", -1, tiled::jittered_wall},
        {"tiled_c", "Tiled planar map (Fig. 4.5 c): bricks deleted at random", -1, tiled::thinned_wall},
        {"tiled_d", "Tiled planar map (Fig. 4.5 d): clusters of bricks", -1, tiled::clustered_wall},
        {"oriented_darts", "Control field: darts turned towards the centre (Fig. 5.2)", -1, fields::darts},
        {"discrete_1a", "Seed 004 Fig. 1a: anisotropic dart throwing", -1, discrete::arrangement_1a},
        {"discrete_1b", "Seed 004 Fig. 1b: constrained dart throwing", -1, discrete::arrangement_1b},
        {"discrete_1c", "Seed 004 Fig. 1c: 1b with orthogonal hatches", -1, discrete::arrangement_1c},
        {"discrete_1d", "Seed 004 Fig. 1d: user shapes, variable scaling", -1, discrete::arrangement_1d},
        {"discrete_1e", "Seed 004 Fig. 1e: scaled Voronoi cells of relaxed circles", -1, discrete::arrangement_1e},
        {"discrete_1f", "Seed 004 Fig. 1f: relaxed circles and stream lines", -1, discrete::arrangement_1f},
        {"discrete_1g", "Seed 004 Fig. 1g: interlocked stream lines", -1, discrete::arrangement_1g},
        {"synth_circle", "Synthesis (seed 002): vine round a circle, one component", -1, synthesis::circle},
        {"synth_curve", "Synthesis (seed 002): vine along waves, one component, no holes", -1, synthesis::curve},
        {"synth_rectangle", "Synthesis (seed 002): a ladder filling a square, one component", -1, synthesis::rectangle},
    };
    return all;
}

const Example& find(const std::string& name) {
    for (const auto& e : examples())
        if (e.name == name) return e;
    throw tex::Error("gallery", "no example named '" + name + "'");
}

std::string default_elements_dir() { return RH_GALLERY_ELEMENTS; }

Curves element(const std::string& path) {
    Curves c = ImportSVG(path);
    const int k = g_detail.load();
    if (k > 1)
        for (Curve& cv : c.curves) cv.points = finer(cv.points, cv.closed, k);
    return c;
}

void SetElementDetail(int k) {
    if (k < 1) throw tex::Error("SetElementDetail", "the detail must be at least 1, not " + std::to_string(k));
    g_detail.store(k);
}

int ElementDetail() { return g_detail.load(); }

}  // namespace gallery
