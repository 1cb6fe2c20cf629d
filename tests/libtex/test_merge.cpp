// Merging operators (table 3.5): which edges Inside and Outside keep in each border mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <tuple>

#include "helpers.hpp"

using namespace tex;

namespace {

// A2: the square [0, 10]^2. A1: a line crossing it, a short segment inside, one far outside.
Arrangement square() { return Constant(Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true)); }
Arrangement strokes() {
    Curves c = Polyline({{-5, 5}, {15, 5}});
    c.append(Polyline({{2, 2}, {4, 2}}));
    c.append(Polyline({{20, 20}, {30, 20}}));
    c.curves[1].labels.add("short");
    return Constant(c);
}
const Region kAny = Region::rectangle(-100, -100, 100, 100);

double len(const Arrangement& a) { return th::length(a(kAny)); }

}  // namespace

TEST(Merge, InsideBorderModes) {
    EXPECT_NEAR(len(Inside(strokes(), square(), CROP)), 10 + 2, 1e-12);
    EXPECT_NEAR(len(Inside(strokes(), square(), CROP_ADD_BOUNDARY)), 10 + 2 + 40, 1e-12);
    EXPECT_NEAR(len(Inside(strokes(), square(), KEEP_INSIDE)), 2, 1e-12);
    EXPECT_NEAR(len(Inside(strokes(), square(), KEEP_OUTSIDE)), 20 + 2, 1e-12);
    for (const auto& c : Inside(strokes(), square(), CROP)(kAny).curves)
        for (const auto& p : c.points) EXPECT_TRUE(BBox({0, 0, 10, 10}).contains(p));
}

TEST(Merge, OutsideBorderModes) {
    EXPECT_NEAR(len(Outside(strokes(), square(), CROP)), 5 + 5 + 10, 1e-12);
    EXPECT_NEAR(len(Outside(strokes(), square(), CROP_ADD_BOUNDARY)), 5 + 5 + 10 + 40, 1e-12);
    EXPECT_NEAR(len(Outside(strokes(), square(), KEEP_INSIDE)), 10, 1e-12);
    EXPECT_NEAR(len(Outside(strokes(), square(), KEEP_OUTSIDE)), 20 + 10, 1e-12);
}

TEST(Merge, LabelsOfKeptEdgesSurvive) {
    const Curves c = Inside(strokes(), square(), CROP)(kAny);
    int labelled = 0;
    for (const auto& cv : c.curves) labelled += cv.labels.has("short");
    EXPECT_EQ(labelled, 1);
    for (const auto& cv : c.curves) EXPECT_FALSE(cv.left.has("\x01libtex-inside"));
}

TEST(Merge, FacesWithoutMaskEdgesInheritTheirStatus) {
    // A small closed square of A1 floating inside the mask (no mask edge on its boundary),
    // and one floating outside.
    Curves c = Polyline({{4, 4}, {6, 4}, {6, 6}, {4, 6}}, true);
    c.append(Polyline({{40, 40}, {42, 40}, {42, 42}, {40, 42}}, true));
    EXPECT_NEAR(len(Inside(Constant(c), square(), CROP)), 8, 1e-12);
    EXPECT_NEAR(len(Outside(Constant(c), square(), CROP)), 8, 1e-12);
    // Mask with a hole: a ring between [0,10]^2 and [3,7]^2.
    Curves ring = Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true);
    ring.append(Polyline({{3, 3}, {7, 3}, {7, 7}, {3, 7}}, true));
    // The hole is a bounded face of the mask's planar map too: "inside" means inside any
    // bounded face, so the floating square in the hole is kept.
    EXPECT_NEAR(len(Inside(Constant(c), Constant(ring), CROP)), 8, 1e-12);
}

TEST(Merge, UnionKeepsEverything) {
    // Every curve of both, uncut: the three strokes (20 + 2 + 10) and the square (40), and
    // the label of the short stroke on that stroke alone.
    const Curves u = Union(strokes(), square())(kAny);
    EXPECT_EQ(u.curves.size(), 4u);
    EXPECT_NEAR(th::length(u), 20 + 2 + 10 + 40, 1e-12);
    int labelled = 0;
    for (const auto& c : u.curves)
        if (c.labels.has("short")) {
            ++labelled;
            EXPECT_NEAR(th::length(Curves{{c}, {}, ""}), 2, 1e-12);
        }
    EXPECT_EQ(labelled, 1);
}

TEST(Merge, RegionMaskWithHole) {
    const Region r({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{3, 3}, {7, 3}, {7, 7}, {3, 7}}});
    const Curves c = apply_mask(Polyline({{-1, 5}, {11, 5}}), r, CROP);
    EXPECT_NEAR(th::length(c), 6, 1e-12);  // 3 + 3, the hole cut out
}

// ---- KEEP modes keep or drop each edge of A1 whole (thesis Table 3.5, Fig. 3.6) ----

namespace {

Curves circle(Point c, double r, const char* label) {
    Curves out;
    Curve cv;
    for (int i = 0; i < 48; ++i) cv.points.push_back(c + Point{r * std::cos(2 * pi * i / 48), r * std::sin(2 * pi * i / 48)});
    cv.closed = true;
    cv.labels = Labels{label};
    out.curves.push_back(cv);
    return out;
}

// Three circles: one well inside the square [0, 10]^2, one across its right side, one
// outside.
Arrangement three_circles() {
    Curves c = circle({5, 5}, 2, "in");
    c.append(circle({10, 5}, 2, "across"));
    c.append(circle({20, 5}, 2, "out"));
    return Constant(c);
}

std::vector<std::string> kept(const Curves& c) {
    std::vector<std::string> out;
    for (const auto& cv : c.curves) {
        EXPECT_TRUE(cv.closed) << "a circle was cut";
        EXPECT_EQ(cv.points.size(), 48u) << "a circle was cut";
        out.push_back(cv.labels.names().at(0));
    }
    std::sort(out.begin(), out.end());
    return out;
}

using Names = std::vector<std::string>;

}  // namespace

TEST(MergeKeep, CirclesAreKeptOrDroppedWhole) {
    EXPECT_EQ(kept(Inside(three_circles(), square(), KEEP_INSIDE)(kAny)), (Names{"in"}));
    EXPECT_EQ(kept(Inside(three_circles(), square(), KEEP_OUTSIDE)(kAny)), (Names{"across", "in"}));
    EXPECT_EQ(kept(Outside(three_circles(), square(), KEEP_INSIDE)(kAny)), (Names{"out"}));
    EXPECT_EQ(kept(Outside(three_circles(), square(), KEEP_OUTSIDE)(kAny)), (Names{"across", "out"}));
}

TEST(MergeKeep, CropCutsTheCircleAcrossTheBorder) {
    const Curves in = Inside(three_circles(), square(), CROP)(kAny);
    const Curves out = Outside(three_circles(), square(), CROP)(kAny);
    // Half of the crossing circle on each side.
    const double c = th::length(circle({0, 0}, 2, "x"));
    EXPECT_NEAR(th::length(in), 1.5 * c, 1e-9);
    EXPECT_NEAR(th::length(out), 1.5 * c, 1e-9);
    std::size_t open = 0;
    for (const auto& cv : in.curves) open += !cv.closed;
    EXPECT_EQ(open, 1u);  // the half circle inside, in one piece
}

TEST(MergeKeep, EdgesOfA1AreCutOnlyWhereA1MeetsItself) {
    // Two overlapping circles of A1 make four edges (two arcs each). Across the square's
    // right side (x = 10), KEEP_INSIDE keeps the three arcs left of it whole and drops b's
    // outer arc, which leaves the square.
    Curves c = circle({8, 5}, 1.5, "a");
    c.append(circle({10, 5}, 1.5, "b"));
    const Curves in = Inside(Constant(c), square(), KEEP_INSIDE)(kAny);
    ASSERT_EQ(in.curves.size(), 3u);
    for (const auto& cv : in.curves) {
        EXPECT_FALSE(cv.closed);
        for (const auto& p : cv.points) EXPECT_LT(p.x, 10);
    }
}

TEST(MergeKeep, FarAndNearCurvesAgreeWithTheExactMap) {
    // Small squares [i, i + 0.5] x [j, j + 0.5]: those with i or j equal to 0 or 10 touch the
    // mask [0, 10]^2 along one side (they take the exact planar map), the others are classified
    // by point location. A piece lying on the mask border counts for both sides.
    Curves c;
    for (int i = -2; i <= 11; ++i)
        for (int j = -2; j <= 11; ++j) c.append(Polyline({{i + 0.0, j + 0.0}, {i + 0.5, j + 0.0}, {i + 0.5, j + 0.5}, {i + 0.0, j + 0.5}}, true));
    auto whole = [](const Curves& k) {
        std::size_t n = 0;
        for (const auto& cv : k.curves) n += cv.closed && cv.points.size() == 4;
        EXPECT_EQ(n, k.curves.size());
        return n;
    };
    EXPECT_EQ(whole(Inside(Constant(c), square(), KEEP_INSIDE)(kAny)), 100u);
    EXPECT_EQ(whole(Inside(Constant(c), square(), KEEP_OUTSIDE)(kAny)), 120u);  // + the 20 touching from outside
    EXPECT_EQ(whole(Outside(Constant(c), square(), KEEP_INSIDE)(kAny)), 96u);
    EXPECT_EQ(whole(Outside(Constant(c), square(), KEEP_OUTSIDE)(kAny)), 115u);  // + the 19 touching from inside
}

TEST(MergeMask, MaskPiecesLeftOutOfTheExactMapCannotHideASide) {
    // A2: a square C with a square D nested inside it (so D's sides have the inside on both
    // hands), and a square E apart. A1 crosses D (inside C, touching neither C's sides) and
    // crosses E. C is not needed to cut anything, but leaving it out of the exact map would
    // put D and E on the same face and make A1's piece left of E look inside.
    Curves a2 = Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true);
    a2.append(Polyline({{4, 4}, {6, 4}, {6, 6}, {4, 6}}, true));
    a2.append(Polyline({{20, 0}, {30, 0}, {30, 10}, {20, 10}}, true));
    Curves a1 = Polyline({{3, 5}, {7, 5}});
    a1.append(Polyline({{15, 5}, {25, 5}}));
    EXPECT_NEAR(th::length(Inside(Constant(a1), Constant(a2), CROP)(kAny)), 4 + 5, 1e-12);
    EXPECT_NEAR(th::length(Outside(Constant(a1), Constant(a2), CROP)(kAny)), 5, 1e-12);
    EXPECT_NEAR(th::length(Outside(Constant(a1), Constant(a2), KEEP_OUTSIDE)(kAny)), 10, 1e-12);
    EXPECT_NEAR(th::length(Inside(Constant(a1), Constant(a2), KEEP_INSIDE)(kAny)), 4, 1e-12);
}

TEST(MergeMask, CropKeepsCurvesWholeBetweenCuts) {
    // A long wavy curve crossing the square twice: its inside part comes out as one curve
    // (not one piece per segment or per run of the classification).
    Curve w;
    for (int i = 0; i <= 400; ++i) w.points.push_back({-10 + 30.0 * i / 400, 5 + std::sin(i * 0.2)});
    Curves c;
    c.curves.push_back(w);
    const Curves in = Inside(Constant(c), square(), CROP)(kAny);
    ASSERT_EQ(in.curves.size(), 1u);
    EXPECT_NEAR(in.curves[0].points.front().x, 0, 1e-12);
    EXPECT_NEAR(in.curves[0].points.back().x, 10, 1e-12);
    EXPECT_EQ(Outside(Constant(c), square(), CROP)(kAny).curves.size(), 2u);
}

TEST(MergeMask, CropAddBoundaryAddsEveryMaskBoundaryWithItsLabels) {
    // A2: two squares apart, labelled "ship" inside; A1 crosses only the first. Every
    // boundary of A2's faces is added, and carries A2's face labels, so that the faces the
    // result induces inside A2 are "ship" faces again (thesis 3.2: labels live on curves).
    Curves a2 = Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true);
    a2.append(Polyline({{20, 0}, {30, 0}, {30, 10}, {20, 10}}, true));
    for (auto& c : a2.curves) c.left = Labels{"ship"};
    const Curves a1 = Polyline({{-5, 5}, {5, 5}});
    for (const Border b : {CROP_ADD_BOUNDARY}) {
        const Curves in = Inside(Constant(a1), Constant(a2), b)(kAny);
        EXPECT_NEAR(th::length(in), 5 + 40 + 40, 1e-12);
        const MapPtr m = PlanarMap::induce(in);
        std::size_t ships = 0;
        for (const auto& f : m->faces()) ships += f.labels.has("ship");
        EXPECT_EQ(ships, 2u);  // A1 ends inside the first square: it does not split it
    }
    const Curves out = Outside(Constant(a1), Constant(a2), CROP_ADD_BOUNDARY)(kAny);
    EXPECT_NEAR(th::length(out), 5 + 40 + 40, 1e-12);
    const MapPtr m = PlanarMap::induce(out);
    std::size_t ships = 0;
    for (const auto& f : m->faces()) ships += f.labels.has("ship");
    EXPECT_EQ(ships, 2u);
    // A1's own pieces keep their labels only (none here), not A2's.
    for (const auto& c : Inside(Constant(a1), Constant(a2), CROP)(kAny).curves) EXPECT_FALSE(c.left.has("ship"));
}

// ---- Crossing-by-crossing crops against the exact planar map ----
//
// Random polylines cropped by a region with a hole (a jagged ring): both ways keep the same
// pieces, with the same labels, their points equal up to the rounding of the cut points.
namespace {
Curves jagged_ring(const Point& c, double r, int n, std::uint64_t seed, bool clockwise) {
    KeyedRng rng(seed);
    std::vector<Point> pts;
    for (int i = 0; i < n; ++i) {
        const double a = (clockwise ? -1 : 1) * 2 * pi * i / n;
        const double rr = r * rng.uniform(0.6, 1.0);
        pts.push_back(c + Point{std::cos(a), std::sin(a)} * rr);
    }
    return Polyline(pts, true);
}
Curves random_strokes(std::uint64_t seed, int n) {
    KeyedRng rng(seed);
    Curves c;
    for (int i = 0; i < n; ++i) {
        std::vector<Point> pts;
        Point p{rng.uniform(-60, 60), rng.uniform(-60, 60)};
        for (int k = 0, m = 2 + int(rng.uniform(0, 4)); k < m; ++k) {
            pts.push_back(p);
            p += Point{rng.uniform(-30, 30), rng.uniform(-30, 30)};
        }
        Curves s = Polyline(pts, i % 7 == 0 && pts.size() >= 3);
        s.curves[0].labels.add(i % 2 ? "odd" : "even");
        c.append(s);
    }
    return c;
}
std::vector<std::pair<std::string, std::vector<Point>>> pieces(const Curves& c) {
    std::vector<std::pair<std::string, std::vector<Point>>> out;
    for (const auto& cv : c.curves) {
        std::string l;
        for (const auto& n : cv.labels.names()) l += n + ";";
        out.push_back({l, cv.points});
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return std::tie(a.first, a.second.front().x, a.second.front().y) <
               std::tie(b.first, b.second.front().x, b.second.front().y);
    });
    return out;
}
}  // namespace

// A CROP of open polylines walks each curve (the common case: a cell's jittered lines) and
// must give what the general crossing path gives, curve for curve and bit for bit, or step
// aside. The cases are made to be close calls: lines sharing end points on a grid, points
// put on the mask's segments by rounding, kinks next to the mask, curves crossing it twice
// at nearly the same point, axis-aligned lines through mask vertices.
TEST(FastCrop, WalkingOpenPolylinesGivesTheGeneralPathsBits) {
    std::size_t walked = 0, cases = 0;
    for (std::uint64_t seed = 1; seed <= 150; ++seed) {
        SCOPED_TRACE(seed);
        KeyedRng rng(seed * 7919);
        const Curves outline = jagged_ring({0, 0}, 30, 25, seed, false);
        std::vector<std::vector<Point>> holes;
        if (seed % 3 == 0) holes.push_back(jagged_ring({4, 3}, 8, 6, seed + 50, true).curves[0].points);
        const Region region(outline.curves[0].points, holes);
        const std::vector<Point>& ring = region.outer();
        Curves subject;
        auto add = [&](std::vector<Point> pts) {
            Curves c = Polyline(pts, false);
            c.curves[0].labels.add(subject.curves.size() % 2 ? "a" : "b");
            subject.append(c);
        };
        auto on_ring = [&](double where) {  // a point on a ring segment, rounded
            const std::size_t k = std::size_t(where * double(ring.size())) % ring.size();
            const Point &p = ring[k], &q = ring[(k + 1) % ring.size()];
            const double t = rng.uniform(0.05, 0.95);
            return p + (q - p) * t;
        };
        const int kind = int(seed % 5);
        if (kind == 0) {  // a jittered grid of two-point lines sharing their ends
            const double h = rng.uniform(2, 6), dx = rng.uniform(-40, -30), dy = rng.uniform(-40, -30);
            std::vector<std::vector<Point>> v(20, std::vector<Point>(20));
            for (int i = 0; i < 20; ++i)
                for (int j = 0; j < 20; ++j) v[i][j] = {dx + i * h + rng.uniform(-1, 1), dy + j * h + rng.uniform(-1, 1)};
            for (int i = 0; i < 20; ++i)
                for (int j = 0; j < 20; ++j) {
                    if (i + 1 < 20) add({v[i][j], v[i + 1][j]});
                    if (j + 1 < 20) add({v[i][j], v[i][j + 1]});
                }
        } else if (kind == 1) {  // lines ending or bending on the mask (rounded onto it)
            for (int i = 0; i < 60; ++i) {
                const Point m = on_ring(rng.uniform(0, 1));
                const Point a{rng.uniform(-40, 40), rng.uniform(-40, 40)};
                if (i % 2) add({a, m});
                else add({a, m, m + Point{rng.uniform(-9, 9), rng.uniform(-9, 9)}});
            }
        } else if (kind == 2) {  // kinks just across the mask: two crossings close together
            for (int i = 0; i < 60; ++i) {
                const Point m = on_ring(rng.uniform(0, 1));
                const double scale = std::pow(10.0, -double(8 + i % 8));  // 1e-8 .. 1e-15
                const Point off{rng.uniform(-scale, scale), rng.uniform(-scale, scale)};
                add({m + Point{rng.uniform(-8, 8), rng.uniform(-8, 8)}, m + off, m + Point{rng.uniform(-8, 8), rng.uniform(-8, 8)}});
            }
        } else if (kind == 3) {  // axis-aligned lines through the ring's vertices
            for (std::size_t k = 0; k < ring.size(); ++k) {
                const Point& p = ring[k];
                add(k % 2 ? std::vector<Point>{{p.x - 50, p.y}, {p.x + 50, p.y}} : std::vector<Point>{{p.x, p.y - 50}, {p.x, p.y + 50}});
            }
        } else {  // random polylines, some long
            subject = random_strokes(seed, 80);
            for (auto& c : subject.curves) c.closed = false;
        }
        for (Border b : {CROP}) {
            const std::uint64_t before = detail::polyline_crops();
            const Curves walked_out = apply_mask(subject, region, b);
            walked += detail::polyline_crops() - before;
            Curves general;
            {
                detail::GeneralCropScope general_path;
                general = apply_mask(subject, region, b);
            }
            ++cases;
            ASSERT_EQ(walked_out.curves.size(), general.curves.size());
            for (std::size_t i = 0; i < general.curves.size(); ++i) {
                ASSERT_EQ(walked_out.curves[i].points, general.curves[i].points) << i;
                ASSERT_EQ(walked_out.curves[i].closed, general.curves[i].closed);
                ASSERT_EQ(walked_out.curves[i].labels.names(), general.curves[i].labels.names());
            }
        }
    }
    // The walk takes most cases (the others step aside to the general path).
    EXPECT_GT(walked, cases / 3);
    EXPECT_LT(walked, cases);
}

namespace {
void expect_same_curves(const Curves& x, const Curves& y) {
    ASSERT_EQ(x.curves.size(), y.curves.size());
    for (std::size_t i = 0; i < y.curves.size(); ++i) {
        EXPECT_EQ(x.curves[i].points, y.curves[i].points) << i;
        EXPECT_EQ(x.curves[i].closed, y.curves[i].closed) << i;
    }
}
}  // namespace

// Two close calls met on real data, where the general path joins two pieces again at a
// rounded crossing that misses the mask: a line through a vertex a hair across a face's
// border (Chamonix.tif, bidirectional: both crossings round to one point), and lines across
// the border between two faces of a mask map (a boundary with the inside on both hands).
TEST(FastCrop, WalkingStepsAsideWhereTheGeneralPathJoinsPieces) {
    const Region face({{334120.77616684377, 5090706.0641785599},
                       {334156.8520927697, 5090613.2975118933},
                       {334208.38912980672, 5090582.3752896711},
                       {334208.38912980672, 5090720},
                       {334120.77616684377, 5090720}});
    const Curves line = Polyline({{334122.29022405209, 5090702.1708885999},
                                  {334122.2902240504, 5090702.1708885999},
                                  {334134.17750744655, 5090700.0882763602}});
    Curves general;
    {
        detail::GeneralCropScope general_path;
        general = apply_mask(line, face, CROP);
    }
    ASSERT_EQ(general.curves.size(), 1u);  // joined again at the repeated crossing
    expect_same_curves(apply_mask(line, face, CROP), general);

    // Two faces side by side: the border between them has the inside on both hands.
    const MapPtr squares = PlanarMap::induce(Append(Polyline({{0, 0}, {1, 0}, {1.3, 1}, {0, 1}}, true),
                                                    Polyline({{1, 0}, {2, 0}, {2, 1}, {1.3, 1}}, true)));
    Curves across;
    for (int k = 1; k < 10; ++k) across.append(Polyline({{-0.5, 0.1 * k}, {2.5, 0.1 * k + 0.013 * k}}));
    Curves general2;
    {
        detail::GeneralCropScope general_path;
        general2 = apply_mask(across, *squares, MaskSide::Inside, CROP);
    }
    expect_same_curves(apply_mask(across, *squares, MaskSide::Inside, CROP), general2);
    // Most lines come out whole across the slanted border (some crossings round onto it).
    EXPECT_LT(general2.curves.size(), 14u);
}

TEST(FastCrop, SamePiecesAsTheExactPlanarMap) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        SCOPED_TRACE(seed);
        Curves outline = jagged_ring({0, 0}, 50, 40, seed, false);
        const Region region(outline.curves[0].points, {jagged_ring({5, 5}, 15, 12, seed + 100, true).curves[0].points});
        const Curves subject = random_strokes(seed, 60);
        for (Border b : {CROP, CROP_ADD_BOUNDARY}) {
            const std::uint64_t before = detail::fast_crops();
            const Curves fast = apply_mask(subject, region, b);
            EXPECT_EQ(detail::fast_crops(), before + 1);  // no degenerate contact here
            Curves exact;
            {
                detail::ExactCropScope only_exact;
                exact = apply_mask(subject, region, b);
            }
            EXPECT_NEAR(th::length(fast), th::length(exact), 1e-9);
            // The exact path also splits a piece where its curve crosses itself or another
            // one; the cut points are the same.
            const auto pf = pieces(fast), pe = pieces(exact);
            EXPECT_LE(pf.size(), pe.size());
            std::map<std::string, double> lf, le;
            for (const auto& [l, pts] : pf) lf[l] += th::length(Polyline(pts));
            for (const auto& [l, pts] : pe) le[l] += th::length(Polyline(pts));
            ASSERT_EQ(lf.size(), le.size());
            for (const auto& [l, v] : lf) EXPECT_NEAR(v, le[l], 1e-9) << l;
            auto is_end_of_exact = [&](const Point& p) {
                for (const auto& q : pe)
                    if (distance(p, q.second.front()) < 1e-9 || distance(p, q.second.back()) < 1e-9) return true;
                return false;
            };
            for (const auto& q : pf) {
                EXPECT_TRUE(is_end_of_exact(q.second.front()));
                EXPECT_TRUE(is_end_of_exact(q.second.back()));
            }
            // No piece of a stroke leaves the region.
            for (const auto& c : fast.curves)
                for (std::size_t k = 0; !c.labels.empty() && k + 1 < c.points.size(); ++k)
                    EXPECT_TRUE(region.contains((c.points[k] + c.points[k + 1]) / 2));
        }
    }
}

// The exact path of a CROP cuts the curves at their exact crossings without the joint
// planar map where every contact is simple (merge.cpp, exact_crossing_pieces): the same
// curves, points, labels, sides and order as the map. Cases like the crest lines of the
// rock style: a border traced from a raster (axis-aligned steps, UTM-sized coordinates),
// lines smoothed from stretches of it (lying along it, leaving and joining it inside its
// segments, cutting its corners), the border's own segments, strokes hanging from feet on
// it, strokes ending at its vertices, touching it or crossing it at one of their points,
// strokes crossing each other and ending on one another.
TEST(ExactCrop, CutAtExactCrossingsLikeTheJointMap) {
    const Point base{331000.3, 5091000.7};
    const double cell = 7.73046875;
    std::uint64_t cut_here = 0, cases = 0, along = 0;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        SCOPED_TRACE(seed);
        KeyedRng rng(seed);
        // A staircase ring: steps right and up, then back left and down.
        std::vector<Point> ring;
        Point p = base;
        const int steps = 6 + int(rng.uniform(0, 6));
        for (int i = 0; i < steps; ++i) {
            ring.push_back(p);
            p.x += cell * (1 + int(rng.uniform(0, 4)));
            ring.push_back(p);
            p.y += cell * (1 + int(rng.uniform(0, 3)));
        }
        const Point top = p;
        ring.push_back(p);
        p.x = base.x - cell * int(rng.uniform(0, 3));
        ring.push_back(p);
        std::vector<Point> outer;
        for (const Point& q : ring) {
            // Some sides in two collinear halves (a traced border has such vertices).
            if (!outer.empty() && outer.back() != q && outer.size() % 3 == 1) outer.push_back((outer.back() + q) * 0.5);
            if (outer.empty() || outer.back() != q) outer.push_back(q);
        }
        const double w = top.x - base.x, h = top.y - base.y;
        const Point hc{base.x + 0.5 * w, base.y + 0.75 * h};
        const std::vector<Point> hole{{hc.x - cell, hc.y - cell}, {hc.x - cell, hc.y + cell}, {hc.x + cell, hc.y + cell},
                                      {hc.x + cell, hc.y - cell}};
        // The hole where it is clear of the outer ring (else none).
        BBox hole_box;
        for (const Point& q : hole) hole_box.add(q);
        bool clear = true;
        for (std::size_t i = 0; i < outer.size(); ++i) {
            BBox sb;
            sb.add(outer[i]);
            sb.add(outer[(i + 1) % outer.size()]);
            clear = clear && !sb.intersects(hole_box.expanded(cell / 4));
        }
        const Region region = clear ? Region(outer, {hole}) : Region(outer);
        const std::size_t n = outer.size();
        auto on_segment = [&](std::size_t i, double t) {  // exactly on border segment i (axis-aligned)
            const Point a = outer[i], b = outer[(i + 1) % n];
            return a.x == b.x ? Point{a.x, a.y + (b.y - a.y) * t} : Point{a.x + (b.x - a.x) * t, a.y};
        };
        auto random_point = [&] { return Point{base.x + rng.uniform(-0.2, 1.2) * w, base.y + rng.uniform(-0.2, 1.2) * h}; };
        Curves subject;
        auto add = [&](std::vector<Point> pts, const char* label) {
            Curves c = Polyline(std::move(pts));
            c.curves[0].labels.add(label);
            c.curves[0].left.add("left");
            subject.append(c);
        };
        // Odd seeds: lines along stretches of the border apart from each other, and strokes
        // on the rest of it, which the cut follows all alone; even seeds: with the border's
        // segments themselves, strokes on the lines and across everything, which send some
        // curves (and then all) to the map.
        const bool apart = seed % 2 == 1;
        std::vector<char> used(n, 0);  // border segments under a line
        for (int k = 0; k < 4; ++k) {
            // A stretch of the border smoothed (corners cut, ends kept).
            const std::size_t i0 = std::size_t(rng.uniform(0, double(n)));
            const std::size_t len = 2 + std::size_t(rng.uniform(0, 4));
            bool free = true;
            for (std::size_t q = 0; q <= len + 1; ++q) free = free && !used[(i0 + n - 1 + q) % n];
            if (apart && !free) continue;
            std::vector<Point> stretch;
            for (std::size_t q = 0; q <= len; ++q) {
                stretch.push_back(outer[(i0 + q) % n]);
                used[(i0 + q) % n] = 1;
            }
            used[(i0 + n - 1) % n] = 1;
            std::vector<Point> smooth{stretch.front()};
            for (std::size_t q = 0; q + 1 < stretch.size(); ++q) {
                smooth.push_back(stretch[q] * 0.75 + stretch[q + 1] * 0.25);
                smooth.push_back(stretch[q] * 0.25 + stretch[q + 1] * 0.75);
            }
            smooth.push_back(stretch.back());
            add(smooth, "crest");
            if (!apart) add({outer[i0], outer[(i0 + 1) % n]}, "edge");
        }
        auto free_segment = [&] {
            for (int tries = 0; tries < 50; ++tries) {
                const std::size_t i = std::size_t(rng.uniform(0, double(n)));
                if (!apart || !used[i]) return i;
            }
            return n;
        };
        for (int k = 0; k < 25; ++k) {
            const std::size_t i = free_segment();
            if (i == n) break;
            const Point foot = on_segment(i, rng.uniform(0.05, 0.95));
            add({foot, foot + Point{rng.uniform(-2, 2), rng.uniform(-2, 2)} * cell}, "stroke");
        }
        for (int k = 0; k < 6; ++k) {
            const std::size_t i = free_segment();
            if (i == n || (apart && used[(i + n - 1) % n])) continue;
            add({outer[i], random_point()}, "from a vertex");
        }
        for (int k = 0; k < 8; ++k) {
            // Through a point of the border at one of its own points (touching or crossing).
            const std::size_t i = free_segment();
            if (i == n) break;
            const Point v = on_segment(i, rng.uniform(0.1, 0.9));
            add({v + Point{rng.uniform(-3, 3), rng.uniform(-3, 3)} * cell, v, v + Point{rng.uniform(-3, 3), rng.uniform(-3, 3)} * cell},
                "through");
        }
        if (!apart) {
            for (int k = 0; k < 20; ++k) {
                std::vector<Point> pts{random_point()};
                for (int q = 0, m = 1 + int(rng.uniform(0, 4)); q < m; ++q)
                    pts.push_back(pts.back() + Point{rng.uniform(-4, 4), rng.uniform(-4, 4)} * cell);
                add(pts, "across");
            }
        }
        // Ending on one another: a horizontal stroke and one ending on it.
        const Point mid = apart ? Point{base.x - 5 * w, base.y} : random_point();
        add({mid, mid + Point{3 * cell, 0}}, "bar");
        add({mid + Point{1.5 * cell, 0}, mid + Point{1.5 * cell, 2 * cell}}, "post");
        for (bool all_exact : {false, true}) {
            Curves by_map, here;
            const std::uint64_t before = detail::exact_crossing_crops(), before_along = detail::pieces_cut_along_mask();
            {
                std::optional<detail::ExactCropScope> exact;
                if (all_exact) exact.emplace();
                here = apply_mask(subject, region, CROP);
            }
            cut_here += detail::exact_crossing_crops() - before;
            along += detail::pieces_cut_along_mask() - before_along;
            {
                std::optional<detail::ExactCropScope> exact;
                if (all_exact) exact.emplace();
                detail::JointMapScope map_only;
                by_map = apply_mask(subject, region, CROP);
            }
            ++cases;
            ASSERT_EQ(here.curves.size(), by_map.curves.size());
            for (std::size_t i = 0; i < here.curves.size(); ++i) {
                const Curve &x = here.curves[i], &y = by_map.curves[i];
                EXPECT_EQ(x.points, y.points) << i;
                EXPECT_EQ(x.closed, y.closed) << i;
                EXPECT_EQ(x.labels, y.labels) << i;
                EXPECT_EQ(x.left, y.left) << i;
                EXPECT_EQ(x.right, y.right) << i;
            }
        }
    }
    // Crops cut here, crops left to the map: the comparison covers both.
    EXPECT_GT(cut_here, cases / 4);
    EXPECT_LT(cut_here, cases);
    EXPECT_GT(along, 10u);  // pieces along the mask cut here
}

TEST(FastCrop, ADegenerateCurveAloneTakesTheExactPath) {
    // Strokes through a vertex of the region, along its edge or ending on it: with CROP the
    // other strokes are still cut crossing by crossing, and the result is the exact one.
    const Region region = Region::rectangle(0, 0, 10, 10);
    Curves subject = random_strokes(3, 40);
    subject.append(Labelled(Polyline({{-5, -5}, {15, 15}}), "through corners"));
    subject.append(Labelled(Polyline({{-2, 0}, {12, 0}}), "along an edge"));
    subject.append(Labelled(Polyline({{5, 5}, {10, 5}}), "ending on it"));
    const std::uint64_t before = detail::fast_crops();
    const Curves fast = apply_mask(subject, region, CROP);
    EXPECT_EQ(detail::fast_crops(), before + 1);
    Curves exact;
    {
        detail::ExactCropScope only_exact;
        exact = apply_mask(subject, region, CROP);
    }
    std::map<std::string, double> lf, le;
    for (const auto& [l, pts] : pieces(fast)) lf[l] += th::length(Polyline(pts));
    for (const auto& [l, pts] : pieces(exact)) le[l] += th::length(Polyline(pts));
    ASSERT_EQ(lf.size(), le.size());
    for (const auto& [l, v] : lf) EXPECT_NEAR(v, le[l], 1e-9) << l;
    EXPECT_NEAR(lf["through corners;"], std::sqrt(200.0), 1e-12);
    EXPECT_NEAR(lf["ending on it;"], 5, 1e-12);
    // With CROP_ADD_BOUNDARY the region's outline is cut by every stroke: all exact.
    const std::uint64_t before_boundary = detail::fast_crops();
    apply_mask(subject, region, CROP_ADD_BOUNDARY);
    EXPECT_EQ(detail::fast_crops(), before_boundary);
}

TEST(Crop, CutsToTheRegionItIsEvaluatedOn) {
    const Region sq = Region::rectangle(0, 0, 10, 10);
    EXPECT_NEAR(th::length(Crop(strokes(), CROP)(sq)), 10 + 2, 1e-12);
    EXPECT_NEAR(th::length(Crop(strokes(), CROP_ADD_BOUNDARY)(sq)), 10 + 2 + 40, 1e-12);
    EXPECT_NEAR(th::length(Crop(strokes(), KEEP_INSIDE)(sq)), 2, 1e-12);
    // The same as Inside with the region's outline as the mask.
    EXPECT_EQ(ToSVG(Crop(strokes(), CROP)(sq), 10), ToSVG(Inside(strokes(), square(), CROP)(sq), 10));
    // Labels ride along.
    for (const auto& c : Crop(Constant(Labelled(strokes()(sq), "fill")), CROP)(sq).curves)
        EXPECT_TRUE(c.labels.has("fill"));
}

namespace {

// Length of the pieces of `c` carrying the label `label`.
double length_labelled(const Curves& c, const std::string& label) {
    double total = 0;
    for (const auto& cv : c.curves) {
        bool on = cv.points.size() >= 2 && cv.labels.has(label);
        if (!on) continue;
        for (std::size_t k = 1; k < cv.points.size(); ++k) total += distance(cv.points[k - 1], cv.points[k]);
    }
    return total;
}

}  // namespace

// A segment whose midpoint is exactly a corner of the region, at 72 directions: the crop
// keeps its half inside the corner's quadrant (a half along a side counts as inside) and
// nothing of a segment that only touches the corner, whether it is cropped alone or with a
// grid of other lines (some through the corner too), by the fast path or the exact one.
// Where the segment overlaps a grid line (along the region's side, or inside with the exact
// path), the shared piece is one curve carrying both curves' labels: the segment is not
// dropped, it is merged (that is what looked like a segment "dropped with the rest of a
// grid"), so the segment's own label is what is measured.
TEST(Merge, CropThroughARegionCorner) {
    const Region r = Region::rectangle(-3, -3, 10, 10);
    const Point corner{10, 10};
    for (int deg = 0; deg < 360; deg += 5) {
        const double t = deg * pi / 180;
        const Point d{std::cos(t), std::sin(t)};
        const Point a = corner - d * 5.0, b = corner + d * 5.0;
        const bool half_inside = (deg >= 0 && deg <= 90) || (deg >= 180 && deg <= 270);
        Curves alone = Polyline({a, b});
        alone.curves.front().labels.add("segment");
        for (double offset : {0.0, 0.25, 0.5}) {
            Curves grid = alone;
            for (int k = -60; k <= 60; k += 5) {
                grid.curves.push_back(Polyline({{-60, k + offset}, {60, k + offset}}).curves.front());
                grid.curves.push_back(Polyline({{k + offset, -60}, {k + offset, 60}}).curves.front());
            }
            for (bool exact : {false, true}) {
                std::optional<detail::ExactCropScope> scope;
                if (exact) scope.emplace();
                const double l1 = length_labelled(apply_mask(alone, r, CROP), "segment");
                const double l2 = length_labelled(apply_mask(grid, r, CROP), "segment");
                EXPECT_NEAR(l1, half_inside ? 5.0 : 0.0, 1e-9) << deg << " degrees, exact " << exact;
                EXPECT_NEAR(l2, l1, 1e-9) << deg << " degrees, grid offset " << offset << ", exact " << exact;
            }
        }
    }
}

// FrayedCrop: cut ends drawn back from the border into a band [min, max], except on hard
// edges and where the `across` field says the drawing goes on beyond the border.
namespace {

// Horizontal lines every 0.5 across [-5, 15], cut by the square [0, 10]^2.
Arrangement rows() {
    Curves c;
    for (double y = 0.25; y < 10; y += 0.5) c.append(Polyline({{-5, y}, {15, y}}));
    return Constant(c);
}

// The rows cross the left and right sides of the rectangle [0, 10] x [-10, 20] (its top and
// bottom lie farther than any band) at right angles.
const Region kTall = Region::rectangle(0, -10, 10, 20);
double to_border(const Point& p) { return std::min(p.x, 10 - p.x); }

}  // namespace

TEST(Merge, FrayedCropDrawsCutEndsBackIntoTheBand) {
    SetSeed(3);
    const Region& sq = kTall;
    const Curves c = FrayedCrop(rows(), 0.5, 2.0)(sq);
    ASSERT_EQ(c.curves.size(), 20u);
    std::vector<double> depths;
    for (const auto& k : c.curves) {
        for (const Point& p : {k.points.front(), k.points.back()}) {
            EXPECT_TRUE(sq.contains(p));
            depths.push_back(to_border(p));
            EXPECT_GE(depths.back(), 0.5 - 1e-9);
            EXPECT_LE(depths.back(), 2.0 + 1e-6);
        }
    }
    // Irregular: the ends spread over the band, no two rows end alike.
    std::sort(depths.begin(), depths.end());
    EXPECT_LT(depths.front(), 0.8);
    EXPECT_GT(depths.back(), 1.7);
    EXPECT_EQ(std::unique(depths.begin(), depths.end()) - depths.begin(), std::ptrdiff_t(depths.size()));
    // A band of width 0 is a plain crop, moved in by min.
    for (const auto& k : FrayedCrop(rows(), 1.0, 1.0)(sq).curves)
        EXPECT_NEAR(distance(k.points.front(), k.points.back()), 8.0, 1e-6);
}

// A face drawn last shares its FrayedCrop's and Apart's curves (and IsoLines' lattice rows)
// with the threads that have run out of faces: the same curves as on one thread. Item 1 of
// the outer call ends at once, so its thread helps with item 0's nested calls.
TEST(Merge, FrayedCropApartAndIsoLinesSharedWithIdleThreadsGiveTheSameCurves) {
    SetSeed(5);
    Curves many;
    for (double y = 0.05; y < 10; y += 0.01) many.append(Polyline({{-5, y}, {15, y + 0.3}}));  // 995 rows
    const Arrangement fray = FrayedCrop(Constant(many), 0.5, 2.0, Field(), {}, 0.5);
    const Field f([](const Point& p) { return std::sin(p.x / 3) + std::cos(p.y / 4); });
    const Arrangement iso = IsoLines(f, 0.3, 0.05);
    Curves lines = Polyline({{2, -1}, {3, 11}});
    lines.append(Polyline({{7, 11}, {8.5, 4}, {6, -1}}));
    const Arrangement apart = Apart(Constant(many), lines, 0.15);
    auto both = [&] {
        Curves c = fray(kTall);
        c.append(iso(kTall));
        c.append(apart(kTall));
        return c;
    };
    Curves alone, shared;
    {
        const ThreadsScope one(1);
        alone = both();
    }
    {
        const ThreadsScope two(2);
        parallel_for(2, [&](std::size_t i) {
            if (i == 0) shared = both();
        });
    }
    ASSERT_GT(alone.curves.size(), 2 * 995u);
    ASSERT_EQ(shared.curves.size(), alone.curves.size());
    for (std::size_t i = 0; i < alone.curves.size(); ++i) ASSERT_EQ(shared.curves[i].points, alone.curves[i].points) << i;
}

TEST(Merge, FrayedCropKeepsHardEdgesAndEndsWithDrawingAcross) {
    SetSeed(3);
    // The left side labelled ridge: ends there stay on the line.
    Curves edges = Polyline({{0, 10}, {0, 0}});
    edges.curves[0].labels.add("ridge");
    edges.append(Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}));
    const Region sq = Region::rectangle(0, 0, 10, 10).with_edges(edges);
    // (The rows nearest the bottom and top sides never get deeper than the band from them:
    // they go; the others end on the ridge on the left.)
    const Curves hard = FrayedCrop(rows(), 0.5, 2.0, Field(), {"ridge"})(sq);
    EXPECT_GE(hard.curves.size(), 12u);
    for (const auto& k : hard.curves) {
        EXPECT_NEAR(k.points.front().x, 0.0, 1e-9);
        EXPECT_GE(10 - k.points.back().x, 0.5 - 1e-9);
    }
    // A field with values right of x = 10 (another face there): those ends stay too.
    const Field across([](const Point& p) { return p.x > 10 ? 1.0 : NAN; });
    for (const auto& k : FrayedCrop(rows(), 0.5, 2.0, across)(kTall).curves) {
        EXPECT_GE(k.points.front().x, 0.5 - 1e-9);
        EXPECT_NEAR(k.points.back().x, 10.0, 1e-9);
    }
}

TEST(Merge, FrayedCropIsKeyedBySeedAndGeometryOnly) {
    const Region& sq = kTall;
    auto draw = [&](std::uint64_t seed, unsigned threads) {
        SetSeed(seed);
        SetThreads(threads);
        const Curves c = MapToFaces([](const Face& f) { return FrayedCrop(rows(), 0.5, 2.0)(ToRegion(f)); },
                                    GridPartition(StripesProperties(0, 5), StripesProperties(pi / 2, 5), CROP))(sq);
        SetThreads(0);
        return ToSVG(c, 10.0);
    };
    EXPECT_EQ(draw(5, 1), draw(5, 2));
    EXPECT_NE(draw(5, 1), draw(6, 1));
    // Curves that do not reach the border are left as they are; a curve shorter than its
    // cuts goes.
    SetSeed(1);
    Curves c = Polyline({{2, 2}, {4, 2}});
    c.append(Polyline({{-1, 5}, {0.6, 5}}));
    // One running along the left side, 0.5 inside it: never 1 deep, it goes.
    c.append(Polyline({{0.5, 1}, {0.5, 8}}));
    const Curves out = FrayedCrop(Constant(c), 1.0, 1.5)(sq);
    ASSERT_EQ(out.curves.size(), 1u);
    EXPECT_EQ(out.curves[0].points, (std::vector<Point>{{2, 2}, {4, 2}}));
    EXPECT_THROW(FrayedCrop(rows(), 2.0, 1.0), Error);
    EXPECT_THROW(FrayedCrop(rows(), -1.0, 1.0), Error);
}

// With `beyond`, that share of the ends goes on past the border to the band's depth outside
// (straight on), the rest back inside: the curves end on both sides of the border, none on
// it, and an end whose way out meets another face goes back in instead.
TEST(Merge, FrayedCropDrawsAShareOfTheEndsOnPastTheBorder) {
    SetSeed(3);
    const Region& sq = kTall;
    auto signed_depth = [](const Point& p) { return p.x < 5 ? p.x : 10 - p.x; };  // < 0: outside
    for (double beyond : {0.0, 0.5, 1.0}) {
        const Curves c = FrayedCrop(rows(), 0.5, 2.0, Field(), {}, beyond)(sq);
        ASSERT_EQ(c.curves.size(), 20u) << beyond;
        std::size_t outside = 0, ends = 0;
        for (const auto& k : c.curves) {
            EXPECT_EQ(k.points.size(), 2u);
            EXPECT_EQ(k.points.front().y, k.points.back().y);  // straight on, along the row
            for (const Point& p : {k.points.front(), k.points.back()}) {
                const double d = signed_depth(p);
                ++ends;
                outside += d < 0;
                EXPECT_GE(std::abs(d), 0.5 - 1e-6) << beyond;
                EXPECT_LE(std::abs(d), 2.0 + 1e-6) << beyond;
            }
        }
        if (beyond == 0) EXPECT_EQ(outside, 0u);
        if (beyond == 1) EXPECT_EQ(outside, ends);
        if (beyond == 0.5) {
            EXPECT_GT(outside, ends / 4);
            EXPECT_LT(outside, 3 * ends / 4);
        }
    }
    // The share's draw is the end's own: the ends that stay inside are those of beyond = 0.
    // (The same stream for both: the first operator created after SetSeed.)
    SetSeed(3);
    const Curves none = FrayedCrop(rows(), 0.5, 2.0)(sq);
    SetSeed(3);
    const Curves half = FrayedCrop(rows(), 0.5, 2.0, Field(), {}, 0.5)(sq);
    ASSERT_EQ(none.curves.size(), half.curves.size());
    for (std::size_t i = 0; i < half.curves.size(); ++i) {
        const auto &h = half.curves[i].points, &n = none.curves[i].points;
        if (signed_depth(h.front()) > 0) EXPECT_NEAR(h.front().x, n.front().x, 1e-6);
        if (signed_depth(h.back()) > 0) EXPECT_NEAR(h.back().x, n.back().x, 1e-6);
        // One that goes out goes as deep as it would have gone in.
        if (signed_depth(h.front()) < 0) EXPECT_NEAR(-h.front().x, n.front().x, 1e-6);
        if (signed_depth(h.back()) < 0) EXPECT_NEAR(h.back().x - 10, 10 - n.back().x, 1e-6);
    }
    // Another face 1 beyond the right side: an end goes out there only as far as the way is
    // free (never onto the face), the others back in; the left side all go out.
    const Field across([](const Point& p) { return p.x > 11 ? 1.0 : NAN; });
    std::size_t left_out = 0, right_in = 0;
    for (const auto& k : FrayedCrop(rows(), 0.5, 2.0, across, {}, 1.0)(sq).curves) {
        const double x = k.points.back().x;
        EXPECT_TRUE((x >= 8.0 - 1e-6 && x <= 9.5 + 1e-6) || (x >= 10.5 - 1e-6 && x < 11)) << x;
        right_in += x < 10;
        left_out += k.points.front().x < 0;
    }
    EXPECT_EQ(left_out, 20u);
    EXPECT_GT(right_in, 5u);
    EXPECT_THROW(FrayedCrop(rows(), 0.5, 2.0, Field(), {}, 1.5), Error);
    EXPECT_THROW(FrayedCrop(rows(), 0.5, 2.0, Field(), {}, -0.1), Error);
}

// FrayedCrop on curves in hand is the operator on those curves: the same stream (taken when
// called, as creating the operator takes it), the same curves, bit for bit; two calls in turn
// draw as two operators created in turn. The rows lie partly outside, so the crop cuts them.
TEST(Merge, FrayedCropOfCurvesInHandIsTheOperatorOnThem) {
    const Region& sq = kTall;
    const Curves given = rows()(sq);
    const Field across([](const Point& p) { return p.x > 11 ? 1.0 : NAN; });
    for (double beyond : {0.0, 0.5}) {
        SetSeed(7);
        const Curves a1 = FrayedCrop(Constant(given), 0.5, 2.0, across, {"hard"}, beyond)(sq);
        const Curves a2 = FrayedCrop(Constant(given), 0.3, 1.0, across, {"hard"}, beyond)(sq);
        SetSeed(7);
        const Curves b1 = FrayedCrop(Curves(given), sq, 0.5, 2.0, across, {"hard"}, beyond);
        const Curves b2 = FrayedCrop(Curves(given), sq, 0.3, 1.0, across, {"hard"}, beyond);
        ASSERT_EQ(a1.curves.size(), b1.curves.size()) << beyond;
        ASSERT_EQ(a2.curves.size(), b2.curves.size()) << beyond;
        for (std::size_t i = 0; i < a1.curves.size(); ++i) EXPECT_EQ(a1.curves[i].points, b1.curves[i].points) << i;
        for (std::size_t i = 0; i < a2.curves.size(); ++i) EXPECT_EQ(a2.curves[i].points, b2.curves[i].points) << i;
        // The second operator draws other depths than the first.
        EXPECT_NE(a1.curves[0].points, a2.curves[0].points);
    }
    EXPECT_THROW(FrayedCrop(Curves(given), sq, 2.0, 1.0), Error);
}

// A crop of curves given up by the caller (apply_mask(Curves&&)) moves the curves it keeps
// whole instead of copying them, and gives what the copying crop gives: the same pieces in
// the same order, whether the fast crop decides or the exact path does (a curve through a
// vertex of the region sends the crop there, and the curves it was given are still whole).
TEST(Merge, ACropOfCurvesGivenUpMovesTheWholeOnesAndCutsTheSame) {
    std::mt19937 rng(20261207);
    std::uniform_real_distribution<double> u(0, 1);
    const Region r({{0, 0}, {10, 1}, {9, 8}, {4, 11}, {-1, 7}});
    for (int k = 0; k < 60; ++k) {
        Curves c;
        for (int i = 0; i < 40; ++i) {
            const Point a{u(rng) * 14 - 2, u(rng) * 14 - 2};
            c.append(Polyline({a, a + Point{u(rng) * 3 - 1.5, u(rng) * 3 - 1.5}, a + Point{u(rng) * 4 - 2, u(rng) * 4 - 2}}));
        }
        if (k % 3 == 0) c.append(Polyline({{-3, -3}, {0, 0}, {1, 5}}));  // through a vertex: the exact path
        const Curves copied = apply_mask(c, r, CROP);
        Curves given = c;
        const Curves moved = apply_mask(std::move(given), r, CROP);
        ASSERT_EQ(copied.curves.size(), moved.curves.size()) << k;
        for (std::size_t i = 0; i < copied.curves.size(); ++i) {
            ASSERT_EQ(copied.curves[i].points, moved.curves[i].points) << k << " piece " << i;
            ASSERT_TRUE(copied.curves[i].labels == moved.curves[i].labels) << k << " piece " << i;
        }
        // The fast crop moved the whole curves out; the exact path took none.
        std::size_t emptied = 0;
        for (const Curve& g : given.curves) emptied += g.points.empty();
        if (k % 3 == 0) EXPECT_EQ(emptied, 0u) << k;
        else EXPECT_GT(emptied, 0u) << k;
    }
}

// Only ends whose strokes cross the rim steeply (60 degrees or more) go on past it: a stroke
// drawn on at a slant runs along the outside of the rim, a hair on the rock's edge.
TEST(Merge, FrayedCropDrawsOnlySteepEndsOnPastTheBorder) {
    // Parallel strokes at `angle` to the sides x = 0 and x = 10 of kTall, every end on a side.
    auto slanted = [](double angle) {
        Curves c;
        const double rise = 10 / std::tan(angle * tex::pi / 180);
        for (double y = -5; y < 5; y += 0.5) c.append(Polyline({{-5, y - rise / 2}, {15, y + 1.5 * rise}}));
        return Constant(c);
    };
    for (double angle : {40.0, 55.0, 65.0, 80.0, 90.0}) {
        SetSeed(3);
        const Curves c = FrayedCrop(slanted(angle), 0.5, 2.0, Field(), {}, 1.0)(kTall);
        std::size_t ends = 0, outside = 0;
        for (const auto& k : c.curves)
            for (const Point& p : {k.points.front(), k.points.back()}) {
                ++ends;
                outside += p.x < 0 || p.x > 10;
                EXPECT_GE(std::min(std::abs(p.x), std::abs(10 - p.x)), 0.5 - 1e-6) << angle;  // none on the rim
            }
        ASSERT_GT(ends, 30u) << angle;
        if (angle < 60) EXPECT_EQ(outside, 0u) << angle << " degrees: drawn back in";
        else EXPECT_EQ(outside, ends) << angle << " degrees: all drawn on";
    }
}

// Apart: a gap left along lines.
TEST(Merge, ApartLeavesAGapAlongTheLines) {
    // Horizontal strokes across a vertical line at x = 5: each cut in two, the gap exactly the
    // distance on either side.
    Curves strokes;
    for (int k = 0; k < 5; ++k) strokes.append(Polyline({{0, double(k)}, {10, double(k)}}));
    strokes.curves[2].labels.add("fill");
    const Curves line = Polyline({{5, -1}, {5, 6}});
    const Curves out = Apart(Constant(strokes), line, 1.0)(Region::rectangle(-1, -1, 11, 11));
    ASSERT_EQ(out.curves.size(), 10u);
    for (const auto& c : out.curves) {
        const double near_x = c.points.front().x < 5 ? c.points.back().x : c.points.front().x;
        EXPECT_NEAR(std::abs(near_x - 5), 1.0, 1e-9);
        EXPECT_TRUE(c.points.front().x == 0 || c.points.back().x == 10);
    }
    EXPECT_TRUE(out.curves[4].labels.has("fill"));
    // A stroke that never comes near stays as it is; one wholly within the gap goes.
    const Curves far = Apart(Constant(Polyline({{0, 20}, {10, 20}})), line, 1.0)(Region::rectangle(-1, -1, 11, 30));
    ASSERT_EQ(far.curves.size(), 1u);
    EXPECT_EQ(far.curves[0].points, (std::vector<Point>{{0, 20}, {10, 20}}));
    EXPECT_TRUE(Apart(Constant(Polyline({{4.5, 0}, {5.5, 0}})), line, 1.0)(Region::rectangle(-1, -1, 11, 11)).empty());
    // Round the line's end: a stroke passing 0.6 below it (y = -1.6) is cut where it enters the
    // disc of radius 1 round (5, -1): x = 5 -/+ 0.8.
    const Curves round = Apart(Constant(Polyline({{0, -1.6}, {10, -1.6}})), line, 1.0)(Region::rectangle(-1, -3, 11, 11));
    ASSERT_EQ(round.curves.size(), 2u);
    EXPECT_NEAR(round.curves[0].points.back().x, 4.2, 1e-9);
    EXPECT_NEAR(round.curves[1].points.front().x, 5.8, 1e-9);
    // A closed ring cut once is one piece, whichever point it starts from.
    const Curves ring = Apart(Constant(Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true)),
                              Polyline({{5, 9}, {5, 12}}), 1.0)(Region::rectangle(-1, -1, 11, 13));
    ASSERT_EQ(ring.curves.size(), 1u);
    EXPECT_FALSE(ring.curves[0].closed);
    EXPECT_NEAR(ring.curves[0].points.front().x, 4.0, 1e-9);
    EXPECT_NEAR(ring.curves[0].points.back().x, 6.0, 1e-9);
    EXPECT_EQ(ring.curves[0].points.size(), 6u);
    EXPECT_THROW(Apart(Constant(strokes), line, 0.0), Error);
}

TEST(Merge, CutAtLevelsHangsRowsFromTheLevelLines) {
    // A plane falling southward (f = y) and strokes down it: cut at every 10, each piece
    // starts on a level line below it and ends 1 above the next (the gap on the higher side).
    const Field f = FunctionField([](const Point& p) { return p.y; });
    Curves strokes;
    for (int k = 0; k < 3; ++k) strokes.append(Polyline({{double(k), 45}, {double(k), 3}}));     // downhill
    strokes.append(Polyline({{5, 3}, {5, 45}}));                                                  // uphill
    strokes.curves[3].labels.add("fill");
    const Curves out = CutAtLevels(Constant(strokes), f, 10, 1)(kAny);
    // 45..41, 40..31, 30..21, 20..11, 10..3 on each: five pieces, each from a level line down.
    ASSERT_EQ(out.curves.size(), 20u);
    for (const auto& c : out.curves) {
        const double hi = std::max(c.points.front().y, c.points.back().y);
        const double lo = std::min(c.points.front().y, c.points.back().y);
        EXPECT_TRUE(hi == 45 || std::abs(std::remainder(hi, 10)) < 1e-9) << hi;  // on a level line
        EXPECT_TRUE(lo == 3 || std::abs(std::remainder(lo - 1, 10)) < 1e-9) << lo;  // 1 above the next
    }
    // The same pieces whichever way a stroke runs, labels kept.
    for (std::size_t k = 0; k < 5; ++k) {
        const auto& down = out.curves[k].points;
        const auto& up = out.curves[15 + 4 - k].points;
        EXPECT_NEAR(down.front().y, up.back().y, 1e-9);
        EXPECT_NEAR(down.back().y, up.front().y, 1e-9);
        EXPECT_TRUE(out.curves[15 + k].labels.has("fill"));
    }
    // Sampled between the points: a bent field cut where it crosses, not where a straight
    // reading of the ends says. f = y^2 / 10 on a stroke from y = 0 to 20 crosses 10 at
    // y = 10, 20 at y = 14.14..., 30 at y = 17.32...
    const Field bent = FunctionField([](const Point& p) { return p.y * p.y / 10; });
    const Curves fine = CutAtLevels(Constant(Polyline({{0, 20}, {0, 0}})), bent, 10, 0, 0.01)(kAny);
    std::vector<double> ends;
    for (const auto& c : fine.curves) ends.push_back(c.points.back().y);
    std::sort(ends.begin(), ends.end());
    ASSERT_GE(ends.size(), 4u);
    EXPECT_NEAR(ends[1], 10, 1e-3);
    EXPECT_NEAR(ends[2], std::sqrt(200.0), 1e-3);
    EXPECT_NEAR(ends[3], std::sqrt(300.0), 1e-3);
    // Only the curve's own points are kept between the cuts, not the samples.
    for (const auto& c : fine.curves) EXPECT_EQ(c.points.size(), 2u);
    // A closed curve is cut on its closing side as well: a ring up the right side (y = 0 to
    // 25) and down the left, cut at 10 and 20 on both sides, is five open pieces (the first
    // and the last meet at the ring's first point), their cut ends on the levels.
    const Curves ring = CutAtLevels(Constant(Polyline({{0, 0}, {10, 0}, {10, 25}, {0, 25}}, true)), f, 10, 0, 1)(kAny);
    ASSERT_EQ(ring.curves.size(), 5u);
    std::vector<double> at_x0;
    for (const auto& c : ring.curves) {
        EXPECT_FALSE(c.closed);
        for (const Point& e : {c.points.front(), c.points.back()})
            if (e.x == 0 && e.y != 0) at_x0.push_back(e.y);
    }
    std::sort(at_x0.begin(), at_x0.end());
    ASSERT_EQ(at_x0.size(), 4u);  // 10 and 20 on the closing side, each the end of two pieces
    EXPECT_NEAR(at_x0[0], 10, 1e-9);
    EXPECT_NEAR(at_x0[3], 20, 1e-9);
    // No value, no cut; bad arguments refused.
    const Curves none = CutAtLevels(Constant(strokes), Field(), 10, 1)(kAny);
    EXPECT_EQ(none.curves.size(), strokes.curves.size());
    EXPECT_THROW(CutAtLevels(Constant(strokes), f, 0, 1), Error);
    EXPECT_THROW(CutAtLevels(Constant(strokes), f, 10, -1), Error);
    EXPECT_THROW(CutAtLevels(Constant(strokes), f, 10, 1, -0.5), Error);
}

TEST(Merge, CutAtLevelsCutsAPartAsTheWhole) {
    // The levels are the plane's: a stroke cut in two regions gives, in each, the whole's
    // pieces cut to it (the cuts placed on the level lines, whatever the samples around them).
    const Field f = FunctionField([](const Point& p) { return 0.3 * p.y + 0.1 * p.x + 0.02 * p.x * p.y; });
    const Curves stroke = Polyline({{1, 40}, {3, 20}, {2, 1}});
    const Curves whole = CutAtLevels(Crop(Constant(stroke), CROP), f, 2.5, 0.4, 0.2)(kAny);
    const Curves lower = CutAtLevels(Crop(Constant(stroke), CROP), f, 2.5, 0.4, 0.2)(Region::rectangle(-10, -10, 10, 20));
    auto same = [](const Curve& a, const Curve& b) {
        if (a.points.size() != b.points.size()) return false;
        for (std::size_t i = 0; i < a.points.size(); ++i)
            if (distance(a.points[i], b.points[i]) > 1e-9) return false;
        return true;
    };
    std::size_t matched = 0;
    for (const auto& c : lower.curves)
        for (const auto& w : whole.curves) matched += same(c, w);
    // Every piece of the lower part but the one the region's edge cuts is a piece of the whole.
    EXPECT_GE(matched + 1, lower.curves.size());
    EXPECT_GE(matched, 3u);
}

TEST(Fields, NoiseIsSmoothBoundedAndKeyedBySeed) {
    const std::uint64_t saved = GetSeed();
    SetSeed(7);
    const Field a = Noise(10);
    const Field b = Noise(10);
    SetSeed(8);
    const Field c = Noise(10);
    SetSeed(saved);
    double lo = 1, hi = -1, differs = 0;
    for (int i = 0; i < 200; ++i) {
        const Point p{i * 0.77 - 50, i * 1.31 - 80};
        const double v = a(p);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        EXPECT_EQ(v, b(p));                                  // the same seed, the same noise
        differs += std::abs(v - c(p));
        EXPECT_LT(std::abs(a(p + Point{0.01, 0}) - v), 0.01);  // smooth: no jump over 1/1000 of its wavelength
    }
    EXPECT_GE(lo, -1.0);
    EXPECT_LE(hi, 1.0);
    EXPECT_GT(hi - lo, 0.8);      // it spans most of its range
    EXPECT_GT(differs, 200 * 0.1);  // another seed, another noise
    EXPECT_THROW(Noise(0), Error);
}

TEST(Fields, NoiseReadInTurnsGivesWhatEachGivesAlone) {
    // Noise keeps the last lattice cell it read on each thread: fields read in turns at the
    // same points (other seeds, other wavelengths) must each give what they give read alone.
    const std::uint64_t saved = GetSeed();
    SetSeed(7);
    const Field a = Noise(10), b = Noise(10.5);
    SetSeed(8);
    const Field c = Noise(10);
    SetSeed(saved);
    std::vector<Point> pts;
    for (int i = 0; i < 300; ++i) pts.push_back({i * 0.37 - 40, (i % 17) * 0.9 - 8});  // runs within cells
    auto alone = [&](const Field& f) {
        std::vector<double> v;
        for (const Point& p : pts) v.push_back(f(p));
        return v;
    };
    const std::vector<double> va = alone(a), vb = alone(b), vc = alone(c);
    int differ = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const double x = c(pts[i]), y = a(pts[i]), z = b(pts[i]);
        EXPECT_EQ(y, va[i]) << i;
        EXPECT_EQ(z, vb[i]) << i;
        EXPECT_EQ(x, vc[i]) << i;
        differ += va[i] != vc[i] && va[i] != vb[i];
    }
    EXPECT_GT(differ, 250);  // the three fields do differ
}

TEST(Merge, MovingAverageIsLocalAndKeepsTheEnds) {
    // A zigzag: averaged over 2 points either side, its teeth shrink; a piece of it is averaged
    // as the whole is, away from the piece's ends.
    std::vector<Point> zig;
    for (int i = 0; i < 40; ++i) zig.push_back({double(i), i % 2 ? 1.0 : 0.0});
    const Curves whole = MovingAverage(Polyline(zig), 2);
    EXPECT_EQ(whole.curves[0].points.front(), zig.front());
    EXPECT_EQ(whole.curves[0].points.back(), zig.back());
    for (std::size_t i = 2; i + 2 < zig.size(); ++i) EXPECT_NEAR(whole.curves[0].points[i].y, 0.5, 0.11);
    const std::vector<Point> part_in(zig.begin() + 10, zig.begin() + 30);
    const Curves part = MovingAverage(Polyline(part_in), 2);
    for (std::size_t i = 2; i + 2 < part_in.size(); ++i)
        EXPECT_EQ(part.curves[0].points[i], whole.curves[0].points[i + 10]);
    // A closed square's window wraps round: every corner drawn in towards its two neighbours.
    const Curves cut = MovingAverage(Polyline({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, true), 1);
    const std::vector<Point> in{{4.0 / 3, 4.0 / 3}, {8.0 / 3, 4.0 / 3}, {8.0 / 3, 8.0 / 3}, {4.0 / 3, 8.0 / 3}};
    for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(distance(cut.curves[0].points[i], in[i]), 0, 1e-12);
}

// ---- Merges whose cost follows curves and crossings, not points

namespace {

// A circle of n points.
Curves circle(Point c, double r, int n, const char* label = nullptr) {
    std::vector<Point> p;
    for (int k = 0; k < n; ++k) p.push_back(c + Point{std::cos(2 * pi * k / n), std::sin(2 * pi * k / n)} * r);
    Curves out = Polyline(p, true);
    if (label) out.curves[0].labels.add(label);
    return out;
}

// Three overlapping squares and a triangle: a mask with inner boundaries and corners.
MapPtr squares_mask() {
    Curves m = Polyline({{0, 0}, {40, 0}, {40, 40}, {0, 40}}, true);
    m.append(Polyline({{30, 30}, {70, 30}, {70, 70}, {30, 70}}, true));
    m.append(Polyline({{80, 0}, {100, 0}, {100, 20}, {80, 20}}, true));
    m.append(Polyline({{0, 60}, {20, 90}, {-10, 90}}, true));
    return PlanarMap::induce(m);
}

}  // namespace

TEST(MergeCost, ACurveThatMeetsNothingIsClassifiedWholeWhateverItsPoints) {
    const MapPtr mask = squares_mask();
    // 60 circles of 200 points, each at least 1.5 from every mask boundary and apart from
    // the others (13 inside the mask), and one circle of 50 points across the first square's
    // right side.
    Curves subject;
    for (int i = 0; i < 60; ++i) {
        const Point c{-46.0 + 12.0 * (i % 15), -33.0 + 35.0 * (i / 15)};
        subject.append(circle(c, 1.5, 200));
    }
    const Curves across = circle({40, 10}, 3, 50, "across");
    Curves both = subject;
    both.append(across);
    for (MaskSide side : {MaskSide::Inside, MaskSide::Outside})
        for (Border b : {CROP, CROP_ADD_BOUNDARY, KEEP_INSIDE, KEEP_OUTSIDE}) {
            SCOPED_TRACE(int(b) * 2 + int(side));
            const std::uint64_t s0 = detail::segments_searched();
            const Curves quiet = apply_mask(subject, *mask, side, b);
            const std::uint64_t s1 = detail::segments_searched();
            const Curves fast = apply_mask(both, *mask, side, b);
            const std::uint64_t s2 = detail::segments_searched();
            // The 12,000 segments of the circles that meet nothing are never searched; the
            // circle across a boundary is searched segment by segment against the mask.
            EXPECT_EQ(s1 - s0, 0u);
            EXPECT_EQ(s2 - s1, 50u);
            Curves exact;
            {
                detail::ExactCropScope only_exact;
                exact = apply_mask(both, *mask, side, b);
            }
            EXPECT_NEAR(th::length(fast), th::length(exact), 1e-9);
            if (b == KEEP_INSIDE || b == KEEP_OUTSIDE) EXPECT_EQ(ToSVG(fast, 200), ToSVG(exact, 200));
            // Whole circles: the 13 inside the mask for Inside, the 47 others for Outside.
            std::size_t whole = 0;
            for (const auto& c : quiet.curves) whole += c.closed && c.points.size() == 200;
            EXPECT_EQ(whole, side == MaskSide::Inside ? 13u : 47u);
        }
}

TEST(MergeCost, KeepModesDecideByCrossingsAsTheExactMapDoes) {
    const MapPtr mask = squares_mask();
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        SCOPED_TRACE(seed);
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(-20, 110);
        Curves subject;
        for (int i = 0; i < 40; ++i) {
            // Rounded to quarters, so that some vertices fall on mask corners and sides.
            auto q = [&] { return std::round(u(rng) * 4) / 4; };
            const Point c{q(), q()};
            if (i % 3 == 0) subject.append(circle(c, 2 + (i % 7), 4 + 4 * (i % 5)));
            else if (i % 3 == 1) subject.append(Polyline({c, {q(), q()}, {q(), q()}}));
            else subject.append(Polyline({c, c + Point{10, 0}, c + Point{10, 10}}, true));
        }
        // Degenerate contacts: along the first square's bottom side, through its corner,
        // ending on its right side.
        subject.append(Polyline({{-5, 0}, {20, 0}}));
        subject.append(Polyline({{-5, -5}, {5, 5}}));
        subject.append(Polyline({{45, 20}, {40, 20}}));
        for (MaskSide side : {MaskSide::Inside, MaskSide::Outside})
            for (Border b : {KEEP_INSIDE, KEEP_OUTSIDE}) {
                const Curves fast = apply_mask(subject, *mask, side, b);
                Curves exact;
                {
                    detail::ExactCropScope only_exact;
                    exact = apply_mask(subject, *mask, side, b);
                }
                EXPECT_EQ(ToSVG(fast, 200), ToSVG(exact, 200)) << int(side) << " " << int(b);
            }
    }
}

TEST(MergeCost, ACurveThatCrossesItselfIsStillSplitIntoItsEdges) {
    // A pentagram goes twice round its centre, every turn the same way: the quick test of
    // simple curves must not take it for one. Its 5 crossings cut it into 10 edges (5 tips,
    // 5 sides of the inner pentagon); a mask holding all but the top tip keeps 9 of them
    // (KEEP_INSIDE). Taken whole, the pentagram would be dropped.
    std::vector<Point> star;
    for (int k = 0; k < 5; ++k) {
        const double t = pi / 2 + 4 * pi * k / 5;
        star.push_back(Point{std::cos(t), std::sin(t)} * 10.0);
    }
    const Curves pentagram = Polyline(star, true);
    const MapPtr below = PlanarMap::induce(Polyline({{-20, -20}, {20, -20}, {20, 4}, {-20, 4}}, true));
    const Curves kept = apply_mask(pentagram, *below, MaskSide::Inside, KEEP_INSIDE);
    EXPECT_EQ(kept.curves.size(), 9u);
    // An open spiral that runs into itself, and the same turned into a loop that meets its
    // start: split at the meeting points, not kept or dropped as one curve.
    std::vector<Point> spiral;
    for (int k = 0; k <= 40; ++k) {
        const double t = 2.4 * pi * k / 40, r = 10 - 3 * double(k) / 40;
        spiral.push_back(Point{std::cos(t), std::sin(t)} * r);
    }
    spiral.push_back({9, -1});  // back across the first turn
    const MapPtr right = PlanarMap::induce(Polyline({{0, -20}, {20, -20}, {20, 20}, {0, 20}}, true));
    const Curves s = apply_mask(Polyline(spiral), *right, MaskSide::Inside, KEEP_OUTSIDE);
    Curves se;
    {
        detail::ExactCropScope only_exact;
        se = apply_mask(Polyline(spiral), *right, MaskSide::Inside, KEEP_OUTSIDE);
    }
    EXPECT_EQ(ToSVG(s, 40), ToSVG(se, 40));
    EXPECT_GT(s.curves.size(), 1u);
}
