// Stock mappers: JitterEdges moves only the edges it is given the label of, draws the same
// values for the same seed, keeps the ends within the stated bounds, scales by the gap and
// lets the gate drop the edges on flat ground.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "helpers.hpp"
#include "libtex/discrete.hpp"

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
    ASSERT_EQ(gapped.size(), whole.size());
    std::size_t checked = 0;
    for (std::size_t i = 0; i < whole.size(); ++i) {
        if (whole[i].empty()) continue;
        EXPECT_NEAR(th::length(gapped[i]), 0.8 * th::length(whole[i]), 1e-9);
        const Point m0 = BBoxCenter(whole[i]), m1 = BBoxCenter(gapped[i]);
        EXPECT_NEAR(distance(m0, m1), 0.0, 1e-9);
        ++checked;
    }
    // The hatch edges were drawn, so the loop above checked them.
    EXPECT_GT(checked, 0u);
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

// ---- ThinLines: continuous thinning of a family of lines (issue 16) ----

namespace {

// The index of the line of StripesProperties(kTheta, 10) that edge e lies on.
long long line_of(const Edge& e) {
    const Point m = LocationAt(e, 0.5);
    return std::llround((-std::sin(kTheta) * m.x + std::cos(kTheta) * m.y) / 10);
}

// The lines that keep at least one edge when `keep` thins them.
std::set<long long> kept_lines(const MapPtr& map, const Field& keep, const Region& owner = Region()) {
    const EdgeMapper m = ThinLines(JitterEdges("hatch", kTheta, 10, 20, 0.0), kTheta, 10, keep, owner);
    std::set<long long> out;
    for (std::size_t i = 0; i < map->edges().size(); ++i) {
        const Edge e(map, int(i));
        if (!m(e).empty()) out.insert(line_of(e));
    }
    return out;
}

}  // namespace

TEST(ThinLines, KeepsTheAskedShareOfLinesEvenlySpread) {
    // Lines 0..999: at every fraction the kept ones number 1000 * keep within 2, in every
    // window of 50 consecutive lines within 2 too (low discrepancy: no clumps, no holes).
    for (double keep : {0.1, 0.25, 0.38, 0.5, 0.73, 0.9}) {
        int total = 0;
        std::vector<int> kept;
        for (long long k = 0; k < 1000; ++k) {
            const bool in = ThinRank(k) < keep;
            total += in;
            if (in) kept.push_back(int(k));
        }
        EXPECT_NEAR(total, 1000 * keep, 2.0) << keep;
        for (int w = 0; w + 50 <= 1000; w += 10) {
            int n = 0;
            for (int k : kept) n += (k >= w && k < w + 50);
            EXPECT_NEAR(n, 50 * keep, 2.0) << "keep " << keep << ", lines " << w << "..";
        }
        // At most three distinct gaps between consecutive kept lines, and the largest is
        // less than twice the mean plus one line.
        std::set<int> gaps;
        for (std::size_t i = 1; i < kept.size(); ++i) gaps.insert(kept[i] - kept[i - 1]);
        EXPECT_LE(gaps.size(), 3u) << keep;
        EXPECT_LT(*gaps.rbegin(), 2.0 / keep + 1) << keep;
    }
    for (long long k : {-5000000LL, -1LL, 0LL, 7LL, 123456789LL}) {
        EXPECT_GE(ThinRank(k), 0.0);
        EXPECT_LT(ThinRank(k), 1.0);
    }
}

TEST(ThinLines, ASmallerFractionKeepsASubsetAndTheEndsFollowTheField) {
    const MapPtr map = hatch_grid();
    const auto all = kept_lines(map, Field(1.0));
    const auto none = kept_lines(map, Field(0.0));
    const auto half = kept_lines(map, Field(0.5));
    const auto third = kept_lines(map, Field(0.3));
    EXPECT_GT(all.size(), 10u);
    EXPECT_TRUE(none.empty());
    EXPECT_TRUE(std::includes(half.begin(), half.end(), third.begin(), third.end()));
    EXPECT_TRUE(std::includes(all.begin(), all.end(), half.begin(), half.end()));
    EXPECT_LT(third.size(), half.size());
    EXPECT_LT(half.size(), all.size());
    // A field growing from 0 on the left to 1 on the right: an edge is kept exactly where its
    // line's rank is below the field at its middle, so each line starts at one place and runs
    // on to the right (no line stops and restarts), and a NaN field keeps nothing.
    const Field ramp = [](const Point& p) { return p.x / 100.0; };
    const EdgeMapper m = ThinLines(JitterEdges("hatch", kTheta, 10, 20, 0.0), kTheta, 10, ramp);
    std::map<long long, std::vector<std::pair<double, bool>>> along;
    for (std::size_t i = 0; i < map->edges().size(); ++i) {
        const Edge e(map, int(i));
        if (!HasLabel(e, "hatch")) continue;
        const bool in = !m(e).empty();
        EXPECT_EQ(in, ThinRank(line_of(e)) < LocationAt(e, 0.5).x / 100.0);
        along[line_of(e)].push_back({LocationAt(e, 0.5).x, in});
    }
    for (auto& [k, v] : along) {
        std::sort(v.begin(), v.end());
        for (std::size_t i = 1; i < v.size(); ++i) EXPECT_FALSE(v[i - 1].second && !v[i].second) << "line " << k;
    }
    EXPECT_TRUE(kept_lines(map, Field()).empty());
}

TEST(ThinLines, AnOwnerTakesTheWholeEdgesCentredInIt) {
    const MapPtr map = hatch_grid();
    const Region left = Region::rectangle(-50, -50, 50, 130), right = Region::rectangle(50, -50, 150, 130);
    const EdgeMapper all = ThinLines(JitterEdges("hatch", kTheta, 10, 20, 0.0), kTheta, 10, Field(1.0));
    const EdgeMapper l = ThinLines(JitterEdges("hatch", kTheta, 10, 20, 0.0), kTheta, 10, Field(1.0), left);
    const EdgeMapper r = ThinLines(JitterEdges("hatch", kTheta, 10, 20, 0.0), kTheta, 10, Field(1.0), right);
    int crossing = 0;
    for (std::size_t i = 0; i < map->edges().size(); ++i) {
        const Edge e(map, int(i));
        const Curves a = all(e), b = l(e), c = r(e);
        // Each edge goes whole to exactly one side (none lies with its middle on x = 50).
        EXPECT_EQ(b.empty() + c.empty(), a.empty() ? 2 : 1);
        const Curves& got = b.empty() ? c : b;
        if (!a.empty()) EXPECT_EQ(got.curves[0].points, a.curves[0].points);
        const Point s = Location(SourceVertex(e)), t = Location(TargetVertex(e));
        crossing += !a.empty() && (s.x - 50) * (t.x - 50) < 0;
    }
    EXPECT_GT(crossing, 0);  // edges across the border were kept whole on one side
}

TEST(ThinLines, BadArgumentsAreRefused) {
    const EdgeMapper j = JitterEdges("hatch", kTheta, 10, 20, 0.0);
    EXPECT_THROW(ThinLines(j, kTheta, 0, Field(1.0)), Error);
    EXPECT_THROW(ThinLines(j, kTheta, -1, Field(1.0)), Error);
    EXPECT_THROW(ThinLines(j, std::nan(""), 10, Field(1.0)), Error);
    EXPECT_THROW(ThinLines(EdgeMapper(), kTheta, 10, Field(1.0)), Error);
    EXPECT_THROW(Pow(Field(2.0), INFINITY), Error);
    EXPECT_DOUBLE_EQ(Pow(Field(2.0), 3.0)(Point{0, 0}), 8.0);
    EXPECT_TRUE(std::isnan(Pow(Field(), 3.0)(Point{0, 0})));
}

namespace {
// Turning angle (degrees) at each inner point of a polyline.
std::vector<double> turns(const std::vector<Point>& p) {
    std::vector<double> out;
    for (std::size_t i = 1; i + 1 < p.size(); ++i) {
        const Point u = p[i] - p[i - 1], v = p[i + 1] - p[i];
        out.push_back(std::abs(std::atan2(cross(u, v), dot(u, v))) * 180 / pi);
    }
    return out;
}
// Distance from q to the polyline p.
double to_polyline(const Point& q, const std::vector<Point>& p) {
    double best = 1e300;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
        const Point e = p[i + 1] - p[i];
        const double t = std::clamp(dot(q - p[i], e) / std::max(dot(e, e), 1e-300), 0.0, 1.0);
        best = std::min(best, distance(q, p[i] + e * t));
    }
    return best;
}
}  // namespace

// A staircase of unit steps (a raster border) smoothed at 4 units: no stair steps left (every
// turn small), within a unit of the staircase, the ends where they were, the labels kept.
TEST(Smoothed, TakesTheStairStepsOutAndKeepsTheEnds) {
    Curve stairs;
    for (int i = 0; i < 20; ++i) {
        stairs.points.push_back({double(i), double(i)});
        stairs.points.push_back({double(i + 1), double(i)});
    }
    stairs.points.push_back({20, 20});
    stairs.labels = Labels::from_names({"ridge"});
    Curves c;
    c.curves.push_back(stairs);
    const Curves s = Smoothed(c, 4);
    ASSERT_EQ(s.curves.size(), 1u);
    const std::vector<Point>& p = s.curves[0].points;
    EXPECT_EQ(p.front(), stairs.points.front());
    EXPECT_EQ(p.back(), stairs.points.back());
    EXPECT_TRUE(s.curves[0].labels.has(intern_label("ridge")));
    const std::vector<double> t = turns(p);
    EXPECT_LT(*std::max_element(t.begin(), t.end()), 15.0);  // the staircase turns 90 degrees each step
    const std::vector<double> steps = turns(stairs.points);
    EXPECT_GT(*std::max_element(steps.begin(), steps.end()), 89.0);
    for (const Point& q : p) EXPECT_LT(to_polyline(q, stairs.points), 1.0);
    // A right angle is rounded, not cut across: the corner point stays within step / 4.
    Curves corner;
    corner.curves.push_back(Curve{{{0, 0}, {40, 0}, {40, 40}}});
    const Curves rounded = Smoothed(corner, 4);
    const std::vector<Point>& r = rounded.curves[0].points;
    double nearest = 1e300;
    for (const Point& q : r) nearest = std::min(nearest, distance(q, {40, 0}));
    EXPECT_LT(nearest, 1.0);
    EXPECT_GT(nearest, 0.1);
    EXPECT_THROW(Smoothed(c, 0), Error);
    EXPECT_THROW(Smoothed(c, NAN), Error);
}

// Two faces see their common border in opposite directions, and a closed border from
// different starts: both must draw the same smoothed line (issue 16: each face draws the
// part of the crest line inside it).
TEST(Smoothed, GivesTheSameLineWhicheverWayTheCurveRuns) {
    Curve wiggle;
    for (int i = 0; i <= 30; ++i) wiggle.points.push_back({3.0 * i, (i % 3 == 0) ? 0.0 : 1.7 * (i % 5)});
    Curve back = wiggle;
    std::reverse(back.points.begin(), back.points.end());
    Curves a, b;
    a.curves.push_back(wiggle);
    b.curves.push_back(back);
    const std::vector<Point> sa = Smoothed(a, 4).curves[0].points;
    std::vector<Point> sb = Smoothed(b, 4).curves[0].points;
    ASSERT_GT(sa.size(), 10u);
    EXPECT_EQ(sb.front(), back.points.front());  // each keeps its own direction
    std::reverse(sb.begin(), sb.end());
    EXPECT_EQ(sa, sb);
    // Sampled from one end only, the two would differ: the test can fail.
    std::vector<Point> from_back = CutCorners(disc::RegularPinning1D(disc::Polyline{back.points, false}, 0.25), 3);
    std::reverse(from_back.begin(), from_back.end());
    EXPECT_NE(from_back, sa);
    // A closed ring, from another start and the other way round: the same ring of points.
    Curve ring{{{0, 0}, {10, 1}, {20, 0}, {21, 10}, {20, 20}, {10, 19}, {0, 20}, {1, 10}}};
    ring.closed = true;
    Curve other = ring;
    std::rotate(other.points.begin(), other.points.begin() + 3, other.points.end());
    std::reverse(other.points.begin(), other.points.end());
    Curves r1, r2;
    r1.curves.push_back(ring);
    r2.curves.push_back(other);
    std::vector<Point> p1 = Smoothed(r1, 4).curves[0].points, p2 = Smoothed(r2, 4).curves[0].points;
    std::sort(p1.begin(), p1.end());
    std::sort(p2.begin(), p2.end());
    EXPECT_EQ(p1, p2);
}

// Points every `spacing` of length, the first half a spacing in, with the unit tangent, the
// index and the length left; each curve on its own.
TEST(MapAlong, VisitsEvenlySpacedPointsWithTheirTangents) {
    Curves c;
    c.curves.push_back(Curve{{{0, 0}, {10, 0}, {10, 4}}});  // length 14
    c.curves.push_back(Curve{{{0, 0}, {0, 0.4}}});         // shorter than half a spacing
    std::vector<Point> at, tangent;
    std::vector<long long> index;
    std::vector<double> left;
    const Curves out = MapAlong(c, 2, [&](const Point& p, const Point& t, long long k, double to_end) {
        at.push_back(p);
        tangent.push_back(t);
        index.push_back(k);
        left.push_back(to_end);
        return Polyline({p, p + Point{0, 1}});
    });
    ASSERT_EQ(at.size(), 7u);  // at 1, 3, ..., 13
    EXPECT_EQ(out.curves.size(), 7u);
    for (std::size_t k = 0; k < at.size(); ++k) {
        const double s = 1 + 2.0 * double(k);
        const Point want = s <= 10 ? Point{s, 0} : Point{10, s - 10};
        EXPECT_NEAR(distance(at[k], want), 0, 1e-12) << k;
        EXPECT_NEAR(norm(tangent[k]), 1, 1e-12);
        EXPECT_NEAR(distance(tangent[k], s <= 10 ? Point{1, 0} : Point{0, 1}), 0, 1e-12) << k;
        EXPECT_EQ(index[k], (long long)k);
        EXPECT_NEAR(left[k], 14 - s, 1e-12);
    }
    EXPECT_THROW(MapAlong(c, 0, [](const Point&, const Point&, long long, double) { return Nothing(); }), Error);
    EXPECT_THROW(MapAlong(c, 1, AlongMapper()), Error);
}
