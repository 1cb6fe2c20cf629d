// Ink coverage (libtex/coverage.hpp): what every raster image of the project is drawn from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "libtex/coverage.hpp"
#include "libtex/error.hpp"
#include "libtex/parallel.hpp"

using tex::BBox;
using tex::Point;
using tex::PixelGrid;

namespace {

// Distance from p to the segment ab.
double seg_dist(Point p, Point a, Point b) {
    const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / l2, 0.0, 1.0) : 0.0;
    return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

std::vector<std::vector<Point>> random_lines(unsigned seed, int n) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-5, 105);
    std::vector<std::vector<Point>> lines;
    for (int i = 0; i < n; ++i) lines.push_back({{u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}});
    return lines;
}

}  // namespace

TEST(Coverage, GridHoldsTheWindow) {
    const PixelGrid g = PixelGrid::Of(BBox{10, 20, 13.5, 21}, 0.5);
    EXPECT_EQ(g.width, 7);
    EXPECT_EQ(g.height, 2);
    EXPECT_DOUBLE_EQ(g.Centre(0, 0).x, 10.25);
    EXPECT_DOUBLE_EQ(g.Centre(0, 0).y, 20.75);  // rows from the top
}

TEST(Coverage, StrokesFollowTheExactDistanceWithASoftEdge) {
    // Every pixel: 1 where its centre is within half the width of a line, 0 beyond half the
    // width plus half a pixel, linear in between; the largest over the lines.
    const PixelGrid g = PixelGrid::Of(BBox{0, 0, 100, 100}, 0.7);
    const double width = 2.3;
    const auto lines = random_lines(7, 40);
    tex::StrokeCoverage s(g, width);
    for (const auto& l : lines) s.Add(l, false);
    std::vector<float> cover(g.Size(), 0.0f);
    s.Render(cover);
    int inked = 0;
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c) {
            double d = INFINITY;
            for (const auto& l : lines)
                for (std::size_t k = 0; k + 1 < l.size(); ++k) d = std::min(d, seg_dist(g.Centre(c, r), l[k], l[k + 1]));
            const double want = std::clamp((width / 2 - d) / g.pixel + 0.5, 0.0, 1.0);
            ASSERT_NEAR(cover[std::size_t(r) * g.width + c], want, 1e-6) << "pixel " << c << "," << r;
            inked += want > 0;
        }
    EXPECT_GT(inked, 1000);
}

TEST(Coverage, ClosedLinesCloseAndOrderAndThreadsDoNotMatter) {
    const PixelGrid g = PixelGrid::Of(BBox{0, 0, 100, 100}, 0.5);
    auto lines = random_lines(3, 60);
    auto draw = [&](unsigned threads) {
        const tex::ThreadsScope scope(threads);
        tex::StrokeCoverage s(g, 1.0);
        for (const auto& l : lines) s.Add(l, true);
        std::vector<float> cover(g.Size(), 0.0f);
        s.Render(cover);
        return cover;
    };
    const std::vector<float> one = draw(1);
    EXPECT_EQ(draw(2), one);
    std::reverse(lines.begin(), lines.end());
    EXPECT_EQ(draw(2), one);
    // The closing segment is drawn. A triangle alone, so no other line can ink the probe: the
    // pixel centre (30.25, 45.25) lies on its closing segment (last point back to the first) and
    // far from its two open segments, so it is blank when the line is open and fully inked
    // when it is closed.
    const std::vector<Point> tri = {{20.25, 20.25}, {60.25, 20.25}, {40.25, 70.25}};
    const int c = 60, r = 109;
    ASSERT_TRUE(c >= 0 && c < g.width && r >= 0 && r < g.height);
    const Point probe = g.Centre(c, r);
    ASSERT_NEAR(seg_dist(probe, tri.back(), tri.front()), 0.0, 1e-9);
    ASSERT_GT(seg_dist(probe, tri[0], tri[1]), 0.5 + g.pixel);
    ASSERT_GT(seg_dist(probe, tri[1], tri[2]), 0.5 + g.pixel);
    auto draw_one = [&](bool closed) {
        tex::StrokeCoverage s(g, 1.0);
        s.Add(tri, closed);
        std::vector<float> cover(g.Size(), 0.0f);
        s.Render(cover);
        return cover[std::size_t(r) * g.width + c];
    };
    EXPECT_EQ(draw_one(false), 0.0f);
    EXPECT_GT(draw_one(true), 0.4f);
}

TEST(Coverage, FillsByTheEvenOddRuleAtPixelCentres) {
    // A square with a square hole: inside the ring and outside the hole exactly.
    const PixelGrid g = PixelGrid::Of(BBox{0, 0, 20, 20}, 1.0);
    const std::vector<std::vector<Point>> rings = {{{2.2, 2.2}, {17.6, 2.2}, {17.6, 17.6}, {2.2, 17.6}},
                                                   {{6.4, 6.4}, {6.4, 12.1}, {12.1, 12.1}, {12.1, 6.4}}};
    std::vector<float> cover(g.Size(), 0.0f);
    tex::CoverFill(g, rings, cover);
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c) {
            const Point p = g.Centre(c, r);
            const bool in_outer = p.x > 2.2 && p.x < 17.6 && p.y > 2.2 && p.y < 17.6;
            const bool in_hole = p.x > 6.4 && p.x < 12.1 && p.y > 6.4 && p.y < 12.1;
            EXPECT_EQ(cover[std::size_t(r) * g.width + c], (in_outer && !in_hole) ? 1.0f : 0.0f) << c << "," << r;
        }
}

TEST(Coverage, BadInputIsAClearError) {
    EXPECT_THROW(PixelGrid::Of(BBox{0, 0, 1, 1}, 0.0), tex::Error);
    EXPECT_THROW(PixelGrid::Of(BBox{0, 0, 1, 1}, NAN), tex::Error);
    EXPECT_THROW(PixelGrid::Of(BBox{}, 1.0), tex::Error);
    EXPECT_THROW(PixelGrid::Of(BBox{0, 0, 1e6, 1e6}, 0.01), tex::Error);  // 1e16 pixels
    const PixelGrid g = PixelGrid::Of(BBox{0, 0, 10, 10}, 1.0);
    EXPECT_THROW(tex::StrokeCoverage(g, 0.0), tex::Error);
    EXPECT_THROW(tex::StrokeCoverage(g, -1.0), tex::Error);
    tex::StrokeCoverage s(g, 1.0);
    std::vector<float> small(3, 0.0f);
    EXPECT_THROW(s.Render(small), tex::Error);
    EXPECT_THROW(tex::CoverFill(g, {{{1, 1}, {2, 1}, {2, 2}}}, small), tex::Error);
}
