// Clipping and placement building blocks.
#include <gtest/gtest.h>

#include <cmath>

#include "carto/error.hpp"
#include "carto/hatching.hpp"

using namespace carto;

namespace {
double length(const std::vector<Polyline>& ls) {
    double l = 0;
    for (const auto& p : ls)
        for (std::size_t i = 0; i + 1 < p.size(); ++i) l += tex::distance(p[i], p[i + 1]);
    return l;
}
}  // namespace

TEST(Hatching, ClipToRegionWithAHole) {
    const tex::Region r({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{3, 3}, {7, 3}, {7, 7}, {3, 7}}});
    const auto pieces = clip_to_region({{-5, 5}, {15, 5}}, r);
    EXPECT_EQ(pieces.size(), 2u);
    EXPECT_NEAR(length(pieces), 6, 1e-12);
    // A bent line that leaves and re-enters.
    const auto bent = clip_to_region({{1, 1}, {12, 1}, {12, 2}, {1, 2}}, r);
    EXPECT_EQ(bent.size(), 2u);
    EXPECT_NEAR(length(bent), 18, 1e-12);
    for (const auto& p : bent)
        for (const auto& q : p) EXPECT_TRUE(r.contains(q));
}

TEST(Hatching, ClipToConvexAndPolygonIntersection) {
    const std::vector<Point> tri = {{0, 0}, {10, 0}, {0, 10}};
    EXPECT_NEAR(length(clip_to_convex({{-1, 1}, {20, 1}}, tri)), 9, 1e-12);
    const std::vector<Point> square = {{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
    const auto piece = clip_polygon_convex(square, tri);
    EXPECT_NEAR(tex::signed_area(piece), 25, 1e-9);  // the quarter [0, 5]^2
}

TEST(Hatching, JitteredLinesAreAnchoredAndKeyedByPosition) {
    const tex::BBox a{0, 0, 100, 100}, b{50, 0, 150, 100};
    const auto la = jittered_lines(a, 0.3, 7, 20, 0.5, 0.5, 42, 1);
    const auto lb = jittered_lines(b, 0.3, 7, 20, 0.5, 0.5, 42, 1);
    // Every vertex of la inside the shared box [55, 95] x [5, 95] is also a vertex of lb.
    std::size_t shared = 0, found = 0;
    for (const auto& l : la)
        for (const auto& p : l)
            if (p.x > 55 && p.x < 95 && p.y > 5 && p.y < 95) {
                ++shared;
                for (const auto& m : lb)
                    for (const auto& q : m)
                        if (q == p) {
                            ++found;
                            goto next;
                        }
            next:;
            }
    EXPECT_GT(shared, 20u);
    EXPECT_EQ(found, shared);
    // Another seed moves the points.
    const auto lc = jittered_lines(a, 0.3, 7, 20, 0.5, 0.5, 43, 1);
    EXPECT_NE(la[3][3], lc[3][3]);
}

// Regression: the box used to be widened by the hatch length across the lines too, so a
// length much larger than the area gave so many lines that nothing was drawn at all.
TEST(Hatching, JitteredLinesCoverTheBoxWhateverTheLength) {
    const tex::BBox box{0, 0, 100, 100};
    for (double length : {20.0, 1e3, 1e9}) {
        const auto lines = jittered_lines(box, 0.0, 10, length, 0, 0, 1, 1);
        ASSERT_FALSE(lines.empty()) << "length " << length;
        tex::Region r = tex::Region::rectangle(0, 0, 100, 100);
        std::size_t inside = 0;
        for (const auto& l : lines) inside += clip_to_region(l, r).size();
        EXPECT_GE(inside, 10u) << "length " << length;  // lines at y = 0, 10, ..., 100
        EXPECT_LE(lines.size(), 14u) << "length " << length;
    }
    // Absurd densities are refused with a message instead of drawing nothing.
    try {
        jittered_lines(box, 0.0, 1e-6, 1e-6, 0, 0, 1, 1);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::Usage);
        EXPECT_NE(std::string(e.what()).find("too small"), std::string::npos) << e.what();
    }
}

TEST(Hatching, StrokesWithGaps) {
    const auto s = split_strokes({{0, 0}, {10, 0}, {20, 0}}, 0.9);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_NEAR(length(s), 18, 1e-12);
    EXPECT_NEAR(s[0][0].x, 0.5, 1e-12);
}
