// Mapping operators (table 3.3): every cell visited once, labels kept, parallel runs
// identical to serial ones.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <map>

#include "helpers.hpp"

using namespace tex;

namespace {

Arrangement labelled_grid() {
    Stripes h = StripesProperties(0, 10, 15), v = StripesProperties(pi / 2, 12);
    SetEdgeLabels(h, {"h1", "h2"});
    SetEdgeLabels(v, {"v1"});
    SetFaceLabels(h, {"r1", "r2", "r3"});
    SetFaceLabels(v, {"c1", "c2"});
    return GridPartition(h, v, KEEP_OUTSIDE);
}

const Region kRegion = Region::rectangle(0, 0, 100, 80);

struct ThreadsGuard {
    unsigned saved = GetThreads();
    ~ThreadsGuard() { SetThreads(saved); }
};

}  // namespace

TEST(Mapping, EachCellVisitedOnce) {
    const MapPtr m = labelled_grid().induce(kRegion);
    // Visits per cell, by the cell's index in the map (the mappers induce the same map).
    std::vector<std::atomic<int>> nv(m->vertices().size()), ne(m->edges().size()), nf(m->faces().size());
    MapToVertices([&](const Vertex& v) { ++nv.at(std::size_t(v.id())); return Nothing(); }, labelled_grid())(kRegion);
    MapToEdges([&](const Edge& e) { ++ne.at(std::size_t(e.id())); return Nothing(); }, labelled_grid())(kRegion);
    MapToFaces([&](const Face& f) {
        EXPECT_FALSE(record(f).unbounded);
        ++nf.at(std::size_t(f.id()));
        return Nothing();
    }, labelled_grid())(kRegion);
    for (const auto& n : nv) EXPECT_EQ(n, 1);
    for (const auto& n : ne) EXPECT_EQ(n, 1);
    for (std::size_t i = 0; i < nf.size(); ++i) EXPECT_EQ(nf[i], m->faces()[i].unbounded ? 0 : 1) << "face " << i;
}

TEST(Mapping, LabelsSurviveAReinducedPlanarMap) {
    const MapPtr m1 = labelled_grid().induce(kRegion);
    const MapPtr m2 = MapToEdges([](const Edge& e) { return ToCurve(e); }, labelled_grid()).induce(kRegion);
    const MapPtr m3 = MapToFaces([](const Face& f) { return Contour(f); }, labelled_grid()).induce(kRegion);
    auto by_key = [](const PlanarMap& m) {
        std::map<std::uint64_t, std::vector<std::string>> out;
        for (const auto& f : m.faces())
            if (!f.unbounded) out[f.key] = f.labels.names();
        return out;
    };
    const auto f1 = by_key(*m1);
    EXPECT_EQ(f1, by_key(*m2));
    EXPECT_EQ(f1, by_key(*m3));
    std::map<std::uint64_t, std::vector<std::string>> e1, e2;
    for (const auto& e : m1->edges()) e1[e.key] = e.labels.names();
    for (const auto& e : m2->edges()) e2[e.key] = e.labels.names();
    EXPECT_EQ(e1, e2);
    // Every face of the grid has one row and one column label.
    for (const auto& [k, names] : f1) EXPECT_EQ(names.size(), 2u);
}

TEST(Mapping, SubScaleArrangementInAMapper) {
    // A mapper evaluating a partition on its own face: the results stay inside the face.
    const Arrangement outer = GridPartition(StripesProperties(0, 50), StripesProperties(pi / 2, 50), KEEP_INSIDE);
    const Arrangement nested = MapToFaces([](const Face& f) {
        const Arrangement inner = StripesPartition(StripesProperties(pi / 4, BBoxWidth(f) / 6));
        return inner(f);
    }, outer);
    const Region r = Region::rectangle(0, 0, 200, 100);
    const Curves c = nested(r);
    EXPECT_GT(c.curves.size(), 8u * 6u);
    // Each curve lies in one 50 x 50 cell of the outer grid: the one holding its middle.
    for (const auto& cv : c.curves) {
        ASSERT_GE(cv.points.size(), 2u);
        const Point mid = (cv.points[0] + cv.points[1]) / 2;
        const double x0 = 50 * std::floor(mid.x / 50), y0 = 50 * std::floor(mid.y / 50);
        const BBox cell = BBox{x0, y0, x0 + 50, y0 + 50}.expanded(1e-9);
        for (const auto& p : cv.points) EXPECT_TRUE(cell.contains(p)) << p.x << "," << p.y << " outside its cell";
        EXPECT_TRUE(r.bbox().expanded(1e-9).contains(mid));
    }
    // Each of the 8 cells is closed by its outline: 8 cells cut into bands.
    const MapPtr m = nested.induce(r);
    EXPECT_GT(th::bounded_faces(*m), 8u * 5u);
}

TEST(Mapping, ParallelRunsEqualSerialRuns) {
    ThreadsGuard guard;
    const Arrangement a = MapToEdges([](const Edge& e) {
        const double s = Random(e, 0.2, 0.8, 0) + Random(0, 0.01);  // keyed and unkeyed
        return Polyline({LocationAt(e, 0), LocationAt(e, s)});
    }, UniformPartition(IrregularProperties(1e-3), CROP_ADD_BOUNDARY));
    const Region r = Region::rectangle(0, 0, 300, 300);
    SetThreads(1);
    const std::string serial = ToSVG(a(r), 300);
    SetThreads(2);
    const std::string parallel = ToSVG(a(r), 300);
    SetThreads(4);
    const std::string four = ToSVG(a(r), 300);
    EXPECT_EQ(serial, parallel);
    EXPECT_EQ(serial, four);
}

TEST(Mapping, MapperExceptionsPropagate) {
    const Arrangement a = MapToFaces([](const Face&) -> Curves { throw Error("my_mapper", "boom"); },
                                     GridPartition(StripesProperties(0, 10), StripesProperties(pi / 2, 10), KEEP_INSIDE));
    EXPECT_TEX_ERROR(a(kRegion), "my_mapper", "boom");
}
