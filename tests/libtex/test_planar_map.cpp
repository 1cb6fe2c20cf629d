// Planar map induction, labels and the cell built-ins of table 3.4.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <random>
#include <set>
#include <thread>
#include <utility>
#include <cmath>
#include <cstdio>

#include "helpers.hpp"

using namespace tex;

namespace {

// Two squares side by side sharing an edge, plus a dangling stroke: the shape of the
// thesis's Fig. 3.2 in spirit (several curves, shared pieces, one unbounded face).
Curves two_squares() {
    Curves c;
    Curve a;
    a.points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    a.closed = true;
    a.left = Labels{"A"};
    a.labels = Labels{"square"};
    Curve b;
    b.points = {{10, 0}, {20, 0}, {20, 10}, {10, 10}};
    b.closed = true;
    b.left = Labels{"B"};
    Curve s;
    s.points = {{20, 5}, {30, 5}};
    s.labels = Labels{"stroke"};
    c.curves = {a, b, s};
    c.points.push_back({{30, 5}, Labels{"tip"}});
    return c;
}

int face_with_label(const PlanarMap& m, const char* l) {
    for (std::size_t i = 0; i < m.faces().size(); ++i)
        if (m.faces()[i].labels.has(l)) return int(i);
    return -1;
}

}  // namespace

TEST(PlanarMap, InducesCellsOfOverlappingCurves) {
    const MapPtr m = PlanarMap::induce(two_squares());
    // Vertices: the two ends of the shared side (degree 3), the stroke's start on B
    // (degree 3) and its tip. The other corners are bends of one curve, not vertices.
    EXPECT_EQ(m->vertices().size(), 4u);
    // Edges: A's three free sides in one piece, the shared side, B's outline split in two
    // by the stroke's start, the stroke.
    EXPECT_EQ(m->edges().size(), 5u);
    EXPECT_EQ(th::bounded_faces(*m), 2u);
    const int fa = face_with_label(*m, "A"), fb = face_with_label(*m, "B");
    ASSERT_GE(fa, 0);
    ASSERT_GE(fb, 0);
    EXPECT_NE(fa, fb);
    EXPECT_FALSE(m->faces()[fa].labels.has("B"));
    EXPECT_NEAR(th::face_area(*m, fa), 100, 1e-12);
}

TEST(PlanarMap, SharedEdgeMergesLabelsAndSides) {
    const MapPtr m = PlanarMap::induce(two_squares());
    const int fa = face_with_label(*m, "A"), fb = face_with_label(*m, "B");
    int shared = -1;
    for (std::size_t e = 0; e < m->edges().size(); ++e) {
        const auto& r = m->edges()[e];
        if ((r.left == fa && r.right == fb) || (r.left == fb && r.right == fa)) shared = int(e);
    }
    ASSERT_GE(shared, 0);
    const Edge e(m, shared);
    EXPECT_EQ(record(e).sources.size(), 2u);
    EXPECT_TRUE(HasLabel(e, "square"));
    // Oriented like its first source curve (square A, counter-clockwise: upwards at x=10).
    EXPECT_EQ(Location(SourceVertex(e)), Point(10, 0));
    EXPECT_EQ(Location(TargetVertex(e)), Point(10, 10));
    EXPECT_EQ(LeftFace(e), Face(m, fa));
    EXPECT_EQ(RightFace(e), Face(m, fb));
    EXPECT_FALSE(IsBoundary(e));
}

TEST(PlanarMap, IncidenceQueries) {
    const MapPtr m = PlanarMap::induce(two_squares());
    const Face a(m, face_with_label(*m, "A"));
    EXPECT_EQ(IncidentEdges(a).size(), 2u);    // the shared side and the rest of A's outline
    EXPECT_EQ(IncidentVertices(a).size(), 2u); // the ends of the shared side
    EXPECT_TRUE(IsBoundary(a));
    const Point c = Centroid(a);
    EXPECT_NEAR(c.x, 5, 1e-12);
    EXPECT_NEAR(c.y, 5, 1e-12);
    for (const Vertex& v : IncidentVertices(a)) {
        const auto faces = IncidentFaces(v);
        EXPECT_NE(std::find(faces.begin(), faces.end(), a), faces.end());
    }
    // The stroke's far end: a vertex of degree one labelled by the "tip" point.
    int tip = -1;
    for (std::size_t v = 0; v < m->vertices().size(); ++v)
        if (m->vertices()[v].point == Point(30, 5)) tip = int(v);
    ASSERT_GE(tip, 0);
    const Vertex t(m, tip);
    EXPECT_EQ(IncidentEdges(t).size(), 1u);
    EXPECT_TRUE(HasLabel(t, "tip"));
    EXPECT_TRUE(HasLabel(IncidentEdges(t), "stroke"));
    EXPECT_FALSE(HasLabel(IncidentEdges(t), "square"));
    EXPECT_TRUE(IsBoundary(t));
    const Point mid = LocationAt(IncidentEdges(t)[0], 0.5);
    EXPECT_NEAR(mid.y, 5, 1e-12);
}

TEST(PlanarMap, ContourCarriesFaceLabelsAndReinducesThem) {
    const MapPtr m = PlanarMap::induce(two_squares());
    const Face a(m, face_with_label(*m, "A"));
    const Curves c = Contour(a);
    ASSERT_EQ(c.curves.size(), 2u);  // one curve per edge of A
    std::vector<Point> ring;
    for (const auto& cv : c.curves) {
        EXPECT_FALSE(cv.closed);
        EXPECT_TRUE(cv.left.has("A"));
        ring.insert(ring.end(), cv.points.begin(), cv.points.end() - 1);
        if (&cv != &c.curves.back()) EXPECT_EQ(cv.points.back(), (&cv + 1)->points.front());
    }
    EXPECT_NEAR(signed_area(ring), 100, 1e-12);
    const MapPtr m2 = PlanarMap::induce(Scale(c, 0.5));
    ASSERT_EQ(th::bounded_faces(*m2), 1u);
    EXPECT_GE(face_with_label(*m2, "A"), 0);
}

TEST(PlanarMap, HolesAreCyclesOfTheirFace) {
    Curves c = Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true);
    c.append(Polyline({{4, 4}, {6, 4}, {6, 6}, {4, 6}}, true));
    const MapPtr m = PlanarMap::induce(c);
    ASSERT_EQ(th::bounded_faces(*m), 2u);
    int ring = -1;
    for (std::size_t f = 0; f < m->faces().size(); ++f)
        if (!m->faces()[f].unbounded && m->faces()[f].cycles.size() == 2) ring = int(f);
    ASSERT_GE(ring, 0);
    EXPECT_NEAR(th::face_area(*m, ring), 96, 1e-12);
    const Region r = ToRegion(Face(m, ring));
    EXPECT_EQ(r.holes().size(), 1u);
    EXPECT_NEAR(r.area(), 96, 1e-12);
    EXPECT_FALSE(r.contains({5, 5}));
    EXPECT_TRUE(r.contains({1, 1}));
}

TEST(PlanarMap, RandomIsKeyedByGeometryNotByIndex) {
    // The same face in two different maps (different cell numbering) draws the same values.
    const MapPtr m1 = PlanarMap::induce(two_squares());
    Curves other = two_squares();
    std::reverse(other.curves.begin(), other.curves.end());
    other.append(Polyline({{100, 100}, {110, 100}, {110, 110}}, true));
    const MapPtr m2 = PlanarMap::induce(other);
    const Face a1(m1, face_with_label(*m1, "A")), a2(m2, face_with_label(*m2, "A"));
    EXPECT_EQ(Random(a1, 0, 1, 3), Random(a2, 0, 1, 3));
    EXPECT_NE(Random(a1, 0, 1, 3), Random(a1, 0, 1, 4));
    const Face b1(m1, face_with_label(*m1, "B"));
    EXPECT_NE(Random(a1, 0, 1, 3), Random(b1, 0, 1, 3));
    const std::uint64_t saved = GetSeed();
    SetSeed(saved + 1);
    const double other_seed = Random(a1, 0, 1, 3);
    SetSeed(saved);
    EXPECT_NE(other_seed, Random(a1, 0, 1, 3));
    const double v = Random(a1, 5, 7, 0);
    EXPECT_GE(v, 5);
    EXPECT_LT(v, 7);
}

TEST(PlanarMap, EmptyAndDegenerateInput) {
    const MapPtr m = PlanarMap::induce(Curves{});
    EXPECT_EQ(m->faces().size(), 1u);
    EXPECT_TRUE(m->faces()[0].unbounded);
    const MapPtr z = PlanarMap::induce(Polyline({{1, 1}, {1, 1}}));
    EXPECT_EQ(z->edges().size(), 0u);
}

// ---- Cells are the thesis's (3.2): maximal subcurves between vertices ----

namespace {

// A closed circle (64 points), an S-shaped stroke (200 points) crossing it twice and a
// bent stroke (3 points) that meets nothing.
Curves circle_and_strokes() {
    Curves c;
    Curve circle;
    for (int i = 0; i < 64; ++i) circle.points.push_back({10 * std::cos(2 * pi * i / 64), 10 * std::sin(2 * pi * i / 64)});
    circle.closed = true;
    circle.labels = Labels{"circle"};
    Curve s;
    for (int i = 0; i <= 200; ++i) {
        const double x = -20 + 40.0 * i / 200;
        s.points.push_back({x, 3 * std::sin(pi * x / 20)});
    }
    s.labels = Labels{"s"};
    Curve bent;
    bent.points = {{0, 20}, {5, 15}, {5, 25}};
    c.curves = {circle, s, bent};
    return c;
}

}  // namespace

TEST(PlanarMapCells, VerticesAreEndsAndCrossingsNotBends) {
    const MapPtr m = PlanarMap::induce(circle_and_strokes());
    // 2 + 2 stroke ends, 2 crossings of the S with the circle.
    EXPECT_EQ(m->vertices().size(), 6u);
    // The circle cut in two arcs, the S in three pieces, the bent stroke whole.
    EXPECT_EQ(m->edges().size(), 6u);
    EXPECT_EQ(th::bounded_faces(*m), 2u);
    for (const auto& v : m->vertices()) EXPECT_NE(v.edges.size(), 2u) << "a bend became a vertex";
    // The edges keep every point of the curves (64 + 201 + 3), each once, plus the two
    // crossings, each the end of two arcs and of two pieces of the S: 268 + 2 x 4 points.
    std::size_t points = 0;
    std::set<std::pair<double, double>> kept;
    for (const auto& e : m->edges()) {
        points += e.points.size();
        for (const Point& q : e.points) kept.insert({q.x, q.y});
    }
    std::size_t input = 0;
    for (const Curve& c : circle_and_strokes().curves)
        for (const Point& q : c.points) {
            ++input;
            EXPECT_EQ(kept.count({q.x, q.y}), 1u) << "lost " << q.x << "," << q.y;
        }
    EXPECT_EQ(input, 268u);
    EXPECT_EQ(points, input + 2 * 4);
    // Faces: the two halves of the disc, each bounded by one arc and one piece of the S.
    for (std::size_t f = 0; f < m->faces().size(); ++f) {
        if (m->faces()[f].unbounded) continue;
        EXPECT_EQ(m->faces()[f].edges.size(), 2u);
        // The S is point-symmetric about the centre: each half has half the polygon's area.
        EXPECT_NEAR(th::face_area(*m, int(f)), 0.25 * 64 * 100 * std::sin(2 * pi / 64), 1e-6);
    }
}

TEST(PlanarMapCells, TwoCrossingBezierStrokes) {
    // Two S-shaped strokes, each one cubic Bezier of an SVG path (flattened to many points),
    // mirror images of each other: they cross on their common axis.
    const Curves c = ParseSVG(R"(<svg xmlns="http://www.w3.org/2000/svg" width="300" height="300">
        <path d="M 0 0 C 300 0, 0 300, 300 300"/><path d="M 300 0 C 0 0, 300 300, 0 300"/></svg>)");
    ASSERT_EQ(c.curves.size(), 2u);
    ASSERT_GT(c.curves[0].points.size(), 10u);
    const MapPtr m = PlanarMap::induce(c);
    std::size_t crossings = 0, ends = 0;
    for (const auto& v : m->vertices()) {
        if (v.edges.size() == 4) ++crossings;
        else if (v.edges.size() == 1) ++ends;
        else ADD_FAILURE() << "vertex of degree " << v.edges.size() << " at " << v.point.x << "," << v.point.y;
    }
    EXPECT_EQ(ends, 4u);
    EXPECT_GE(crossings, 1u);
    EXPECT_EQ(m->vertices().size(), 4 + crossings);
    EXPECT_EQ(m->edges().size(), 2 + 2 * crossings);
}

TEST(PlanarMapCells, ClosedCurveAloneIsOneLoopOnItsSmallestPoint) {
    Curves c = Polyline({{5, 0}, {10, 5}, {5, 10}, {0, 5}}, true);
    c.curves[0].left = Labels{"in"};
    const MapPtr m = PlanarMap::induce(c);
    ASSERT_EQ(m->vertices().size(), 1u);
    ASSERT_EQ(m->edges().size(), 1u);
    ASSERT_EQ(m->faces().size(), 2u);
    EXPECT_EQ(m->vertices()[0].point, Point(0, 5));
    const Edge e(m, 0);
    EXPECT_EQ(SourceVertex(e), TargetVertex(e));
    EXPECT_EQ(IncidentEdges(SourceVertex(e)).size(), 2u);  // a loop counts twice
    EXPECT_NE(LeftFace(e), RightFace(e));
    EXPECT_TRUE(HasLabel(LeftFace(e), "in"));
    const Curves curve = ToCurve(e);
    ASSERT_EQ(curve.curves.size(), 1u);
    EXPECT_TRUE(curve.curves[0].closed);
    EXPECT_EQ(curve.curves[0].points.size(), 4u);
    EXPECT_NEAR(th::length(curve), 4 * std::sqrt(50.0), 1e-12);
    EXPECT_EQ(Contour(LeftFace(e)).curves[0].points.size(), 4u);
}

TEST(PlanarMapCells, OverlapsStartAndStopAtVertices) {
    // Two bent curves sharing their middle stretch: vertices where they start and stop
    // overlapping, and an edge for each stretch with its own sources.
    Curves c = Polyline({{0, 0}, {5, 2}, {10, 2}, {15, 2}});
    c.append(Polyline({{5, 2}, {10, 2}, {15, 2}, {20, 0}}));
    c.append(Polyline({{10, 2}, {10, -5}}));  // a third curve leaving the shared stretch
    const MapPtr m = PlanarMap::induce(c);
    // The six curve ends (the second curve starts where the first bends, the first ends
    // where the second bends); the third curve starts on the shared stretch.
    EXPECT_EQ(m->vertices().size(), 6u);
    std::size_t shared = 0;
    for (const auto& e : m->edges()) shared += e.sources.size() == 2;
    EXPECT_EQ(shared, 2u);  // (5,2)-(10,2) and (10,2)-(15,2): cut by the third curve
    EXPECT_EQ(m->edges().size(), 5u);
}

TEST(PlanarMapCells, LocationAtFollowsTheWholeEdge) {
    const MapPtr m = PlanarMap::induce(Polyline({{0, 0}, {10, 0}, {10, 10}}));
    ASSERT_EQ(m->edges().size(), 1u);
    const Edge e(m, 0);
    const Point p = LocationAt(e, 0.75);
    EXPECT_NEAR(p.x, 10, 1e-12);
    EXPECT_NEAR(p.y, 5, 1e-12);
    EXPECT_EQ(LocationAt(e, 0), Point(0, 0));
    EXPECT_EQ(LocationAt(e, 1), Point(10, 10));
    EXPECT_EQ(BBoxHeight(e), 10);
}

TEST(PlanarMapCells, MappersSeeWholeCells) {
    // A curved stroke from an SVG cubic Bezier: one edge, two vertices.
    const Curves s = ParseSVG(R"(<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 C 50 100, 100 -100, 150 0"/></svg>)");
    ASSERT_GT(s.curves[0].points.size(), 10u);
    std::atomic<int> edge_calls{0}, vertex_calls{0};
    const Curves edges = MapToEdges([&](const Edge& e) { ++edge_calls; return ToCurve(e); }, Constant(s))(
        Region::rectangle(-10, -100, 200, 100));
    EXPECT_EQ(edge_calls.load(), 1);
    ASSERT_EQ(edges.curves.size(), 1u);
    EXPECT_EQ(edges.curves[0].points.size(), s.curves[0].points.size());
    EXPECT_NEAR(th::length(edges), th::length(s), 1e-9);
    MapToVertices([&](const Vertex&) { ++vertex_calls; return Nothing(); }, Constant(s))(
        Region::rectangle(-10, -100, 200, 100));
    EXPECT_EQ(vertex_calls.load(), 2);
}

// ---- The direct trace of clean drawings and CGAL's arrangement give the same map ----

namespace tex::detail {
MapPtr induce_with_cgal(const Curves& curves, bool caching = true);
std::uint64_t direct_inductions();
}

TEST(PlanarMapWays, DirectTraceAndExactArrangementAgree) {
    const Region window = Region::rectangle(0, 0, 1000, 1000);
    const Region blob({{100, 100}, {900, 150}, {700, 500}, {950, 900}, {300, 800}, {50, 500}},
                      {{{300, 300}, {300, 450}, {450, 450}, {450, 300}}});
    Stripes h = StripesProperties(0.3, 70, 30), v = StripesProperties(1.9, 55);
    SetEdgeLabels(h, {"a", "b"});
    SetFaceLabels(v, {"x", "y", "z"});
    Irregular p = IrregularProperties(60e-6);
    SetWeightedFaceLabels(p, {{"f", 0.5}});
    SetWeightedEdgeLabels(p, {{"e", 0.3}});
    SetWeightedVertexLabels(p, {{"v", 0.4}});
    const std::vector<std::pair<const char*, Curves>> cases = {
        {"grid keep outside", GridPartition(h, v, KEEP_OUTSIDE)(window)},
        {"grid keep inside on a blob", GridPartition(h, v, KEEP_INSIDE)(blob)},
        {"grid crop with boundary", GridPartition(h, v, CROP_ADD_BOUNDARY)(blob)},
        {"grid crop", GridPartition(h, v, CROP)(blob)},
        {"stripes", StripesPartition(h)(blob)},
        {"voronoi keep outside", UniformPartition(p, KEEP_OUTSIDE, 1)(window)},
        {"voronoi crop with boundary", RandomPartition(p, CROP_ADD_BOUNDARY, 2)(blob)},
        {"contours", MapToFaces([](const Face& f) { return Scale(Contour(f), 0.7); },
                                UniformPartition(p, KEEP_INSIDE, 3))(window)},
        {"one closed curve", Polyline({{5, 0}, {10, 5}, {5, 10}, {0, 5}}, true)},
        {"a tree", [] {
             Curves c = Polyline({{0, 0}, {10, 0}, {20, 5}});
             c.append(Polyline({{10, 0}, {10, -10}}));
             c.append(Polyline({{20, 5}, {30, 5}, {30, 15}}));
             return c;
         }()},
        {"two squares and a stroke", two_squares()},
        {"nested pieces", [] {
             Curves c = Polyline({{0, 0}, {100, 0}, {100, 100}, {0, 100}}, true);
             c.append(Polyline({{10, 10}, {90, 10}, {90, 90}, {10, 90}}, true));
             c.append(Polyline({{40, 40}, {60, 40}, {60, 60}, {40, 60}}, true));
             c.append(Polyline({{45, 50}, {55, 50}}));                 // inside the innermost
             c.append(Polyline({{2, 2}, {5, 2}, {5, 5}}));             // in the outer ring
             c.append(Polyline({{3, 8}, {3, 3}}));
             c.append(Polyline({{200, 0}, {300, 0}, {250, 80}}, true)); // beside
             c.curves[0].left = Labels{"outer"};
             c.curves[2].left = Labels{"inner"};
             return c;
         }()},
        {"pieces stacked on one vertical", [] {
             // Smallest vertices right below other pieces' vertices: the ray's half-open rule.
             Curves c = Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true);
             c.append(Polyline({{0, 20}, {10, 20}, {10, 30}, {0, 30}}, true));
             c.append(Polyline({{0, 15}, {5, 15}}));
             c.append(Polyline({{10, 15}, {20, 15}}));
             c.append(Polyline({{-5, -20}, {25, -20}, {25, 50}, {-5, 50}}, true));
             c.append(Polyline({{2, 4}, {8, 4}, {5, 8}}, true));
             return c;
         }()},
        {"a figure eight pinched at a point", Polyline({{0, 0}, {10, 10}, {20, 0}, {20, 20}, {10, 10}, {0, 20}}, true)},
        {"a T junction", [] {  // an end on another curve's segment: exact map
             Curves c = Polyline({{0, 0}, {10, 0}});
             c.append(Polyline({{5, 0}, {5, 7}}));
             return c;
         }()},
        {"curves meeting end to end", [] {
             Curves c = Polyline({{0, 0}, {10, 0}, {10, 10}});
             c.append(Polyline({{10, 10}, {0, 10}, {0, 0}}));
             c.curves[0].left = Labels{"in"};
             return c;
         }()},
    };
    std::size_t traced = 0;
    for (const auto& [what, curves] : cases) {
        const std::uint64_t before = detail::direct_inductions();
        const MapPtr direct = PlanarMap::induce(curves);
        traced += detail::direct_inductions() - before;
        const MapPtr exact = detail::induce_with_cgal(curves);
        th::expect_same_map(*direct, *exact, what);
    }
    // All but the overlapping squares and the T junction take the direct way; the
    // comparison would be empty otherwise.
    EXPECT_EQ(traced, cases.size() - 2);
}

TEST(PlanarMapWays, SmallMapsAndForestsTraceLikeCgal) {
    // Small maps are checked pair by pair, larger ones through the grid index; a drawing
    // without cycles (parallel stripes cut to a cell) has only the unbounded face. Every
    // case gives CGAL's map, and StripesPartition(s, CROP) draws the stripes of the
    // partition without its outline.
    const Region cell({{0, 0}, {31, 1}, {30, 28}, {2, 30}});
    const Region big({{0, 0}, {300, 10}, {310, 280}, {20, 300}});
    Stripes s = StripesProperties(0.3, 2.5);
    SetEdgeLabels(s, {"fill"});
    std::size_t traced = 0;
    for (const Region* r : {&cell, &big})
        for (Border b : {CROP, CROP_ADD_BOUNDARY}) {
            const Curves c = StripesPartition(s, b)(*r);
            const std::uint64_t before = detail::direct_inductions();
            const MapPtr direct = PlanarMap::induce(c);
            traced += detail::direct_inductions() - before;
            th::expect_same_map(*direct, *detail::induce_with_cgal(c), r == &cell ? "cell" : "big region");
            if (b == CROP) {
                EXPECT_EQ(direct->faces().size(), 1u);
                for (const auto& cv : c.curves) EXPECT_TRUE(cv.labels.has("fill"));
                double with_outline = 0, alone = 0;
                for (const auto& cv : StripesPartition(s)(*r).curves)
                    if (cv.labels.has("fill")) with_outline += th::length(Curves{{cv}});
                for (const auto& cv : c.curves) alone += th::length(Curves{{cv}});
                EXPECT_NEAR(alone, with_outline, 1e-9);
            }
        }
    EXPECT_EQ(traced, 4u);
}

TEST(PlanarMapWays, ReusedScratchGivesTheMapsOfAFreshThread) {
    // The builder keeps its temporary vectors per thread from map to map (and frees those a
    // large map grew). Maps built one after the other on one thread, a large one among them,
    // by either way, are the maps a fresh thread builds for each drawing alone.
    Stripes h = StripesProperties(0.3, 1.2), v = StripesProperties(1.9, 1.2);
    SetEdgeLabels(h, {"a", "b"});
    const Curves large = GridPartition(h, v, KEEP_INSIDE)(Region::rectangle(0, 0, 170, 170));
    Curves t_junction = Polyline({{0, 0}, {10, 0}});
    t_junction.append(Polyline({{5, 0}, {5, 7}}));
    Curves nested = Polyline({{0, 0}, {100, 0}, {100, 100}, {0, 100}}, true);
    nested.append(Polyline({{40, 40}, {60, 40}, {60, 60}, {40, 60}}, true));
    nested.append(Polyline({{45, 50}, {55, 50}}));
    nested.append(Polyline({{200, 0}, {300, 0}, {250, 80}}, true));
    const std::vector<std::pair<const char*, Curves>> cases = {
        {"two squares", two_squares()}, {"nested pieces", nested}, {"T junction (exact way)", t_junction},
        {"large grid", large},          {"nested pieces again", nested}, {"two squares again", two_squares()},
        {"T junction again", t_junction}};
    std::vector<MapPtr> fresh(cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i)
        std::thread([&, i] { fresh[i] = PlanarMap::induce(cases[i].second); }).join();
    EXPECT_GT(fresh[3]->edges().size(), 30000u);  // enough half-edges to free the scratch after it
    for (std::size_t i = 0; i < cases.size(); ++i)
        th::expect_same_map(*PlanarMap::induce(cases[i].second), *fresh[i], cases[i].first);
}

TEST(PlanarMapWays, CrossingsAreRoundedToTheNearestDouble) {
    // Rays from the origin to (p, q) cross the vertical x = a at y = a q / p: a rational that
    // is mostly not a double. IEEE division of the exact integers a q and p rounds it to the
    // nearest double, and the exact map must give that same double, whatever the history of
    // its lazy number (the middle of an interval approximation is not it: the gallery's
    // exact crops drew other faces in a sanitizer build than in Release).
    std::size_t crossings = 0, not_doubles = 0;
    for (int p : {3, 7, 10, 11, 13, 29, 31, 97})
        for (int a = 1; a < p; a += 1 + p / 8) {
            Curves c = Polyline({{double(a), -1.0}, {double(a), 200.0}});
            for (int q = 1; q <= 2 * p; q += 1 + p / 16) c.append(Polyline({{0, 0}, {double(p), double(q)}}));
            const MapPtr m = detail::induce_with_cgal(c);
            for (const auto& v : m->vertices()) {
                if (v.point.x != a || v.point.y < 0.5 || v.point.y == 200.0) continue;  // not the ends
                // The ray through this crossing: the q with a q / p nearest to the vertex.
                const int q = int(std::lround(v.point.y * p / a));
                const double want = double(a * q) / double(p);
                EXPECT_EQ(v.point.y, want) << "x = " << a << ", ray to (" << p << ", " << q << ")";
                ++crossings;
                if ((a * q) % p != 0) ++not_doubles;
            }
        }
    EXPECT_GT(crossings, 300u) << crossings;
    EXPECT_GT(not_doubles, 200u) << not_doubles;  // most crossings are not doubles: the rounding is tested
}

TEST(PlanarMapWays, BothCgalTraitsGiveTheSameCells) {
    // Crossing strokes and overlapping outlines: the caching and non-caching segment traits
    // (chosen by how much the segments cross) must give the same cells.
    Curves c;
    for (int k = 0; k < 40; ++k) {
        const double a = 0.37 * k, r = 400 + 13 * k;
        c.append(Polyline({{500 + r * std::cos(a), 500 + r * std::sin(a)}, {500 - r * std::cos(a + 0.3), 500 - r * std::sin(a + 0.3)}}));
    }
    c.append(Polyline({{0, 0}, {300, 0}, {300, 300}, {0, 300}}, true));
    c.append(Polyline({{300, 0}, {600, 0}, {600, 300}, {300, 300}}, true));
    c.append(Polyline({{300, 100}, {300, 200}}));  // overlaps the shared side
    const MapPtr a = detail::induce_with_cgal(c, true), b = detail::induce_with_cgal(c, false);
    ASSERT_EQ(a->vertices().size(), b->vertices().size());
    ASSERT_EQ(a->edges().size(), b->edges().size());
    ASSERT_EQ(a->faces().size(), b->faces().size());
    EXPECT_GT(a->vertices().size(), 300u);
    for (std::size_t i = 0; i < a->vertices().size(); ++i) {
        EXPECT_NEAR(a->vertices()[i].point.x, b->vertices()[i].point.x, 1e-9);
        EXPECT_NEAR(a->vertices()[i].point.y, b->vertices()[i].point.y, 1e-9);
        EXPECT_EQ(a->vertices()[i].edges.size(), b->vertices()[i].edges.size());
    }
    for (std::size_t i = 0; i < a->edges().size(); ++i) {
        EXPECT_EQ(a->edges()[i].sources.size(), b->edges()[i].sources.size());
        EXPECT_EQ(a->edges()[i].points.size(), b->edges()[i].points.size());
    }
}

// A face's key is the hash of its outer ring read from its smallest point: the builder
// walks the ring in place, this test reads it through cycle_points, on maps whose rings
// start anywhere and run through edges of many points.
TEST(PlanarMapKeys, FaceKeyIsTheOuterRingFromItsSmallestPoint) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 40; ++trial) {
        Curves c;
        // A jittered grid of polylines (many bends per edge), plus a closed curve.
        for (int k = 0; k <= 4; ++k) {
            Curve h, v;
            for (int s = -1; s <= 13; ++s) {
                h.points.push_back({s * 1.0 + 0.01 * u(rng), k * 3.0 + 0.3 * u(rng)});
                v.points.push_back({k * 3.0 + 0.3 * u(rng), s * 1.0 + 0.01 * u(rng)});
            }
            c.curves.push_back(h);
            c.curves.push_back(v);
        }
        Curve loop;
        for (int s = 0; s < 9; ++s)
            loop.points.push_back({20 + std::cos(s * 0.7) * (3 + u(rng)), 5 + std::sin(s * 0.7) * (3 + u(rng))});
        loop.closed = true;
        c.curves.push_back(loop);
        const MapPtr m = PlanarMap::induce(c);
        ASSERT_GT(m->faces().size(), 10u);
        for (std::size_t f = 0; f < m->faces().size(); ++f) {
            std::uint64_t key = 0x46414345ULL;
            if (!m->faces()[f].unbounded) {
                const std::vector<Point> ring = m->cycle_points(int(f), 0);
                const std::size_t start = std::size_t(std::min_element(ring.begin(), ring.end()) - ring.begin());
                for (std::size_t j = 0; j < ring.size(); ++j) key = hash_point(key, ring[(start + j) % ring.size()]);
            }
            EXPECT_EQ(m->faces()[f].key, key) << "face " << f;
        }
    }
}
