// Tiled planar maps (thesis Chapter 4): structure, conversion with the four border modes,
// locality, threads, NIZ mapping, shifted-cell adjacency, ghost mapping, union, queries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <utility>

#include "helpers.hpp"
#include "libtex/tex.hpp"
#include "tiled_helpers.hpp"

using namespace tex;

namespace {

// Rows of widths 10 and 20 with three edge labels (6 lines per period: 90), columns of 25
// with two face labels (2 lines per period: 50).
Stripes rows() {
    Stripes s = StripesProperties(0, 10, 20);
    SetEdgeLabels(s, {"r1", "r2", "r3"});
    return s;
}
Stripes columns() {
    Stripes s = StripesProperties(pi / 2, 25);
    SetFaceLabels(s, {"c1", "c2"});
    return s;
}

// Every byte of a set of curves, for same-bytes comparisons.
std::string dump(const Curves& c) {
    std::ostringstream s;
    s.precision(17);
    for (const auto& cv : c.curves) {
        s << cv.closed << th::label_text(cv.labels) << "|" << th::label_text(cv.left) << "|"
          << th::label_text(cv.right);
        for (const auto& p : cv.points) s << " " << p.x << "," << p.y;
        s << "\n";
    }
    for (const auto& p : c.points) s << "p " << p.point.x << "," << p.point.y << th::label_text(p.labels) << "\n";
    return s.str();
}

const Region kWindow = Region::rectangle(-37, -12, 413, 287);
// Its corners on no line of the grids below (a crop through a corner is a degenerate case:
// see CropThroughARegionCorner). x = 400 is a column of columns(), so no corner there.
const Region kTriangle({{-47, -41}, {401, 11}, {61, 333}});

}  // namespace

TEST(Tiled, GridPeriodsFollowTheCycles) {
    const TiledMap t = GridPartition(rows(), columns(), Tiled());
    // Rows: LCM(2 widths, 3 labels) = 6 lines, 6 / 2 * (10 + 20) = 90 across (along y).
    EXPECT_NEAR(t.period1().x, 0, 1e-12);
    EXPECT_NEAR(t.period1().y, 90, 1e-12);
    // Columns: LCM(1, 2) = 2 lines of 25: 50 along x.
    EXPECT_NEAR(std::abs(t.period2().x), 50, 1e-12);
    EXPECT_NEAR(t.period2().y, 0, 1e-12);
    // One element per edge class: 6 x 2 cells, two edges each.
    EXPECT_EQ(t.elements().size(), 24u);
    EXPECT_EQ(t.cells().size(), 12u);
}

TEST(Tiled, BadInputIsAClearError) {
    EXPECT_TEX_ERROR(GridPartition(StripesProperties(0, 10), StripesProperties(pi, 10), Tiled()), "GridPartition",
                     "parallel");
    Stripes bad;
    bad.widths = {-1};
    EXPECT_TEX_ERROR(GridPartition(bad, StripesProperties(1, 10), Tiled()), "GridPartition", "width -1");
    bad.widths = {};
    EXPECT_TEX_ERROR(StripesPartition(bad, Tiled()), "StripesPartition", "no width");
    EXPECT_TEX_ERROR(TiledMap({1, 0}, {2, 0}, {}, CROP), "TiledMap", "colinear");
}

// The conversion of a tiled grid equals the planar-map engine's grid with every border mode,
// on a rectangle and on a triangle.
class TiledModes : public ::testing::TestWithParam<Border> {};

TEST_P(TiledModes, GridConversionMatchesTheEngine) {
    const Border b = GetParam();
    const TiledMap t = GridPartition(rows(), columns(), Tiled(b));
    for (const Region& r : {kWindow, kTriangle}) {
        const Curves engine = GridPartition(rows(), columns(), b)(r);
        const Curves tiled = t(r);
        ASSERT_FALSE(tiled.curves.empty());
        EXPECT_SAME_CURVES(tiled, engine);
    }
}

INSTANTIATE_TEST_SUITE_P(AllModes, TiledModes,
                         ::testing::Values(Border::CROP, Border::CROP_ADD_BOUNDARY, Border::KEEP_INSIDE,
                                           Border::KEEP_OUTSIDE));

// Stripes are stored as line pieces one period long; every mode gives the engine's whole
// lines (KEEP_*: whole bands, each line once from one side of the engine's box to the other).
TEST_P(TiledModes, StripesConversionGivesTheEnginesWholeLines) {
    const Border b = GetParam();
    Stripes s = StripesProperties(pi / 5, 12, 30);
    SetFaceLabels(s, {"a", "b", "c"});
    SetEdgeLabels(s, {"x", "y"});
    const TiledMap t = StripesPartition(s, Tiled(b));
    for (const Region& r : {kWindow, kTriangle}) {
        const Curves tiled = t(r), engine = StripesPartition(s, b)(r);
        if (b != KEEP_INSIDE) ASSERT_GT(tiled.curves.size(), 10u);
        EXPECT_SAME_CURVES(tiled, engine);
        // No two curves of the output on one line of the stripes: in CROP, where the tiled
        // map joins its one-period pieces (the KEEP modes hand the stripes to the engine
        // whole), each line crossing these convex regions is one curve.
        std::set<long long> lines;
        std::size_t labelled = 0;
        for (const auto& c : tiled.curves)
            if (c.labels.has("x") || c.labels.has("y")) {
                ++labelled;
                lines.insert(std::llround(cross(c.points.back() - c.points.front(), c.points.front()) /
                                          norm(c.points.back() - c.points.front())));
            }
        if (b == CROP) {
            EXPECT_GT(labelled, 5u);
            EXPECT_EQ(lines.size(), labelled);
            EXPECT_EQ(labelled, tiled.curves.size());
        } else if (b != CROP_ADD_BOUNDARY) {
            EXPECT_EQ(lines.size(), tiled.curves.size());
        }
    }
}

TEST(Tiled, StripesInAKeepModeAreWholeBandsNotCopies) {
    // Stripes' faces are infinite bands, which no copy of a one-period element can stand
    // for: in a KEEP mode the tiled map hands them to the engine. What must come out, found
    // here from the widths alone: KEEP_OUTSIDE keeps every band that meets the region, so its
    // lines run from the last line at or below the region's lowest offset along the normal to
    // the first at or above its highest, one whole line each (x at 42 m, y at 42 m + 12), its
    // ends outside the region; KEEP_INSIDE keeps no band of a bounded region.
    Stripes s = StripesProperties(pi / 5, 12, 30);
    SetEdgeLabels(s, {"x", "y"});
    const TiledMap t = StripesPartition(s, Tiled());
    const Point n{-std::sin(pi / 5), std::cos(pi / 5)};
    for (const Region& r : {kWindow, kTriangle}) {
        double lo = INFINITY, hi = -INFINITY;
        for (const Point& v : r.outer()) lo = std::min(lo, dot(v, n)), hi = std::max(hi, dot(v, n));
        std::map<long long, std::string> expected;  // offset -> label
        for (long long m = (long long)std::floor(lo / 42) - 1; m <= (long long)std::ceil(hi / 42) + 1; ++m)
            for (const auto& [offset, label] : {std::pair{42.0 * m, "x"}, std::pair{42.0 * m + 12, "y"}})
                expected[std::llround(offset)] = label;
        const double first = double(std::prev(expected.upper_bound((long long)std::floor(lo)))->first);
        const double last = double(expected.lower_bound((long long)std::ceil(hi))->first);
        for (auto it = expected.begin(); it != expected.end();)
            it = (it->first < first || it->first > last) ? expected.erase(it) : std::next(it);
        ASSERT_GT(expected.size(), 10u);

        const Curves outside = t.Convert(r, KEEP_OUTSIDE);
        std::map<long long, std::string> got;
        for (const auto& c : outside.curves) {
            ASSERT_EQ(c.points.size(), 2u);
            const double offset = dot(c.points.front(), n);
            EXPECT_NEAR(dot(c.points.back(), n), offset, 1e-6);
            EXPECT_NEAR(offset, std::round(offset), 1e-6);
            EXPECT_FALSE(r.contains(c.points.front()));
            EXPECT_FALSE(r.contains(c.points.back()));
            EXPECT_TRUE(got.emplace(std::llround(offset), c.labels.has("x") ? "x" : c.labels.has("y") ? "y" : "?").second)
                << "two curves on the line at " << offset;
        }
        EXPECT_EQ(got, expected);
        EXPECT_TRUE(t.Convert(r, KEEP_INSIDE).curves.empty());
    }
}

TEST(Tiled, StripesSameBytesAtOneAndTwoThreads) {
    Stripes s = StripesProperties(pi / 5, 12, 30);
    SetFaceLabels(s, {"a", "b", "c"});
    const TiledMap t = StripesPartition(s, Tiled());
    for (Border b : {CROP, CROP_ADD_BOUNDARY, KEEP_INSIDE, KEEP_OUTSIDE}) {
        std::string one, two;
        {
            ThreadsScope scope(1);
            one = dump(t.Convert(kTriangle, b));
        }
        {
            ThreadsScope scope(2);
            two = dump(t.Convert(kTriangle, b));
        }
        EXPECT_EQ(one, two) << border_name(b);
    }
}

TEST(Tiled, StripesLinesStayWholeThroughAUnion) {
    // Stripes of period 36 with a grid of 40 x 90 along them: the common period along the
    // lines is 360, ten pieces of the stripes' own; the lines still come out whole.
    const Stripes s = StripesProperties(0, 12, 24);
    const TiledMap u = Union(StripesPartition(s, Tiled(CROP)), GridPartition(StripesProperties(0, 40), StripesProperties(pi / 2, 90), Tiled(CROP)));
    const Curves engine = Union(StripesPartition(s, CROP), GridPartition(StripesProperties(0, 40), StripesProperties(pi / 2, 90), CROP))(kWindow);
    EXPECT_SAME_CURVES(u(kWindow), engine);
    std::string one, two;
    {
        ThreadsScope t(1);
        one = dump(u(kTriangle));
    }
    {
        ThreadsScope t(2);
        two = dump(u(kTriangle));
    }
    EXPECT_EQ(one, two);
}

TEST(Tiled, ConversionIsLocal) {
    // The edges as curves (a mapped map: KEEP_* keep or drop each curve on its own).
    const TiledMap t = MapToEdges([](const Edge& e) { return ToCurve(e); }, GridPartition(rows(), columns(), Tiled()));
    const Region w1 = Region::rectangle(0, 0, 170, 300), w2 = Region::rectangle(170, 0, 400, 300);
    const Region both = Region::rectangle(0, 0, 400, 300);
    // KEEP_OUTSIDE: the curves each window receives are the union's, whole.
    std::set<std::string> apart, together;
    for (const Region* w : {&w1, &w2})
        for (const auto& c : t.Convert(*w, KEEP_OUTSIDE).curves) {
            Curves one;
            one.curves.push_back(c);
            apart.insert(dump(one));
        }
    for (const auto& c : t.Convert(both, KEEP_OUTSIDE).curves) {
        Curves one;
        one.curves.push_back(c);
        together.insert(dump(one));
    }
    EXPECT_EQ(apart, together);
    // CROP: the pieces of the two windows put together draw the union's drawing.
    Curves cropped = t.Convert(w1, CROP);
    cropped.append(t.Convert(w2, CROP));
    EXPECT_SAME_RUNS(th::runs(cropped), th::runs(t.Convert(both, CROP)));
    // And a window's own result is the larger region's, cut to the window.
    EXPECT_SAME_RUNS(th::runs(t.Convert(w1, CROP)), th::runs(apply_mask(t.Convert(both, CROP), w1, CROP)));
}

TEST(Tiled, SameBytesAtOneAndTwoThreads) {
    const TiledMap t = GridPartition(rows(), columns(), Tiled());
    for (Border b : {CROP, CROP_ADD_BOUNDARY, KEEP_INSIDE, KEEP_OUTSIDE}) {
        std::string one, two;
        {
            ThreadsScope s(1);
            one = dump(t.Convert(kTriangle, b));
        }
        {
            ThreadsScope s(2);
            two = dump(t.Convert(kTriangle, b));
        }
        EXPECT_EQ(one, two) << border_name(b);
        EXPECT_FALSE(one.empty());
    }
}

TEST(Tiled, ConversionIsLinearInTheWindow) {
    // Four times the area, four times the curves (up to the border).
    const TiledMap t = GridPartition(StripesProperties(0, 10), StripesProperties(pi / 2, 10), Tiled(KEEP_INSIDE));
    const double n1 = double(t(Region::rectangle(0, 0, 1000, 1000)).curves.size());
    const double n4 = double(t(Region::rectangle(0, 0, 2000, 2000)).curves.size());
    EXPECT_NEAR(n4 / n1, 4.0, 0.05);
}

TEST(Tiled, BorderVerticesReportAllTheirNeighbours) {
    // Every vertex class, wherever it sits in the tile, has degree 4 in a grid: those on the
    // tile's sides see their neighbours through shifted copies.
    const TiledMap t = GridPartition(rows(), columns(), Tiled());
    const TiledMap::Block b = t.block();
    EXPECT_EQ(b.vertices.size(), 12u);
    EXPECT_EQ(b.edges.size(), 24u);
    EXPECT_EQ(b.faces.size(), 12u);
    auto degree = [](const Vertex& v) {
        Curves c;
        c.points.push_back({Location(v), Labels{std::string_view("degree" + std::to_string(IncidentEdges(v).size()))}});
        return c;
    };
    const Curves out = MapToVertices(degree, t).Convert(kWindow, KEEP_INSIDE);
    ASSERT_GT(out.points.size(), 100u);
    for (const auto& p : out.points) EXPECT_TRUE(p.labels.has("degree4")) << p.point.x << "," << p.point.y;
    // An engine map of a window gives degree 2 or 3 on its border: the tiled map has none.
}

TEST(Tiled, RandomInARegularMapperIsAnError) {
    const TiledMap t = GridPartition(rows(), columns(), Tiled());
    auto jitter = [](const Face& f) { return Translate(Contour(f), {Random(f, 0, 1, 0), 0}); };
    EXPECT_TEX_ERROR(MapToFaces(jitter, t), "MapToFaces", "GhostMap");
    auto unkeyed = [](const Edge& e) { return Scale(ToCurve(e), Random(0.5, 1.0)); };
    EXPECT_TEX_ERROR(MapToEdges(unkeyed, t), "MapToEdges", "random");
    auto sub = [](const Face& f) { return UniformPartition(IrregularProperties(0.01), CROP)(f); };
    EXPECT_TEX_ERROR(MapToFaces(sub, t), "MapToFaces", "random");
}

// A partition built inside a mapper is anchored to the plane, not to the cell. Hatching at
// 45 degrees, 3 apart, in the cells of a lattice of (0, 90) and (-50, 0): the periods
// project to 63.6 and 35.4 on the hatching's normal, no rational number of its periods, so
// the hatched grid has no period at all: a clear error naming both, not a wrong drawing.
TEST(Tiled, SubPartitionThatCannotRepeatIsAnError) {
    const TiledMap t = GridPartition(rows(), columns(), Tiled());
    auto hatch = [](const Face& f) { return StripesPartition(StripesProperties(pi / 4, 3), CROP)(f); };
    EXPECT_TEX_ERROR(MapToFaces(hatch, t), "MapToFaces", "every 3 ");
    EXPECT_TEX_ERROR(MapToFaces(hatch, t), "MapToFaces", "(0, 90) and (-50, 0)");
    EXPECT_TEX_ERROR(MapToFaces(hatch, t), "MapToFaces", "not periodic");
    // Inside a grid too (both its families are checked), and in an edge mapper.
    auto cells = [](const Face& f) {
        return GridPartition(StripesProperties(0, 7), StripesProperties(pi / 2, 25 * std::sqrt(2.0)), CROP)(f);
    };
    EXPECT_TEX_ERROR(MapToFaces(cells, t), "MapToFaces", "not periodic");
    auto around = [](const Edge& e) {
        const BBox b = CellBBox(e).expanded(5);
        return StripesPartition(StripesProperties(0.1, 4), CROP)(Region::rectangle(b.xmin, b.ymin, b.xmax, b.ymax));
    };
    EXPECT_TEX_ERROR(MapToEdges(around, t), "MapToEdges", "not periodic");
}

// Horizontal hatching 40 apart with two edge labels (it repeats every 80) in cells of a
// lattice 90 high: both repeat every 720 = 8 periods of the grid (and with every column).
// The tiled map is mapped on that coarser lattice and equals the engine; without it, every
// copy of a cell would get the central cell's hatching.
TEST(Tiled, SubPartitionOnACoarserLattice) {
    Stripes lines = StripesProperties(0, 40);
    SetEdgeLabels(lines, {"a", "b"});
    auto hatch = [lines](const Face& f) { return StripesPartition(lines, CROP)(f); };
    const TiledMap t = MapToFaces(hatch, GridPartition(rows(), columns(), Tiled()));
    EXPECT_NEAR(t.period1().y, 720, 1e-9);
    EXPECT_NEAR(t.period2().x, -50, 1e-9);
    const Region inner = Region::rectangle(60, 100, 330, 450), window = Region::rectangle(0, 0, 400, 560);
    const Curves engine = MapToFaces(hatch, GridPartition(rows(), columns(), KEEP_OUTSIDE))(window);
    const BBox keep = inner.bbox().expanded(-0.01);
    const Curves tiled_in = th::inside_box(t.Convert(inner, KEEP_OUTSIDE), keep);
    EXPECT_GT(tiled_in.curves.size(), 50u);
    EXPECT_SAME_CURVES(tiled_in, th::inside_box(engine, keep));
    // Same bytes at 1 and 2 threads.
    std::string one, two;
    {
        ThreadsScope s(1);
        one = dump(MapToFaces(hatch, GridPartition(rows(), columns(), Tiled()))(kTriangle));
    }
    {
        ThreadsScope s(2);
        two = dump(MapToFaces(hatch, GridPartition(rows(), columns(), Tiled()))(kTriangle));
    }
    EXPECT_EQ(one, two);
}

// On a lattice turned 45 degrees the copies of one vertex made by different translations
// differ in their last bits; the block's planar map must still see one vertex, not two and a
// sliver edge between them (every edge a mapper visits is a real edge of the grid).
TEST(Tiled, TurnedLatticeHasNoSliverEdges) {
    const TiledMap t = GridPartition(StripesProperties(pi / 4, 200), StripesProperties(-pi / 4, 300), Tiled());
    std::vector<double> lengths;
    const TiledMap edges = MapToEdges(
        [](const Edge& e) { return ToCurve(e); }, t, MapperThreads::Serial);
    for (const auto& e : edges.elements()) {
        const auto& pts = e.curves.curves.front().points;
        lengths.push_back(distance(pts.front(), pts.back()));
    }
    ASSERT_EQ(lengths.size(), 2u);  // one cell per period: one edge of each family
    std::sort(lengths.begin(), lengths.end());
    EXPECT_NEAR(lengths[0], 200, 1e-6);
    EXPECT_NEAR(lengths[1], 300, 1e-6);
}

TEST(Tiled, StripesCannotBeMapped) {
    const TiledMap t = StripesPartition(StripesProperties(0.3, 10), Tiled());
    EXPECT_TEX_ERROR(MapToFaces([](const Face& f) { return Contour(f); }, t), "MapToFaces", "unbounded");
}

TEST(Tiled, NeighbourhoodInfluenceZoneOverflow) {
    // A circle three cells wide around each cell's centre overflows into the neighbouring
    // tiles; converted, every circle inside the window is there, as the engine draws them.
    const Stripes s1 = StripesProperties(0, 20), s2 = StripesProperties(pi / 2, 30);
    auto circle = [](const Face& f) {
        std::vector<Point> pts;
        const Point c = Centroid(f);
        for (int k = 0; k < 24; ++k) pts.push_back(c + Point{std::cos(k * pi / 12), std::sin(k * pi / 12)} * 45.0);
        return Polyline(pts, true);
    };
    const TiledMap t = MapToFaces(circle, GridPartition(s1, s2, Tiled()));
    ASSERT_EQ(t.elements().size(), 1u);
    EXPECT_GE(t.block_reach(), 1);
    const Region inner = Region::rectangle(0, 0, 300, 200);
    const Curves engine = MapToFaces(circle, GridPartition(s1, s2, KEEP_OUTSIDE))(Region::rectangle(-200, -200, 500, 400));
    const Curves tiled = t.Convert(inner, KEEP_INSIDE);
    EXPECT_SAME_RUNS(th::runs(tiled), th::runs(th::inside_box(engine, inner.bbox())));
    // Circles of centres outside the window reach into it.
    const Curves meeting = t.Convert(inner, KEEP_OUTSIDE);
    std::size_t outside_centres = 0;
    for (const auto& c : meeting.curves) outside_centres += !inner.contains(BBoxCenter(Polyline(c.points)));
    EXPECT_GT(outside_centres, 0u);
}

TEST(Tiled, GhostMappingIsSemiRegularAndDeterministic) {
    const TiledMap bricks = MapToFaces([](const Face& f) { return Scale(Contour(f), 0.8); },
                                       GridPartition(StripesProperties(0, 20), StripesProperties(pi / 2, 40), Tiled()));
    auto jitter = [](const TiledElement& e) {
        return Translate(Scale(e.curves, Random(e, 0.7, 1.0, 0)), {Random(e, -2, 2, 1), Random(0.0, 1.0)});
    };
    const TiledMap ghost = GhostMap(jitter, bricks);
    std::string one, two, again;
    {
        ThreadsScope s(1);
        one = dump(ghost.Convert(kWindow, KEEP_OUTSIDE));
    }
    {
        ThreadsScope s(2);
        two = dump(ghost.Convert(kWindow, KEEP_OUTSIDE));
        again = dump(ghost.Convert(kWindow, KEEP_OUTSIDE));
    }
    EXPECT_EQ(one, two);
    EXPECT_EQ(one, again);
    {
        SavedSeed keep;
        SetSeed(7);
        EXPECT_NE(dump(ghost.Convert(kWindow, KEEP_OUTSIDE)), one);
    }
    // Semi-regular: copies of one element differ in size.
    const Curves c = ghost.Convert(kWindow, KEEP_INSIDE);
    std::set<long long> widths;
    for (const auto& cv : c.curves) widths.insert(std::llround(BBoxWidth(Polyline(cv.points)) * 1000));
    EXPECT_GT(widths.size(), c.curves.size() / 8);  // four curves per brick, two of them flat
    // A window's copies are the same whatever the region around them.
    const BBox box = Region::rectangle(0, 0, 100, 100).bbox();
    const Curves small = ghost.Convert(Region::rectangle(0, 0, 100, 100), KEEP_OUTSIDE);
    const Curves large = ghost.Convert(Region::rectangle(-100, -100, 300, 300), KEEP_OUTSIDE);
    EXPECT_SAME_RUNS(th::runs(th::inside_box(small, box)), th::runs(th::inside_box(large, box)));
    EXPECT_FALSE(th::inside_box(small, box).empty());
    EXPECT_TEX_ERROR(MapToEdges([](const Edge& e) { return ToCurve(e); }, ghost), "MapToEdges", "ghost");
}

TEST(Tiled, UnionTakesTheLeastCommonMultipleOfThePeriods) {
    const TiledMap a = GridPartition(StripesProperties(0, 30), StripesProperties(pi / 2, 20), Tiled(CROP));
    const TiledMap b = GridPartition(StripesProperties(0, 45), StripesProperties(pi / 2, 50), Tiled(CROP));
    const TiledMap u = Union(a, b);
    EXPECT_NEAR(u.period1().y, 90, 1e-9);
    EXPECT_NEAR(std::abs(u.period2().x), 100, 1e-9);
    Curves both = a.Convert(kWindow, CROP);
    both.append(b.Convert(kWindow, CROP));
    EXPECT_SAME_RUNS(th::runs(u.Convert(kWindow, CROP)), th::runs(both));
    const TiledMap c = GridPartition(StripesProperties(0, 30 * std::sqrt(2.0)), StripesProperties(pi / 2, 20), Tiled());
    EXPECT_TEX_ERROR(Union(a, c), "(0, 30)", "no common multiple");
}

TEST(Tiled, PointQueries) {
    const TiledMap t = GridPartition(rows(), columns(), Tiled());
    // (1012.5, 904): rows at 900, 910 (the fourth line of a period 90 x 10 + 0): distance 4
    // to y = 900; columns every 25: x = 1012.5 is 12.5 from both.
    EXPECT_NEAR(t.DistanceToCurves({1012.5, 904}), 4.0, 1e-9);
    EXPECT_NEAR(t.DistanceToCurves({-3, -100000}), 3.0, 1e-6);
    // Columns of face labels c1, c2 alternate every 25 (face i between lines i and i+1).
    EXPECT_TRUE(t.FaceLabelsAt({10, 5}).has("c2") || t.FaceLabelsAt({10, 5}).has("c1"));
    EXPECT_NE(t.FaceLabelsAt({10, 5}), t.FaceLabelsAt({35, 5}));
    EXPECT_EQ(t.FaceLabelsAt({10, 5}), t.FaceLabelsAt({10 + 50 * 1000, 5 - 90 * 77}));
}

TEST(Tiled, RasterizeAWindow) {
    const TiledMap t = GridPartition(StripesProperties(0, 20), StripesProperties(pi / 2, 30), Tiled());
    const Raster r = Rasterize(t, Region::rectangle(0, 0, 60, 40).bbox(), 1.0, 2.0);
    ASSERT_EQ(r.width, 60);
    ASSERT_EQ(r.height, 40);
    auto at = [&](double x, double y) { return int(r.pixels[std::size_t(40 - 1 - int(y)) * 60 + std::size_t(x)]); };
    EXPECT_EQ(at(10.5, 20.5), 0);    // on the line y = 20
    EXPECT_EQ(at(30.5, 7.5), 0);     // on the line x = 30
    EXPECT_EQ(at(15.5, 10.5), 255);  // in the middle of a cell
    EXPECT_EQ(at(45.5, 30.5), 255);
    // A finer pixel draws the same lines: at both pixel sizes, a pixel whose centre is within
    // half the line width of a line (y = 20k, x = 30k) is black, one beyond half the width
    // plus half a pixel (past the anti-aliased edge) is white.
    const Raster fine = Rasterize(t, Region::rectangle(0, 0, 60, 40).bbox(), 0.5, 2.0);
    ASSERT_EQ(fine.width, 120);
    ASSERT_EQ(fine.height, 80);
    for (const auto& [img, pixel] : {std::pair<const Raster*, double>{&r, 1.0}, {&fine, 0.5}}) {
        int black = 0, white = 0;
        for (int row = 0; row < img->height; ++row)
            for (int col = 0; col < img->width; ++col) {
                const double x = (col + 0.5) * pixel, y = 40 - (row + 0.5) * pixel;
                const double d = std::min(std::abs(y - 20 * std::round(y / 20)), std::abs(x - 30 * std::round(x / 30)));
                const int v = img->pixels[std::size_t(row) * img->width + col];
                if (d <= 1.0) {
                    EXPECT_EQ(v, 0) << "pixel " << pixel << " at " << x << "," << y;
                    ++black;
                } else if (d >= 1.0 + pixel / 2) {
                    EXPECT_EQ(v, 255) << "pixel " << pixel << " at " << x << "," << y;
                    ++white;
                }
            }
        EXPECT_GT(black, 0);
        EXPECT_GT(white, black);
    }
    // A ghost map rasterises the same at 1 and 2 threads.
    const TiledMap ghost = GhostMap([](const TiledElement& e) { return Random(e, 0, 1, 0) < 0.5 ? Nothing() : e.curves; },
                                    MapToEdges([](const Edge& e) { return ToCurve(e); }, t));
    std::vector<std::uint8_t> one, two;
    {
        ThreadsScope s(1);
        one = Rasterize(ghost, Region::rectangle(-3, -7, 500, 300).bbox(), 0.5, 1.5).pixels;
    }
    {
        ThreadsScope s(2);
        two = Rasterize(ghost, Region::rectangle(-3, -7, 500, 300).bbox(), 0.5, 1.5).pixels;
    }
    EXPECT_EQ(one, two);
    EXPECT_NE(std::count(one.begin(), one.end(), 0), 0);
    EXPECT_TEX_ERROR(Rasterize(t, Region::rectangle(0, 0, 6, 4).bbox(), 0.0, 1.0), "Rasterize", "pixel size 0");
    EXPECT_TEX_ERROR(Rasterize(t, BBox{}, 1.0, 1.0), "Rasterize", "empty");
}

TEST(Tiled, InsideAndOutsideMatchTheEngine) {
    // Horizontal lines 6 apart inside / outside squares (grid of 40, each cell shrunk to 55 %):
    // no line runs along a square's side.
    const Stripes lines = StripesProperties(0, 6);
    const Stripes s1 = StripesProperties(0, 40), s2 = StripesProperties(pi / 2, 40);
    auto square = [](const Face& f) { return Scale(Contour(f), 0.55); };
    const TiledMap squares = MapToFaces(square, GridPartition(s1, s2, Tiled()));
    const Arrangement engine_squares = MapToFaces(square, GridPartition(s1, s2, KEEP_OUTSIDE));
    const Region window = Region::rectangle(0, 0, 400, 300);
    // Both cut to an inner window (the engine's pieces and the tiled ones end at different
    // points of a line: the tiled map stores lines a period at a time).
    const Region inner = Region::rectangle(60, 60, 340, 240);
    auto cut = [&inner](const Curves& c) { return th::runs(apply_mask(c, inner, CROP)); };
    const TiledMap in = Inside(StripesPartition(lines, Tiled()), squares, CROP);
    EXPECT_NEAR(std::abs(in.period1().y), 120, 1e-9);  // LCM(6, 40)
    const Curves engine_in = Inside(StripesPartition(lines, CROP), engine_squares, CROP)(window);
    EXPECT_SAME_RUNS(cut(in.Convert(window, KEEP_OUTSIDE)), cut(engine_in));
    EXPECT_FALSE(cut(engine_in).empty());
    // KEEP_* keep or drop whole edges: small circles on a grid of 10, some across the squares'
    // sides (a stripe's edges are one period long in a tiled map, whole lines in the engine).
    const Stripes c1 = StripesProperties(0, 10), c2 = StripesProperties(pi / 2, 10);
    auto circle = [](const Face& f) {
        std::vector<Point> pts;
        for (int k = 0; k < 24; ++k) pts.push_back(Centroid(f) + Point{std::cos(k * pi / 12), std::sin(k * pi / 12)} * 4.5);
        return Polyline(pts, true);
    };
    for (Border b : {KEEP_INSIDE, KEEP_OUTSIDE}) {
        const Curves tiled = Inside(MapToFaces(circle, GridPartition(c1, c2, Tiled())), squares, b).Convert(window, KEEP_OUTSIDE);
        const Curves engine = Inside(MapToFaces(circle, GridPartition(c1, c2, KEEP_OUTSIDE)), engine_squares, b)(window);
        EXPECT_SAME_RUNS(cut(tiled), cut(engine));
        EXPECT_FALSE(cut(engine).empty()) << border_name(b);
    }
    const Curves engine_out = Outside(StripesPartition(lines, CROP), engine_squares, CROP)(window);
    const Curves tiled_out = Outside(StripesPartition(lines, Tiled()), squares, CROP).Convert(window, KEEP_OUTSIDE);
    EXPECT_SAME_RUNS(cut(tiled_out), cut(engine_out));
    // As whole curves: the pieces the mask kept are joined where only the period cut them, so
    // each run between two squares (or a square and the window) is one curve, as in the
    // engine; converted with CROP, the window cuts them where the engine's window does.
    const TiledMap out = Outside(StripesPartition(lines, Tiled()), squares, CROP);
    EXPECT_SAME_CURVES(out.Convert(window, CROP), engine_out);
    EXPECT_SAME_CURVES(in.Convert(window, CROP), engine_in);
    // Lines that meet no square stay whole lines of the tiled map (hatching 6 apart, squares
    // 22 wide in rows 40 apart: the lines at y = 30 + 40 k... miss every square).
    const std::size_t whole = std::count_if(out.elements().begin(), out.elements().end(),
                                            [](const TiledMap::Element& e) { return e.continues; });
    EXPECT_GT(whole, 0u);
    // Same bytes at 1 and 2 threads.
    std::string one, two;
    {
        ThreadsScope t(1);
        one = dump(Outside(StripesPartition(lines, Tiled()), squares, CROP).Convert(window, CROP));
    }
    {
        ThreadsScope t(2);
        two = dump(Outside(StripesPartition(lines, Tiled()), squares, CROP).Convert(window, CROP));
    }
    EXPECT_EQ(one, two);
    const TiledMap skew = StripesPartition(StripesProperties(0.3, 6), Tiled());
    EXPECT_TEX_ERROR(Inside(skew, squares, CROP), "Inside", "no common multiple");
}

// Which face contains a point, on a mapped tiled map: each cell of a labelled grid turned 45
// degrees into a square 1.2 times as wide (so that neighbours overlap), its inner side
// labelled with the cell's labels and "tile". The faces of that drawing (overlaps, the holes
// between squares, pieces carrying one, two or more squares' labels) against the engine's
// planar map of the same script over a window, at random points of an inner window.
TEST(Tiled, FaceAtAPointIsTheEnginesFace) {
    auto turned = [](const Face& f) {
        Curves c = Rotate(Scale(Contour(f), 0.85), pi / 4);
        for (auto& cv : c.curves) {
            cv.left = record(f).labels;
            cv.left.add("tile");
            cv.right = Labels{};
        }
        return c;
    };
    const TiledMap t = MapToFaces(turned, GridPartition(rows(), columns(), Tiled()));
    const Region window = Region::rectangle(-200, -200, 600, 600);
    const FaceLocator engine(MapToFaces(turned, GridPartition(rows(), columns(), KEEP_OUTSIDE)).induce(window));
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> x(50, 350), y(50, 350);
    int checked = 0;
    std::set<std::string> seen;
    for (int k = 0; k < 3000; ++k) {
        const Point p{x(rng), y(rng)};
        const Labels want = engine.map().faces()[std::size_t(engine.face_at(p))].labels;
        const Labels got = t.FaceLabelsAt(p);
        EXPECT_EQ(th::label_text(got), th::label_text(want)) << "at (" << p.x << ", " << p.y << ")";
        seen.insert(th::label_text(want));
        ++checked;
        // The same face one period away in both directions.
        EXPECT_EQ(th::label_text(t.FaceLabelsAt(p + t.period1() * 3.0 - t.period2() * 7.0)), th::label_text(got));
    }
    EXPECT_EQ(checked, 3000);
    EXPECT_GE(seen.size(), 3u) << *seen.begin();  // several kinds of faces were met
}

// The locator on its own: nested faces (a square inside a square) and the unbounded face.
TEST(Tiled, FaceLocatorFindsNestedFaces) {
    Curves c;
    Curve outer, inner;
    outer.points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    outer.closed = true;
    outer.left.add("ring");
    inner.points = {{3, 3}, {7, 3}, {7, 7}, {3, 7}};
    inner.closed = true;
    inner.left.add("core");
    c.curves = {outer, inner};
    const FaceLocator loc(PlanarMap::induce(c));
    auto labels = [&](Point p) { return th::label_text(loc.map().faces()[std::size_t(loc.face_at(p))].labels); };
    EXPECT_EQ(labels({1, 1}), "ring,");
    EXPECT_EQ(labels({5, 5}), "core,");
    EXPECT_EQ(loc.face_at({20, 5}), loc.map().unbounded_face());
}

namespace {

// Horizontal stripes 120 and 300 wide with three face labels (period 1260 across), and small
// squares in a grid of 210 x 180 (commensurable: 6 and 7 cells per 1260), their inner side
// labelled "in" and the cell's labels, their outer side "out". The union has faces of every
// kind: bands (unbounded), the band around the squares (unbounded, with holes), inside
// squares, pieces of squares cut by a stripe line.
Stripes labelled(Stripes s, const std::vector<std::string>& face_labels) {
    SetFaceLabels(s, face_labels);
    return s;
}
Stripes wide_bands() { return labelled(StripesProperties(0, 120, 300), {"a", "b", "c"}); }
Stripes square_rows() { return labelled(StripesProperties(0, 210), {"r1", "r2"}); }
Stripes square_columns() { return StripesProperties(pi / 2, 180); }
Curves small_square(const Face& f) {
    Curves c = Scale(Contour(f), 0.3);
    for (auto& cv : c.curves) {
        cv.left = record(f).labels;
        cv.left.add("in");
        cv.right = Labels{};
        cv.right.add("out");
    }
    return c;
}

}  // namespace

// FaceLabelsAt where faces are unbounded (bands of stripes, the space around closed shapes):
// the labels of the engine's face at thousands of random points, many of them far from every
// curve, and the same labels a whole number of periods away.
TEST(Tiled, FaceLabelsOnUnboundedFacesAreTheEnginesFaces) {
    const TiledMap bands = StripesPartition(wide_bands(), Tiled());
    const TiledMap squares = MapToFaces(small_square, GridPartition(square_rows(), square_columns(), Tiled()));
    const TiledMap both = Union(bands, squares);
    EXPECT_FALSE(both.bounded_faces());
    const Region window = Region::rectangle(-2000, -2000, 4000, 4000);
    const FaceLocator engine_bands(StripesPartition(wide_bands(), CROP_ADD_BOUNDARY).induce(window));
    const FaceLocator engine_both(Union(StripesPartition(wide_bands(), CROP_ADD_BOUNDARY),
                                        MapToFaces(small_square, GridPartition(square_rows(), square_columns(), KEEP_OUTSIDE)))
                                      .induce(window));
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> u(-1000, 3000);
    std::set<std::string> kinds;
    int far = 0;
    for (int k = 0; k < 3000; ++k) {
        const Point p{u(rng), u(rng)};
        auto labels_of = [&](const FaceLocator& l) {
            return th::label_text(l.map().faces()[std::size_t(l.face_at(p))].labels);
        };
        const std::string want_bands = labels_of(engine_bands), want_both = labels_of(engine_both);
        ASSERT_EQ(th::label_text(bands.FaceLabelsAt(p)), want_bands) << "stripes at (" << p.x << ", " << p.y << ")";
        ASSERT_EQ(th::label_text(both.FaceLabelsAt(p)), want_both) << "union at (" << p.x << ", " << p.y << ")";
        const Point away = p + both.period1() * 4000.0 - both.period2() * 7001.0;
        ASSERT_EQ(th::label_text(both.FaceLabelsAt(away)), want_both) << "far copy of (" << p.x << ", " << p.y << ")";
        kinds.insert(want_both);
        if (both.DistanceToCurves(p) > 40) ++far;
    }
    // Bands with and without squares, inside squares, squares cut by a line.
    EXPECT_TRUE(kinds.count("a,out,")) << kinds.size();
    EXPECT_TRUE(kinds.count("b,out,") && kinds.count("c,out,"));
    EXPECT_GE(kinds.size(), 6u);
    EXPECT_GT(far, 600);  // many points are far from every curve
}

// DistanceToCurves through its grid gives the linear scan's answer, bit for bit, on maps of
// every kind, near the origin and far from it, and the brute force over a wider block of
// copies to 1e-12.
TEST(Tiled, IndexedDistanceIsTheScansDistance) {
    auto ring = [](const Face& f) { return Rotate(Scale(Contour(f), 0.7), 0.3); };
    const std::vector<TiledMap> maps = {
        GridPartition(rows(), columns(), Tiled()),
        MapToFaces(ring, GridPartition(rows(), columns(), Tiled())),
        GridPartition(StripesProperties(pi / 4, 30, 11), StripesProperties(-pi / 3, 17), Tiled()),
        StripesPartition(StripesProperties(pi / 5, 12, 30), Tiled()),
        Union(StripesPartition(wide_bands(), Tiled()),
              MapToFaces(small_square, GridPartition(square_rows(), square_columns(), Tiled()))),
    };
    std::mt19937_64 rng(7);
    for (std::size_t m = 0; m < maps.size(); ++m) {
        const TiledMap& t = maps[m];
        BBox tile;
        for (const Point& c : {Point{0, 0}, t.period1(), t.period2(), t.period1() + t.period2()}) tile.add(c);
        std::uniform_real_distribution<double> x(tile.xmin - 3 * tile.width(), tile.xmax + 3 * tile.width());
        std::uniform_real_distribution<double> y(tile.ymin - 3 * tile.height(), tile.ymax + 3 * tile.height());
        for (int k = 0; k < 2000; ++k) {
            Point p{x(rng), y(rng)};
            if (k % 4 == 3) p += t.shift(123456, -654321);
            const double got = t.DistanceToCurves(p);
            ASSERT_EQ(got, t.DistanceToCurvesByScan(p)) << "map " << m << " at (" << p.x << ", " << p.y << ")";
            if (k % 20 != 0 || k % 4 == 3) continue;
            // Brute force: every segment of every copy within reach + 3 tiles.
            const Point l = t.lattice(p);
            const long long ti = (long long)std::floor(l.x), tj = (long long)std::floor(l.y);
            const int w = t.block_reach() + 3;
            double best = std::numeric_limits<double>::infinity();
            for (long long i = ti - w; i <= ti + w; ++i)
                for (long long j = tj - w; j <= tj + w; ++j)
                    for (const auto& e : t.elements())
                        for (Curve c : e.curves.curves) {
                            for (auto& q : c.points) q += t.shift(i, j);
                            const std::size_t n = c.points.size(), segs = c.closed ? n : n - 1;
                            for (std::size_t s = 0; s < segs; ++s) {
                                const Point a = c.points[s], b = c.points[(s + 1) % n], d = b - a;
                                const double h = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
                                best = std::min(best, distance(p, a + d * h));
                            }
                        }
            EXPECT_NEAR(got, best, 1e-12 * (1 + norm(p))) << "map " << m;
        }
    }
    // A map with no curve is at an infinite distance.
    const TiledMap none = MapToFaces([](const Face&) { return Nothing(); }, GridPartition(rows(), columns(), Tiled()));
    EXPECT_EQ(none.DistanceToCurves({3, 4}), std::numeric_limits<double>::infinity());
}

// A ghost mapper on stripes sees whole lines, as MapToEdges on the engine's stripes does: a
// ghost that keeps the lines labelled "x" and marks them gives the engine's curves, line for
// line; a random ghost keeps or drops each line whole, the same line alike in two windows.
TEST(Tiled, GhostMapperSeesWholeStripeLines) {
    Stripes s = StripesProperties(pi / 5, 12, 30);
    SetFaceLabels(s, {"a", "b", "c"});
    SetEdgeLabels(s, {"x", "y"});
    auto mark = [](Curves c) {
        if (c.curves.empty() || !c.curves.front().labels.has("x")) return Nothing();
        for (auto& cv : c.curves) cv.labels.add("kept");
        return c;
    };
    const TiledMap ghost = GhostMap([&](const TiledElement& e) { return mark(e.curves); }, StripesPartition(s, Tiled()));
    const Curves engine = MapToEdges([&](const Edge& e) { return mark(ToCurve(e)); }, StripesPartition(s, CROP))(kWindow);
    EXPECT_GT(engine.curves.size(), 10u);
    EXPECT_SAME_CURVES(ghost.Convert(kWindow, CROP), engine);

    const TiledMap random = GhostMap(
        [](const TiledElement& e) { return Random(e, 0, 1, 0) < 0.5 ? Nothing() : e.curves; }, StripesPartition(s, Tiled()));
    const Curves small = random.Convert(kWindow, CROP);
    const Curves large = random.Convert(Region::rectangle(-1000, -1200, 1500, 900), CROP);
    // One curve per line kept (no piece of a line alone), and a line of the small window
    // kept in the large one (the large one's line covers it).
    std::set<long long> lines;
    auto line_of = [](const Curve& c) {
        const Point d = c.points.back() - c.points.front();
        return std::llround(cross(d, c.points.front()) / norm(d) * 1e3);
    };
    for (const auto& c : small.curves) lines.insert(line_of(c));
    EXPECT_EQ(lines.size(), small.curves.size());
    EXPECT_GT(small.curves.size(), 5u);
    std::set<long long> large_lines;
    for (const auto& c : large.curves) large_lines.insert(line_of(c));
    for (long long l : lines) EXPECT_TRUE(large_lines.count(l)) << l;
    std::string one, two;
    {
        ThreadsScope t(1);
        one = dump(random.Convert(kWindow, CROP));
    }
    {
        ThreadsScope t(2);
        two = dump(random.Convert(kWindow, CROP));
    }
    EXPECT_EQ(one, two);
}

// A mapper that reads absolute positions does not repeat with the periods: a tiled map
// cannot stand for it, and says so instead of copying the central tile's output.
TEST(Tiled, MapperReadingAbsolutePositionsIsAnError) {
    const TiledMap grid = GridPartition(rows(), columns(), Tiled());
    auto right_half = [](const Face& f) { return Centroid(f).x > 0 ? Contour(f) : Nothing(); };
    EXPECT_TEX_ERROR(MapToFaces(right_half, grid), "MapToFaces", "reads absolute positions");
    auto field = [](const Face& f) { return Scale(Contour(f), 0.5 + 0.3 * std::sin(Centroid(f).x / 37)); };
    EXPECT_TEX_ERROR(MapToFaces(field, grid), "MapToFaces", "periods (0, 90) and (-50, 0)");
    auto upper = [](const Vertex& v) { return Location(v).y > 0 ? Polyline({Location(v), Location(v) + Point{1, 1}}) : Nothing(); };
    EXPECT_TEX_ERROR(MapToVertices(upper, grid), "MapToVertices", "reads absolute positions");
    auto long_left = [](const Edge& e) { return LocationAt(e, 0.5).x < 10 ? ToCurve(e) : Nothing(); };
    EXPECT_TEX_ERROR(MapToEdges(long_left, grid, MapperThreads::Serial), "MapToEdges", "reads absolute positions");
    // The same mappers reading the cell only are fine, and so is a field with the periods.
    EXPECT_NO_THROW(MapToFaces([](const Face& f) { return Scale(Contour(f), 0.5); }, grid));
    auto periodic = [](const Face& f) { return Scale(Contour(f), 0.5 + 0.3 * std::sin(Centroid(f).x * 2 * pi / 50)); };
    EXPECT_NO_THROW(MapToFaces(periodic, grid));
}
