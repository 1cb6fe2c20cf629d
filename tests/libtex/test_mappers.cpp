// Stock mappers: JitterEdges moves only the edges it is given the label of, draws the same
// values for the same seed, keeps the ends within the stated bounds, scales by the gap and
// lets the gate drop the edges on flat ground.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "helpers.hpp"

using namespace tex;

namespace {

constexpr double kTheta = 0.3;  // hatch direction (radians)
const Region kBox = Region::rectangle(0, 0, 100, 80);

// Lines labelled "hatch" every 10 at kTheta, cut every 20 by unlabelled lines across.
MapPtr hatch_grid() {
    Stripes along = StripesProperties(kTheta, 10), across = StripesProperties(kTheta + pi / 2, 20);
    SetEdgeLabels(along, {"hatch"});
    return GridPartition(along, across, KEEP_OUTSIDE).induce(kBox);
}

std::vector<Curves> map_each(const EdgeMapper& m, const MapPtr& map) {
    std::vector<Curves> out;
    for (std::size_t i = 0; i < map->edges().size(); ++i) out.push_back(m(Edge(map, int(i))));
    return out;
}

struct SeedGuard {
    std::uint64_t saved = GetSeed();
    ~SeedGuard() { SetSeed(saved); }
};

std::vector<std::vector<Point>> points_of(const std::vector<Curves>& v) {
    std::vector<std::vector<Point>> out;
    for (const auto& c : v)
        for (const auto& cv : c.curves) out.push_back(cv.points);
    return out;
}

}  // namespace

TEST(JitterEdges, MovesOnlyTheLabelledEdges) {
    const MapPtr map = hatch_grid();
    const std::vector<Curves> got = map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0), map);
    std::size_t labelled = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
        const Edge e(map, int(i));
        if (HasLabel(e, "hatch")) {
            ++labelled;
            ASSERT_EQ(got[i].curves.size(), 1u);
            EXPECT_TRUE(got[i].curves[0].labels.has(intern_label("hatch")));
            EXPECT_NE(got[i].curves[0].points.front(), Location(SourceVertex(e)));
        } else {
            EXPECT_TRUE(got[i].empty()) << "edge " << i << " has no label hatch";
        }
    }
    EXPECT_GT(labelled, 20u);
    EXPECT_LT(labelled, got.size());
}

TEST(JitterEdges, SameSeedSameValuesOtherSeedOthers) {
    SeedGuard guard;
    const MapPtr map = hatch_grid();
    SetSeed(7);
    const auto a = points_of(map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0), map));
    const auto b = points_of(map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0), map));
    SetSeed(8);
    const auto c = points_of(map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0), map));
    EXPECT_EQ(a, b);
    ASSERT_EQ(a.size(), c.size());
    EXPECT_NE(a, c);
    // Through MapToEdges, on two worker threads or on this one: the same curves.
    const unsigned threads = GetThreads();
    SetThreads(2);
    SetSeed(7);
    const Curves par = MapToEdges(JitterEdges("hatch", kTheta, 10, 20, 1.0),
                                  Constant(hatch_grid()->edge_curves()))(kBox);
    const Curves ser = MapToEdges(JitterEdges("hatch", kTheta, 10, 20, 1.0),
                                  Constant(hatch_grid()->edge_curves()), MapperThreads::Serial)(kBox);
    SetThreads(threads);
    ASSERT_EQ(par.curves.size(), ser.curves.size());
    for (std::size_t i = 0; i < par.curves.size(); ++i) EXPECT_EQ(par.curves[i].points, ser.curves[i].points);
}

TEST(JitterEdges, EndsMoveWithinTheBounds) {
    const MapPtr map = hatch_grid();
    const double across = 10, along = 20, r = 0.6;
    const Point d{std::cos(kTheta), std::sin(kTheta)}, n{-d.y, d.x};
    const std::vector<Curves> got = map_each(JitterEdges("hatch", kTheta, across, along, r), map);
    double worst_across = 0, worst_along = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
        const Edge e(map, int(i));
        if (!HasLabel(e, "hatch")) continue;
        const auto& pts = got[i].curves.at(0).points;
        for (const auto& [p, v] : {std::pair{pts.front(), SourceVertex(e)}, std::pair{pts.back(), TargetVertex(e)}}) {
            const Point shift = p - Location(v);
            worst_across = std::max(worst_across, std::fabs(dot(shift, n)));
            worst_along = std::max(worst_along, std::fabs(dot(shift, d)));
        }
    }
    EXPECT_LE(worst_across, r * across / 2 + 1e-9);
    EXPECT_LE(worst_along, r * along / 2 + 1e-9);
    // The bounds are reached, not just respected (dozens of draws).
    EXPECT_GT(worst_across, 0.5 * r * across / 2);
    EXPECT_GT(worst_along, 0.5 * r * along / 2);
}

TEST(JitterEdges, TheGapShortensAboutTheMiddle) {
    const MapPtr map = hatch_grid();
    const auto whole = map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0), map);
    const auto gapped = map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0, 0.8), map);
    for (std::size_t i = 0; i < whole.size(); ++i) {
        if (whole[i].empty()) continue;
        EXPECT_NEAR(th::length(gapped[i]), 0.8 * th::length(whole[i]), 1e-9);
        const Point m0 = BBoxCenter(whole[i]), m1 = BBoxCenter(gapped[i]);
        EXPECT_NEAR(distance(m0, m1), 0.0, 1e-9);
    }
}

TEST(JitterEdges, TheGateDropsFlatEdges) {
    const MapPtr map = hatch_grid();
    const Field slope = [](const Point& p) { return p.x < 50 ? 2.0 : 30.0; };
    const auto all = map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0), map);
    const auto gated = map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0, 1.0, slope, 10.0), map);
    std::size_t kept = 0, dropped = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
        const Edge e(map, int(i));
        if (!HasLabel(e, "hatch")) continue;
        if (LocationAt(e, 0.5).x < 50) {
            EXPECT_TRUE(gated[i].empty());
            ++dropped;
        } else {
            ASSERT_EQ(gated[i].curves.size(), 1u);
            EXPECT_EQ(gated[i].curves[0].points, all[i].curves[0].points);
            ++kept;
        }
    }
    EXPECT_GT(kept, 0u);
    EXPECT_GT(dropped, 0u);
    // No value (NaN) is flat too; gate_min 0 reads no field.
    for (const auto& c : map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0, 1.0, Field(), 10.0), map))
        EXPECT_TRUE(c.empty());
    EXPECT_EQ(points_of(map_each(JitterEdges("hatch", kTheta, 10, 20, 1.0, 1.0, Field(), 0.0), map)), points_of(all));
}
