// Planar map induction, labels and the cell built-ins of table 3.4.
#include <gtest/gtest.h>

#include <algorithm>

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
    EXPECT_EQ(m->vertices().size(), 8u);  // 6 square corners, stroke start on B, stroke tip
    EXPECT_EQ(m->edges().size(), 9u);     // 7 sides (one shared), B's right side split, stroke
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
    EXPECT_EQ(IncidentEdges(a).size(), 4u);
    EXPECT_EQ(IncidentVertices(a).size(), 4u);
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
    ASSERT_EQ(c.curves.size(), 1u);
    EXPECT_GT(signed_area(c.curves[0].points), 0);
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
