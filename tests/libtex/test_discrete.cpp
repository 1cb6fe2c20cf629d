// The discrete operator set of seed 004 (libtex/discrete.hpp) and, when the gallery is
// built, the properties that define its figures 1a-1g.
//
// Overlaps and distances of the outputs are checked with Boost.Geometry on all pairs, an
// implementation independent of the R-tree and of the exact tests the operators use.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/geometry.hpp>
#include <cstdio>
#include <fstream>

#include "helpers.hpp"
#include "libtex/discrete.hpp"
#include "libtex/random.hpp"

#ifdef RH_DISCRETE_FIGURES
#include "gallery.hpp"
#include "gallery_discrete.hpp"
#endif

namespace {

using namespace tex::disc;
using tex::BBox;
using tex::Point;
using tex::Region;

namespace bg = boost::geometry;
using BPoint = bg::model::d2::point_xy<double>;
using BPolygon = bg::model::polygon<BPoint, false, false>;  // counter-clockwise, open rings

BPolygon to_bg(const Region& r) {
    BPolygon p;
    for (const auto& q : r.outer()) p.outer().push_back({q.x, q.y});
    for (const auto& h : r.holes()) {
        p.inners().emplace_back();
        for (const auto& q : h) p.inners().back().push_back({q.x, q.y});
    }
    return p;
}

// Smallest distance between two members of the set, over every pair (no index), and
// whether some pair intersects.
struct PairReport {
    double min_distance = std::numeric_limits<double>::infinity();
    std::size_t overlapping_pairs = 0;
};

PairReport all_pairs(const std::vector<Region>& a, const std::vector<Region>& b, bool same_set,
                     double reach) {
    std::vector<BPolygon> pa, pb;
    for (const auto& r : a) pa.push_back(to_bg(r));
    for (const auto& r : b) pb.push_back(to_bg(r));
    PairReport rep;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = same_set ? i + 1 : 0; j < b.size(); ++j) {
            if (!a[i].bbox().expanded(reach).intersects(b[j].bbox())) continue;
            if (bg::intersects(pa[i], pb[j])) {
                ++rep.overlapping_pairs;
                rep.min_distance = 0;
            } else {
                rep.min_distance = std::min(rep.min_distance, double(bg::distance(pa[i], pb[j])));
            }
        }
    return rep;
}

Region square(double x, double y, double s) {
    return Region::rectangle(x, y, x + s, y + s);
}

// ---- Operators as values ----

TEST(DiscreteOperators, CountUpToIsTrueNTimes) {
    const Condition c = CountUpTo(3);
    EXPECT_TRUE(c());
    EXPECT_TRUE(c());
    EXPECT_TRUE(c());
    EXPECT_FALSE(c());
    EXPECT_FALSE(c());
}

TEST(DiscreteOperators, NotAndComposeCombineCallables) {
    const RegionSet s({square(0, 0, 10)});
    const PointCheck inside = Overlap(s);
    const PointCheck outside = Not(Overlap(s));
    const PointCheck left_half = And(Overlap(s), [](const Point& p) { return p.x < 5; });
    EXPECT_TRUE(inside(Point{5, 5}));
    EXPECT_FALSE(outside(Point{5, 5}));
    EXPECT_TRUE(left_half(Point{2, 5}));
    EXPECT_FALSE(left_half(Point{7, 5}));
    // Check of a point = Overlap ∘ a shaping; a generator composed stays a generator.
    const std::function<bool(const Point&)> hits =
        Compose(Overlap(s), Translation(BuiltinCircle(1)));
    EXPECT_TRUE(hits(Point{10.5, 5}));
    EXPECT_FALSE(hits(Point{12, 5}));
    const std::function<Region()> big = Compose(Scale(2.0), Const(square(0, 0, 1)));
    EXPECT_NEAR(big().area(), 4, 1e-12);
}

TEST(DiscreteOperators, RandomOperatorsRepeatWithTheSeedAndDifferFromEachOther) {
    auto draw = [] {
        tex::StreamScope fresh(0);
        const RealGen a = RandomR(2, 3), b = RandomR(2, 3);
        const Pinning p = RandomPinning(square(0, 0, 10));
        return std::vector<double>{a(), a(), b(), p().x, p().y};
    };
    const auto one = draw(), two = draw();
    EXPECT_EQ(one, two);
    EXPECT_NE(one[0], one[2]) << "two RandomR draw from different streams";
    for (int i = 0; i < 3; ++i) {
        EXPECT_GE(one[i], 2);
        EXPECT_LT(one[i], 3);
    }
    const std::uint64_t seed = tex::GetSeed();
    tex::SetSeed(seed + 1);
    const auto other = draw();
    tex::SetSeed(seed);
    EXPECT_NE(one, other);
}

TEST(DiscreteOperators, RandomPinningStaysInTheRegionAndFollowsTheDensity) {
    const Region ring({{0, 0}, {100, 0}, {100, 100}, {0, 100}},
                      {{{25, 25}, {75, 25}, {75, 75}, {25, 75}}});
    const Pinning p =
        RandomPinning(ring, tex::Field([](const Point& q) { return q.x < 50 ? 1.0 : 0.0; }));
    for (int i = 0; i < 2000; ++i) {
        const Point q = p();
        ASSERT_TRUE(ring.contains(q));
        ASSERT_LT(q.x, 50);
    }
}

TEST(DiscreteOperators, RandomPinningInPiecesStaysInThemAndWeighsThemByArea) {
    // Two far apart squares, the second with four times the area of the first, and a density
    // that empties the right half of the big one.
    const std::vector<Region> pieces = {square(0, 0, 10), square(1000, 1000, 20)};
    const Pinning p = RandomPinning(
        pieces, tex::Field([](const Point& q) { return q.x > 1010 ? 0.0 : 1.0; }));
    int small = 0, big = 0;
    for (int i = 0; i < 4000; ++i) {
        const Point q = p();
        const bool in_small = pieces[0].contains(q), in_big = pieces[1].contains(q);
        ASSERT_TRUE(in_small || in_big) << q.x << "," << q.y;
        ASSERT_LE(q.x, 1010);
        (in_small ? small : big)++;
    }
    // Half of the big square is left, twice the small one's area: about 2 points in it for 1.
    EXPECT_NEAR(double(big) / small, 2.0, 0.25);
    // Same streams, same points.
    auto draw = [&] {
        tex::StreamScope fresh(0);
        const Pinning q = RandomPinning(pieces, tex::Field(1.0));
        return std::vector<Point>{q(), q(), q()};
    };
    EXPECT_EQ(draw(), draw());
}

TEST(DiscreteOperators, RegionSetIndexFindsWhatAScanFinds) {
    // Members of very different sizes (the grid keeps the common ones, the tree the long
    // ones), added one by one, in bulk and past the extent of the last rebuild: every query
    // must find exactly the members whose boxes meet its box.
    tex::KeyedRng rng(42);
    std::vector<Region> all;
    RegionSet set;
    auto some = [&](int n, double spread, double size) {
        std::vector<Region> v;
        for (int i = 0; i < n; ++i) {
            const double x = rng.uniform(-spread, spread), y = rng.uniform(-spread, spread);
            const double w = size * rng.uniform(0.2, 1.0), h = size * rng.uniform(0.2, 1.0);
            v.push_back(Region::rectangle(x, y, x + w, y + h));
        }
        return v;
    };
    for (const Region& r : some(50, 100, 2)) set.add(r), all.push_back(r);  // below the grid
    std::vector<Region> bulk = some(500, 100, 2);
    for (const Region& r : some(20, 100, 150)) bulk.push_back(r);  // long members
    all.insert(all.end(), bulk.begin(), bulk.end());
    set.add(bulk);
    for (const Region& r : some(700, 400, 3)) set.add(r), all.push_back(r);  // grows past the extent
    ASSERT_EQ(set.size(), all.size());
    for (int q = 0; q < 300; ++q) {
        const double x = rng.uniform(-450, 450), y = rng.uniform(-450, 450), s = rng.uniform(0, 30);
        const BBox box{x, y, x + s, y + s};
        std::vector<std::size_t> scan;
        for (std::size_t i = 0; i < all.size(); ++i)
            if (all[i].bbox().intersects(box)) scan.push_back(i);
        ASSERT_EQ(set.near(box), scan) << "query " << q;
        EXPECT_EQ(set.any_near(box, [](std::size_t) { return true; }), !scan.empty());
    }
    // A box over everything finds everything.
    EXPECT_EQ(set.near(BBox{-1e6, -1e6, 1e6, 1e6}).size(), all.size());
}

TEST(DiscreteOperators, RegularPinningCountsAndPositions) {
    const auto grid = RegularPinning(Image(500, 500), 5, 5);
    ASSERT_EQ(grid.size(), 25u);
    EXPECT_EQ(grid.front(), (Point{50, 50}));
    EXPECT_EQ(grid.back(), (Point{450, 450}));
    const auto in_circle = RegularPinning(BuiltinCircle(10, 64), 10, 10);
    EXPECT_LT(in_circle.size(), 100u);
    EXPECT_GT(in_circle.size(), 60u);  // about pi/4 of the grid
    // Along a 100-long segment every 10: 11 points; a closed 400 perimeter: 40.
    EXPECT_EQ(RegularPinning1D(Polyline{{{0, 0}, {60, 0}, {100, 0}}, false}, 0.1).size(), 11u);
    const auto around = RegularPinning1D(Contour(square(0, 0, 100)), 0.1);
    EXPECT_EQ(around.size(), 40u);
    for (std::size_t i = 1; i < around.size(); ++i)
        EXPECT_NEAR(tex::distance(around[i - 1], around[i]), 10, 1e-9) << i;
}

TEST(DiscreteOperators, CentroidAndTransformations) {
    const Region holed({{0, 0}, {10, 0}, {10, 10}, {0, 10}},
                       {{{5, 0.5}, {9.5, 0.5}, {9.5, 9.5}, {5, 9.5}}});
    const Point c = Centroid(holed);
    EXPECT_LT(c.x, 5);  // the hole on the right pulls the centroid left
    EXPECT_NEAR(c.y, 5, 1e-12);
    const Region moved = Translation(holed, Point{100, 200});
    EXPECT_NEAR(Centroid(moved).x, 100, 1e-9);
    EXPECT_NEAR(Centroid(moved).y, 200, 1e-9);
    const Region turned = Rotation(holed, 1.0);
    EXPECT_NEAR(turned.area(), holed.area(), 1e-9);
    EXPECT_NEAR(Centroid(turned).x, c.x, 1e-9);
    EXPECT_NEAR(Scale(holed, 3).area(), 9 * holed.area(), 1e-9);
    const Point v =
        Rotation(Point{1, 0}, tex::pi / 2);  // a point is a vector: turned about the origin
    EXPECT_NEAR(v.x, 0, 1e-15);
    EXPECT_NEAR(v.y, 1, 1e-15);
    EXPECT_EQ(Translation(Point{1, 2}, Point{3, 4}), (Point{3, 4}));
}

// Rotation, Scale and Translation take a generator for the element or for their parameter
// alike: the result is a generator drawing both anew at every call, element first, giving
// what the full form gives on the drawn values.
TEST(DiscreteOperators, TransformationsTakeAShapeOrAGeneratorAlike) {
    const Region shape({{0, 0}, {4, 0}, {4, 1}, {0, 1}});
    auto values = [](std::vector<double> v) {
        auto next = std::make_shared<std::size_t>(0);
        return RealGen([v, next] { return v.at((*next)++); });
    };
    auto same = [](const Region& a, const Region& b) {
        ASSERT_EQ(a.outer().size(), b.outer().size());
        for (std::size_t i = 0; i < a.outer().size(); ++i) {
            EXPECT_DOUBLE_EQ(a.outer()[i].x, b.outer()[i].x);
            EXPECT_DOUBLE_EQ(a.outer()[i].y, b.outer()[i].y);
        }
    };
    const RegionGen turned = Rotation(shape, values({0.3, 1.2}));
    same(turned(), Rotation(shape, 0.3));
    same(turned(), Rotation(shape, 1.2));
    const RegionGen grown = Scale(shape, values({2.0, 0.5}));
    same(grown(), Scale(shape, 2.0));
    same(grown(), Scale(shape, 0.5));
    const RegionGen placed = Translation(shape, Sequence({Point{10, 20}, Point{-5, 3}}));
    same(placed(), Translation(shape, Point{10, 20}));
    same(placed(), Translation(shape, Point{-5, 3}));
    // A generator as the element: each call takes its next region; with two generators the
    // element is drawn before the parameter.
    const Region other = Scale(shape, 3.0);
    auto shapes = [&](std::vector<Region> v) {
        auto next = std::make_shared<std::size_t>(0);
        return RegionGen([v, next] { return v.at((*next)++); });
    };
    const RegionGen both = Rotation(shapes({shape, other}), values({0.7, 0.1}));
    same(both(), Rotation(shape, 0.7));
    same(both(), Rotation(other, 0.1));
    same(Scale(shapes({other}), 0.25)(), Scale(other, 0.25));
    same(Translation(shapes({other}), Point{1, 1})(), Translation(other, Point{1, 1}));
    // The seed's spelling of a randomly turned shape: the same draws as the composition.
    // (SetSeed restarts the numbering of streams, so both RandomR get the same stream.)
    tex::SetSeed(0);
    const RegionGen a = Rotation(shape, RandomR(0, tex::pi));
    tex::SetSeed(0);
    const RegionGen b = Compose(Rotation(RandomR(0, tex::pi)), Const(shape));
    same(a(), b());
    same(a(), b());
    // Bad parameters are refused when the generator is made or when it draws them.
    EXPECT_TEX_ERROR(Rotation(RegionGen(Const(shape)), std::nan("")), "Rotation", "finite");
    EXPECT_TEX_ERROR(Scale(RegionGen(Const(shape)), -1.0), "Scale", "positive");
    EXPECT_TEX_ERROR(Scale(shape, values({-2.0}))(), "Scale", "positive");
    EXPECT_TEX_ERROR(Rotation(RegionGen(), 1.0), "Rotation", "no element generator");
}

TEST(DiscreteOperators, OverlapIsClosedAndKnowsHoles) {
    const Region frame({{0, 0}, {30, 0}, {30, 30}, {0, 30}},
                       {{{10, 10}, {20, 10}, {20, 20}, {10, 20}}});
    const RegionSet s({frame});
    EXPECT_TRUE(Overlap(s, square(30, 0, 5))) << "touching along an edge counts";
    EXPECT_TRUE(Overlap(s, square(30, 30, 5))) << "touching at a corner counts";
    EXPECT_FALSE(Overlap(s, square(30.000001, 0, 5)));
    EXPECT_FALSE(Overlap(s, square(12, 12, 5))) << "inside the hole";
    EXPECT_TRUE(Overlap(s, square(2, 2, 5))) << "inside the region";
    EXPECT_TRUE(Overlap(s, square(-10, -10, 100))) << "the element contains the region";
    EXPECT_TRUE(Overlap(s, Point{5, 5}));
    EXPECT_FALSE(Overlap(s, Point{15, 15}));
    EXPECT_TRUE(Overlap(s, Polyline{{{15, 15}, {25, 15}}, false}));
    EXPECT_FALSE(Overlap(s, Polyline{{{12, 15}, {18, 15}}, false}));
}

TEST(DiscreteOperators, DistanceAndMinimalDistance) {
    EXPECT_NEAR(Distance(square(0, 0, 1), square(4, 0, 1)), 3, 1e-15);
    EXPECT_NEAR(Distance(square(0, 0, 1), square(4, 5, 1)), 5, 1e-15);
    EXPECT_EQ(Distance(square(0, 0, 10), square(2, 2, 1)), 0);
    EXPECT_NEAR(Distance(Point{0, 3}, Polyline{{{-5, 0}, {5, 0}}, false}), 3, 1e-15);
    const RegionSet s({square(0, 0, 1)});
    EXPECT_TRUE(MinimalDistance(s, square(2.5, 0, 1), 2));
    EXPECT_FALSE(MinimalDistance(s, square(3.5, 0, 1), 2));
    EXPECT_TRUE(MinimalDistance(s, Point{0.5, 0.5}, 0.1));
}

TEST(DiscreteOperators, InterpolationPassesThroughThePoints) {
    const std::vector<Point> pts = {{0, 0}, {10, 5}, {20, -5}, {30, 0}};
    const Polyline c = Interpolation(pts, 4);
    EXPECT_EQ(c.points.size(), 13u);
    for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(c.points[4 * i], pts[i]);
}

TEST(DiscreteOperators, ApplyThicknessGivesTheWidth) {
    const Region r =
        ApplyThickness(Polyline{{{0, 0}, {50, 0}, {100, 0}}, false}, [](double) { return 4.0; });
    EXPECT_NEAR(r.area(), 400, 1e-9);
    const Region tapered = ApplyThickness(Polyline{{{0, 0}, {50, 0}, {100, 0}}, false},
                                          [](double t) { return t < 0.5 ? 0.0 : 2.0; });
    // The width is taken at the curve's points (t = 0, 0.5, 1: widths 0, 2, 2) and runs
    // straight between them: a triangle 50 long and 2 high, then a 50 x 2 rectangle.
    EXPECT_NEAR(tapered.area(), 50 * 2 / 2.0 + 50 * 2, 1e-9);
    EXPECT_NEAR(tapered.bbox().ymax, 1, 1e-12);
    EXPECT_NEAR(tapered.bbox().ymin, -1, 1e-12);
    // Around a closed curve, a ring: 1 on each side of the square 10 x 10, mitred at the
    // corners, so the 12 x 12 square less the 8 x 8 one, whichever way the curve runs (the
    // square's contour runs counter-clockwise; reversed, clockwise).
    const Polyline ccw = Contour(square(0, 0, 10));
    Polyline cw = ccw;
    std::reverse(cw.points.begin(), cw.points.end());
    for (const Polyline* c : {&ccw, static_cast<const Polyline*>(&cw)}) {
        SCOPED_TRACE(c == &cw ? "clockwise" : "counter-clockwise");
        const Region annulus = ApplyThickness(*c, [](double) { return 2.0; });
        ASSERT_EQ(annulus.holes().size(), 1u);
        EXPECT_NEAR(annulus.area(), 12 * 12 - 8 * 8, 1e-9);
        EXPECT_NEAR(annulus.bbox().xmin, -1, 1e-12);
        EXPECT_NEAR(annulus.bbox().xmax, 11, 1e-12);
    }
}

TEST(DiscreteOperators, ReadPGMAndImage) {
    const std::string path = ::testing::TempDir() + "rh_disc_test.pgm";
    std::ofstream(path) << "P2\n# a comment\n3 2\n255\n0 128 255\n255 255 0\n";
    const tex::GridSamples g = ReadPGM(path);
    ASSERT_EQ(g.width, 3);
    ASSERT_EQ(g.height, 2);
    EXPECT_FLOAT_EQ((*g.values)[2], 1.0f);
    const Region frame = Image(g);
    EXPECT_EQ(frame.bbox().xmax, 3);
    EXPECT_EQ(frame.bbox().ymax, 2);
    // The top-left pixel (black) is at y in [1, 2].
    EXPECT_NEAR(tex::nearest_grid(g.values->data(), g.width, g.height, g.transform, {0.5, 1.5}), 0,
                1e-7);
    std::remove(path.c_str());
    const tex::GridSamples b = ParsePGM(std::string("P5\n2 1\n65535\n\x00\x00\xff\xff", 17));
    ASSERT_EQ(b.width, 2);
    EXPECT_FLOAT_EQ((*b.values)[0], 0.0f);
    EXPECT_FLOAT_EQ((*b.values)[1], 1.0f);
}

// ---- Programs ----

TEST(DiscretePrograms, GreedyDistributionNeverOverlaps) {
    tex::StreamScope fresh(0);
    RegionSet hatches;
    const long long thrown = greedy_distribution(
        hatches, CountUpTo(3000), RandomPinning(Image(500, 500)),
        Translation(Compose(Rotation(RandomR(0, tex::pi)), Const(BuiltinHatch()))),
        Not(Overlap(hatches)));
    EXPECT_EQ(thrown, 3000);
    EXPECT_GT(hatches.size(), 300u);
    EXPECT_LT(hatches.size(), 3000u);
    const PairReport rep = all_pairs(hatches.regions(), hatches.regions(), true, 0);
    EXPECT_EQ(rep.overlapping_pairs, 0u);
}

TEST(DiscretePrograms, MinimalDistanceKeepsTheGap) {
    tex::StreamScope fresh(0);
    RegionSet dots;
    greedy_distribution(dots, CountUpTo(2000), RandomPinning(Image(400, 400)),
                        Translation(BuiltinCircle(4, 12)), Not(MinimalDistance(dots, 6)));
    EXPECT_GT(dots.size(), 200u);
    const PairReport rep = all_pairs(dots.regions(), dots.regions(), true, 6);
    EXPECT_EQ(rep.overlapping_pairs, 0u);
    EXPECT_GE(rep.min_distance, 6 - 1e-9);
}

TEST(DiscretePrograms, VoronoiCellsTileTheDomainAndHoldTheirRegions) {
    tex::StreamScope fresh(0);
    RegionSet circles;
    greedy_distribution(circles, CountUpTo(80), RandomPinning(Image(600, 400)),
                        Translation(BuiltinCircle(15, 20)), Not(Overlap(circles)));
    const BBox domain{0, 0, 600, 400};
    const std::vector<Region> cells = VoronoiCells(circles.regions(), domain);
    ASSERT_EQ(cells.size(), circles.size());
    double total = 0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        total += cells[i].area();
        for (const auto& p : circles[i].outer()) {
            if (!domain.contains(p)) continue;
            EXPECT_TRUE(cells[i].contains(p)) << "region " << i << " sticks out of its cell";
        }
    }
    EXPECT_NEAR(total, 600 * 400, 1e-6 * 600 * 400);
    // Every point of the domain lies in exactly one cell, nearest (up to the sampling) to its
    // region.
    tex::KeyedRng rng(7);
    for (int k = 0; k < 400; ++k) {
        const Point p{rng.uniform(0, 600), rng.uniform(0, 400)};
        int owner = -1, count = 0;
        for (std::size_t i = 0; i < cells.size(); ++i)
            if (cells[i].contains(p)) owner = int(i), ++count;
        ASSERT_EQ(count, 1) << p.x << " " << p.y;
        double nearest = 1e300;
        for (const auto& c : circles.regions()) nearest = std::min(nearest, Distance(p, c));
        EXPECT_LE(Distance(p, circles[std::size_t(owner)]), nearest + 3.0);
    }
    // Parallel merge: the same cells with one or two threads.
    const unsigned saved = tex::GetThreads();
    tex::SetThreads(1);
    const std::string one = tex::ToSVG(ToCurves(VoronoiCells(circles.regions(), domain)), 600);
    tex::SetThreads(2);
    const std::string two = tex::ToSVG(ToCurves(VoronoiCells(circles.regions(), domain)), 600);
    tex::SetThreads(saved);
    EXPECT_EQ(one, two);
}

TEST(DiscretePrograms, RelaxationSpreadsTheCircles) {
    tex::StreamScope fresh(0);
    RegionSet circles, relaxed;
    greedy_distribution(circles, CountUpTo(60), RandomPinning(Image(500, 500)),
                        Translation(BuiltinCircle(10, 16)), Not(Overlap(circles)));
    relaxation(circles, relaxed, CountUpTo(10), VoronoiCells(BBox{0, 0, 500, 500}),
               [](const Region& r) { return Centroid(r); });
    ASSERT_EQ(relaxed.size(), circles.size());
    EXPECT_NEAR(relaxed[0].area(), circles[0].area(), 1e-9);
    auto closest = [](const RegionSet& s) {
        return all_pairs(s.regions(), s.regions(), true, 1e9).min_distance;
    };
    EXPECT_GT(closest(relaxed), closest(circles)) << "Lloyd steps push the closest pair apart";
}

TEST(DiscretePrograms, StreamLinesFollowTheField) {
    // Around a single circle the tangent field is circular: a stream line stays on a circle.
    const RegionSet one({BuiltinCircle(50, 256)});
    const FlowField flow = TangentFlowField(one, 1.0);
    const Polyline line = trace_stream(
        Point{80, 0}, flow, [](const Point&) { return true; }, 200);
    ASSERT_GT(line.points.size(), 150u);
    for (const auto& p : line.points) EXPECT_NEAR(tex::norm(p), 80, 2.0);
    // Each step is along the field where it starts, and of its length.
    for (std::size_t i = 1; i < line.points.size(); ++i) {
        const Point step = line.points[i] - line.points[i - 1];
        const Point f = flow(line.points[i - 1]);
        EXPECT_NEAR(std::fabs(tex::cross(step, f)), 0, 1e-9);
        EXPECT_NEAR(tex::norm(step), 1.0, 1e-9);
    }
    // The check stops the line: nothing beyond x < 0.
    const Polyline half = trace_stream(
        Point{80, 0}, flow, [](const Point& p) { return p.x >= 0; }, 1000);
    for (const auto& p : half.points) EXPECT_GE(p.x, 0);
    EXPECT_LT(half.points.size(), 300u);
}

TEST(DiscretePrograms, AStreamLineNeverCrossesItself) {
    // A field whose stream lines are closed circles (the radial term pulls back to r = 80):
    // after one turn the line would run over its start, so it stops there.
    const FlowField orbit = [](const Point& p) {
        const double r = tex::norm(p);
        return Point{-p.y / r, p.x / r} + p * ((80 - r) / r);
    };
    const Polyline line = trace_stream(
        Point{80, 0}, orbit, [](const Point&) { return true; }, 5000);
    double length = 0;
    for (std::size_t i = 1; i < line.points.size(); ++i)
        length += tex::distance(line.points[i - 1], line.points[i]);
    EXPECT_GT(length, 2 * tex::pi * 80 - 10) << "it goes nearly all the way round";
    EXPECT_LT(length, 2 * tex::pi * 80 + 10) << "and no further";
    namespace bg = boost::geometry;
    using Seg = bg::model::segment<BPoint>;
    for (std::size_t i = 0; i + 1 < line.points.size(); ++i)
        for (std::size_t j = i + 2; j + 1 < line.points.size(); ++j) {
            const Seg a{{line.points[i].x, line.points[i].y},
                        {line.points[i + 1].x, line.points[i + 1].y}};
            const Seg b{{line.points[j].x, line.points[j].y},
                        {line.points[j + 1].x, line.points[j + 1].y}};
            ASSERT_FALSE(bg::intersects(a, b)) << i << " " << j;
        }
}

TEST(DiscretePrograms, StreamLinesDoNotCrossEachOther) {
    tex::StreamScope fresh(0);
    RegionSet circles;
    for (const Point c : {Point{100, 100}, Point{300, 120}, Point{200, 300}})
        circles.add(Translation(BuiltinCircle(30), c));
    RegionSet lines;
    const Shaping shaping = stream_line(
        TangentFlowField(circles, 2), Not(MinimalDistance(lines, 4)), 150,
        [](double) { return 3.0; }, 10);
    greedy_distribution(lines, CountUpTo(400), RandomPinning(Image(400, 400)), shaping,
                        And(Not(Overlap(circles)), Not(MinimalDistance(lines, 1))));
    EXPECT_GT(lines.size(), 20u);
    const PairReport rep = all_pairs(lines.regions(), lines.regions(), true, 1);
    EXPECT_EQ(rep.overlapping_pairs, 0u);
    EXPECT_GE(rep.min_distance, 1 - 1e-9);
    EXPECT_EQ(all_pairs(lines.regions(), circles.regions(), false, 0).overlapping_pairs, 0u);
}

// ---- Bad input ----

TEST(DiscreteErrors, BadInputNamesTheOperator) {
    EXPECT_TEX_ERROR(RandomPinning(Region()), "RandomPinning", "empty");
    EXPECT_TEX_ERROR(RandomPinning(std::vector<Region>{}, tex::Field(1.0)), "RandomPinning", "no piece");
    EXPECT_TEX_ERROR(RandomPinning(std::vector<Region>{square(0, 0, 1), Region()}, tex::Field(1.0)),
                     "RandomPinning", "empty");
    EXPECT_TEX_ERROR(RegionSet().add(std::vector<Region>{square(0, 0, 1), Region()}), "RegionSet", "empty");
    EXPECT_TEX_ERROR(RegularPinning(Image(10, 10), 0, 3), "RegularPinning", "nx, ny");
    EXPECT_TEX_ERROR(RegularPinning1D(Polyline{{{0, 0}, {1, 0}}, false}, -1), "RegularPinning1D",
                     "density");
    EXPECT_TEX_ERROR(RegularPinning1D(Polyline{}, 1), "RegularPinning1D", "no point");
    EXPECT_TEX_ERROR(VoronoiCells({square(0, 0, 1)}, BBox{0, 0, 10, 10}), "VoronoiCells",
                     "two regions");
    EXPECT_TEX_ERROR(VoronoiCells({square(0, 0, 1), square(3, 3, 1)}, BBox{}), "VoronoiCells",
                     "domain");
    EXPECT_TEX_ERROR(ApplyThickness(Polyline{{{1, 1}, {1, 1}}, false}, [](double) { return 1.0; }),
                     "ApplyThickness", "two distinct");
    EXPECT_TEX_ERROR(ApplyThickness(Polyline{{{0, 0}, {1, 1}}, false}, [](double) { return -1.0; }),
                     "ApplyThickness", ">= 0");
    EXPECT_TEX_ERROR(Scale(square(0, 0, 1), 0.0), "Scale", "positive");
    EXPECT_TEX_ERROR(Rotation(square(0, 0, 1), std::nan("")), "Rotation", "finite");
    EXPECT_TEX_ERROR(CountUpTo(-1), "CountUpTo", ">= 0");
    EXPECT_TEX_ERROR(RandomR(2, 1), "RandomR", "a <= b");
    EXPECT_TEX_ERROR(Sequence({Point{0, 0}})(); Sequence({})(), "Sequence", "were used");
    EXPECT_TEX_ERROR(ReadPGM("/nonexistent/x.pgm"), "ReadPGM", "cannot open");
    EXPECT_TEX_ERROR(ParsePGM("P6\n1 1\n255\n\x01\x02\x03", "a.ppm"), "a.ppm", "not a PGM");
    EXPECT_TEX_ERROR(ParsePGM("P5\n10000 10000\n255\n\x01", "big.pgm"), "big.pgm", "truncated");
    EXPECT_TEX_ERROR(ParsePGM("P2\n2 1\n9\n3 12\n", "over.pgm"), "over.pgm", "exceeds the maximum");
    EXPECT_TEX_ERROR(ParsePGM("P5\n0 3\n255\n", "zero.pgm"), "zero.pgm", "bad size");
    EXPECT_TEX_ERROR(ParsePGM("P2\n# only a comment", "short.pgm"), "short.pgm",
                     "malformed header");
    EXPECT_TEX_ERROR(TangentFlowField(RegionSet(), 1), "TangentFlowField", "at least one");
    EXPECT_TEX_ERROR(TangentFlowField(RegionSet({square(0, 0, 1)}), 0), "TangentFlowField", "step");
    EXPECT_TEX_ERROR(stream_line(
                         FlowField([](const Point&) {
                             return Point{1, 0};
                         }),
                         [](const Point&) { return true; }, -1, [](double) { return 1.0; }),
                     "stream_line", "length");
    EXPECT_TEX_ERROR(MinimalDistance(RegionSet(), -2), "MinimalDistance", ">= 0");
    EXPECT_TEX_ERROR(Image(0, 10), "Image", "positive");
    EXPECT_TEX_ERROR(BuiltinCircle(5, 2), "BuiltinCircle", "3 segments");
    RegionSet out;
    EXPECT_TEX_ERROR(greedy_distribution(out, CountUpTo(1), nullptr, Translation(BuiltinHatch()),
                                         Not(Overlap(out))),
                     "greedy_distribution", "must all be given");
    const RegionSet one({square(0, 0, 1)});
    const Reshaping lose_all = [](const std::vector<Region>&) { return std::vector<Region>{}; };
    EXPECT_TEX_ERROR(
        relaxation(one, out, CountUpTo(1), lose_all, [](const Region& r) { return Centroid(r); }),
        "relaxation", "returned 0 shapes");
}

#ifdef RH_DISCRETE_FIGURES
// ---- Figures 1a-1g: the properties that define them ----
namespace fig = gallery::discrete;

void expect_apart(const RegionSet& a, const RegionSet& b, bool same, double gap, const char* what) {
    const PairReport rep = all_pairs(a.regions(), b.regions(), same, gap);
    EXPECT_EQ(rep.overlapping_pairs, 0u) << what;
    if (gap > 0) EXPECT_GE(rep.min_distance, gap - 1e-9) << what;
}

// A set of at least `at_least` elements, no two of them touching.
void expect_layer(const RegionSet& s, std::size_t at_least, const char* what) {
    EXPECT_GE(s.size(), at_least) << what;
    expect_apart(s, s, true, 0, what);
}

TEST(DiscreteFigures, Fig1aHatchesDoNotOverlap) {
    tex::StreamScope fresh(0);
    const auto f = fig::fig_1a();
    expect_layer(f.main, 500, "hatches");
    EXPECT_LE(f.main.size(), 1000u) << "one hatch at most per dart";
}

TEST(DiscreteFigures, Fig1bHatchesTouchTheRectangles) {
    tex::StreamScope fresh(0);
    const auto f = fig::fig_1b();
    EXPECT_EQ(f.other.size(), 25u);
    expect_layer(f.other, 25, "rectangles");
    expect_layer(f.main, 100, "hatches");
    for (const auto& h : f.main.regions()) ASSERT_TRUE(Overlap(f.other, h));
}

TEST(DiscreteFigures, Fig1cOrthogonalHatchesAvoidBothSets) {
    tex::StreamScope fresh(0);
    const auto f = fig::fig_1c();
    expect_layer(f.other, 300, "orthogonal hatches");
    expect_apart(f.main, f.other, false, 0, "hatches against orthogonal hatches");
    for (const auto& h : f.other.regions()) ASSERT_GT(h.bbox().height(), h.bbox().width());
}

TEST(DiscreteFigures, Fig1dUserShapesDoNotOverlap) {
    tex::StreamScope fresh(0);
    const auto f = fig::fig_1d(gallery::default_elements_dir());
    expect_layer(f.main, 300, "leaves");
}

TEST(DiscreteFigures, Fig1eScaledCellsAreApartAndOnePerCircle) {
    tex::StreamScope fresh(0);
    const auto c = fig::circle_distribution();
    tex::StreamScope again(0);
    const auto f = fig::fig_1e();
    EXPECT_EQ(f.main.size(), c.main.size());
    expect_apart(f.main, f.main, true, 0, "scaled cells");
}

TEST(DiscreteFigures, Fig1fStreamLinesKeepTheirGap) {
    tex::StreamScope fresh(0);
    const auto f = fig::fig_1f();
    EXPECT_GT(f.main.size(), 100u);
    expect_apart(f.main, f.main, true, fig::kStreamGap, "stream lines");
    expect_apart(f.main, f.other, false, 0, "stream lines against circles");
}

TEST(DiscreteFigures, Fig1gBothSetsKeepTheirGap) {
    tex::StreamScope fresh(0);
    const auto f = fig::fig_1g();
    EXPECT_GT(f.main.size(), 100u);
    EXPECT_GT(f.other.size(), 100u);
    expect_apart(f.main, f.main, true, fig::kStreamGap, "first stream lines");
    expect_apart(f.other, f.other, true, fig::kStreamGap, "second stream lines");
}
#endif

}  // namespace
