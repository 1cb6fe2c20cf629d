// Control fields (thesis 5.3): builders, grids, face-wise constants, compositions,
// controlled arrangements and mappers, and the local-control check.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <random>
#include <set>

#include "helpers.hpp"

using namespace tex;

namespace {

const double kNaN = std::nan("");

struct ThreadsGuard {
    unsigned saved = GetThreads();
    ~ThreadsGuard() { SetThreads(saved); }
};

GridSamples grid(int w, int h, std::array<double, 6> t, std::vector<float> v) {
    return {w, h, t, std::make_shared<const std::vector<float>>(std::move(v))};
}

// The face of a map whose region has this area.
int face_with_area(const MapPtr& m, double area) {
    for (std::size_t i = 0; i < m->faces().size(); ++i)
        if (!m->faces()[i].unbounded && std::abs(ToRegion(Face(m, int(i))).area() - area) < 1e-9) return int(i);
    return -1;
}

}  // namespace

TEST(Field, ConstantFunctionAndDomain) {
    EXPECT_TRUE(std::isnan(Field()({0, 0})));
    EXPECT_FALSE(Field().has_value({0, 0}));
    EXPECT_EQ(Field(2.5)({7, 8}), 2.5);
    EXPECT_EQ(ConstantField(-1)({1e9, 0}), -1);
    EXPECT_FALSE(ConstantField(1).domain());
    const Field lambda = [](const Point& p) { return p.x + 2 * p.y; };  // implicit, as carto assigns them
    EXPECT_EQ(lambda({1, 2}), 5);
    const Field f = FunctionField([](const Point& p) { return p.x; }, BBox{0, 0, 10, 10});
    EXPECT_EQ(f({3, 4}), 3);
    EXPECT_EQ(f({10, 10}), 10);  // the domain's border belongs to it
    EXPECT_TRUE(std::isnan(f({11, 4})));
    EXPECT_TRUE(f.has_value({0, 0}));
    EXPECT_FALSE(f.has_value({-1, 0}));
    ASSERT_TRUE(f.domain());
    EXPECT_EQ(f.domain()->xmax, 10);
    EXPECT_STREQ(Field(1.0).kind(), "constant");
    EXPECT_STREQ(Field().kind(), "none");
}

TEST(Field, GridIsBilinearOverCellCentres) {
    // 2 x 2 cells of 10, top-left corner (0, 20): centres (5,15)=1 (15,15)=2 (5,5)=3 (15,5)=NoData.
    const Field g = GridField(grid(2, 2, {0, 10, 0, 20, 0, -10}, {1, 2, 3, NAN}));
    EXPECT_EQ(g({5, 15}), 1);
    EXPECT_EQ(g({15, 15}), 2);
    EXPECT_EQ(g({5, 5}), 3);
    // Halfway between the four centres: the NoData one left out, weights 1/4 renormalised.
    EXPECT_DOUBLE_EQ(g({10, 10}), (1 + 2 + 3) / 3.0);
    // (7.5, 12.5): weights 9/16, 3/16, 3/16 (and 1/16 on NoData) -> 1.5 / 0.9375.
    EXPECT_DOUBLE_EQ(g({7.5, 12.5}), 1.6);
    // Between 1 and 2 only (no NoData involved).
    EXPECT_DOUBLE_EQ(g({7.5, 15}), 1.25);
    // Outside the grid.
    EXPECT_TRUE(std::isnan(g({-0.1, 10})));
    EXPECT_TRUE(std::isnan(g({10, 20.5})));
    EXPECT_FALSE(std::isnan(g({0, 0})));  // the grid's corner is inside
    ASSERT_TRUE(g.domain());
    EXPECT_EQ(g.domain()->xmin, 0);
    EXPECT_EQ(g.domain()->ymax, 20);
    EXPECT_STREQ(g.kind(), "grid");
}

TEST(Field, GridSamplesAreTheWeightedMeanToTheBitEverywhere) {
    // The sampler's common case (four valid cells inside the grid) is computed apart from
    // its edges and NoData: both must give the renormalised weighted mean, summed in the
    // order of the cells (top-left, top-right, bottom-left, bottom-right), to the bit.
    const int w = 7, h = 5;
    std::vector<float> v(std::size_t(w) * h);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = float(std::sin(0.7 * double(i)) * 1000.0 + 0.1 * double(i));
    v[std::size_t(2) * w + 3] = NAN;
    v[std::size_t(4) * w + 6] = NAN;
    auto expected = [&](const Point& p) {
        const double fx = p.x - 0.5, fy = p.y - 0.5;
        const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
        const double tx = fx - x0, ty = fy - y0;
        double sum = 0, wsum = 0;
        for (int dy = 0; dy <= 1; ++dy)
            for (int dx = 0; dx <= 1; ++dx) {
                const int cx = std::clamp(x0 + dx, 0, w - 1), cy = std::clamp(y0 + dy, 0, h - 1);
                const float val = v[std::size_t(cy) * w + cx];
                if (std::isnan(val)) continue;
                const double wgt = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty);
                sum += wgt * val;
                wsum += wgt;
            }
        return wsum > 1e-12 ? sum / wsum : nearest_grid_pixel(v.data(), w, h, p);
    };
    auto same = [](double a, double b) { return std::isnan(b) ? std::isnan(a) : std::memcmp(&a, &b, sizeof a) == 0; };
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> ux(0.0, double(w)), uy(0.0, double(h));
    int inner = 0;
    for (int k = 0; k < 20000; ++k) {
        const Point p{ux(rng), uy(rng)};
        const double got = sample_grid_pixel(v.data(), w, h, p), want = expected(p);
        ASSERT_TRUE(same(got, want))
            << p.x << " " << p.y << ": " << got << " against " << want;
        inner += p.x > 1 && p.x < w - 1 && p.y > 1 && p.y < h - 1;
    }
    EXPECT_GT(inner, 5000);  // the common case was sampled
    // The grid's own edges and corners.
    for (const Point& p : {Point{0, 0}, Point{double(w), double(h)}, Point{0.25, 2.5}, Point{3.5, double(h)}})
        EXPECT_TRUE(same(sample_grid_pixel(v.data(), w, h, p), expected(p))) << p.x << " " << p.y;
}

TEST(Field, GridWithOnlyNoDataAroundIsNaN) {
    const Field g = GridField(grid(3, 1, {0, 1, 0, 1, 0, -1}, {NAN, NAN, 5}));
    EXPECT_TRUE(std::isnan(g({0.5, 0.5})));
    EXPECT_EQ(g({2.5, 0.5}), 5);
    EXPECT_EQ(g({1.6, 0.5}), 5);  // the one valid neighbour alone
}

TEST(Field, RotatedGridInvertsItsTransform) {
    // Columns run up y, rows along x: the grid of `north` turned a quarter and mirrored.
    const std::vector<float> v = {1, 2, 3, 4, 5, 6};  // 3 columns, 2 rows
    const Field turned = GridField(grid(3, 2, {100, 0, 10, 50, 10, 0}, v));
    const Field plain = GridField(grid(3, 2, {100, 10, 0, 50, 0, 10}, v));
    for (double c : {0.2, 0.5, 1.3, 2.0, 2.9})
        for (double r : {0.1, 0.5, 1.0, 1.7}) {
            // Pixel (c, r) is (100 + 10 r, 50 + 10 c) in the turned grid, (100 + 10 c, 50 + 10 r) in the plain one.
            EXPECT_NEAR(turned({100 + 10 * r, 50 + 10 * c}), plain({100 + 10 * c, 50 + 10 * r}), 1e-12) << c << " " << r;
        }
    EXPECT_TRUE(std::isnan(turned({99, 60})));
    // A general rotation: the cell centres keep their values.
    const double a = 0.3, cs = std::cos(a), sn = std::sin(a);
    const Field rot = GridField(grid(3, 2, {7, 2 * cs, -2 * sn, -4, 2 * sn, 2 * cs}, v));
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 3; ++c) {
            const Point w{7 + (c + 0.5) * 2 * cs - (r + 0.5) * 2 * sn, -4 + (c + 0.5) * 2 * sn + (r + 0.5) * 2 * cs};
            EXPECT_NEAR(rot(w), v[std::size_t(r) * 3 + c], 1e-9);
        }
}

TEST(Field, GridRefusesBadInput) {
    EXPECT_THROW(GridField(grid(0, 2, {0, 1, 0, 0, 0, -1}, {})), Error);
    EXPECT_THROW(GridField(grid(2, 2, {0, 1, 0, 0, 0, -1}, {1, 2, 3})), Error);
    EXPECT_THROW(GridField(grid(1, 1, {0, 0, 0, 0, 0, -1}, {1})), Error);
}

TEST(Field, FaceFieldLocatesFacesHolesAndBorders) {
    // A 10 x 10 square split at x = 5; a 2 x 2 square inside the left half (a hole of it).
    Curves c = Polyline({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true);
    c.append(Polyline({{5, 0}, {5, 10}}));
    c.append(Polyline({{1, 1}, {3, 1}, {3, 3}, {1, 3}}, true));
    const MapPtr m = PlanarMap::induce(c);
    const int left = face_with_area(m, 46), right = face_with_area(m, 50), inner = face_with_area(m, 4);
    ASSERT_GE(left, 0);
    ASSERT_GE(right, 0);
    ASSERT_GE(inner, 0);
    std::vector<double> values(m->faces().size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 100.0 + double(i);
    const Field f = FaceField(m, values);
    EXPECT_EQ(f({4, 8}), values[left]);
    EXPECT_EQ(f({7, 5}), values[right]);
    EXPECT_EQ(f({2, 2}), values[inner]);  // inside the hole: the inner face, not the left one
    EXPECT_TRUE(std::isnan(f({20, 5})));
    EXPECT_TRUE(std::isnan(f({-1, -1})));
    // On an edge: the adjacent face of smallest id, every time.
    EXPECT_EQ(f({5, 5}), values[std::min(left, right)]);
    EXPECT_EQ(f({1, 2}), values[std::min(left, inner)]);
    EXPECT_EQ(f({0, 5}), values[left]);  // on the outer border: the one bounded face there
    EXPECT_THROW(FaceField(m, {1.0}), Error);
}

TEST(Field, RegionFieldOverDisjointRegions) {
    const Region a = Region::rectangle(0, 0, 1, 1), b = Region::rectangle(1, 0, 2, 1);
    const Region ring({{10, 10}, {20, 10}, {20, 20}, {10, 20}}, {{{14, 14}, {16, 14}, {16, 16}, {14, 16}}});
    const Field f = RegionField({a, b, ring}, {1, 2, 3});
    EXPECT_EQ(f({0.5, 0.5}), 1);
    EXPECT_EQ(f({1.5, 0.5}), 2);
    EXPECT_EQ(f({1, 0.5}), 1);  // shared border: the smallest index
    EXPECT_EQ(f({12, 12}), 3);
    EXPECT_TRUE(std::isnan(f({15, 15})));  // in the hole
    EXPECT_EQ(f({14, 15}), 3);             // on the hole's border
    EXPECT_TRUE(std::isnan(f({5, 5})));
    EXPECT_THROW(RegionField({a}, {1, 2}), Error);
}

TEST(Field, CompositionsAndNaN) {
    const Field x = [](const Point& p) { return p.x; };
    const Field y = [](const Point& p) { return p.y; };
    const Point p{3, 4};
    EXPECT_EQ((x + y)(p), 7);
    EXPECT_EQ((x - y)(p), -1);
    EXPECT_EQ((x * y)(p), 12);
    EXPECT_EQ((x / y)(p), 0.75);
    EXPECT_EQ((x + 1)(p), 4);
    EXPECT_EQ((2 * y)(p), 8);
    EXPECT_EQ((-x)(p), -3);
    EXPECT_EQ(Apply(x, [](double v) { return v * v; })(p), 9);
    EXPECT_EQ(Combine(x, y, [](double a, double b) { return std::hypot(a, b); })(p), 5);
    EXPECT_EQ(Clamp(x, 0, 2)(p), 2);
    EXPECT_EQ(Clamp(x, 5, 6)(p), 5);
    EXPECT_EQ(Restrict(x, BBox{0, 0, 5, 5})(p), 3);
    EXPECT_TRUE(std::isnan(Restrict(x, BBox{0, 0, 2, 5})(p)));
    EXPECT_EQ(Restrict(x, Region::rectangle(0, 0, 3, 4))(p), 3);  // the border is inside
    EXPECT_TRUE(std::isnan(Restrict(x, Region::rectangle(0, 0, 2, 2))(p)));
    const Field part = Restrict(x, BBox{0, 0, 1, 1});
    EXPECT_EQ(Fallback(part, 42)(p), 42);
    EXPECT_EQ(Fallback(part, 42)({0.5, 0.5}), 0.5);
    // NaN goes through everything, and Apply / Combine do not call their function on it.
    const Field none;
    bool called = false;
    EXPECT_TRUE(std::isnan((none + 1)(p)));
    EXPECT_TRUE(std::isnan((x * none)(p)));
    EXPECT_TRUE(std::isnan(Clamp(none, 0, 1)(p)));
    EXPECT_TRUE(std::isnan(Apply(none, [&](double v) { called = true; return v; })(p)));
    EXPECT_TRUE(std::isnan(Combine(x, none, [&](double a, double) { called = true; return a; })(p)));
    EXPECT_FALSE(called);
    // Domains: intersected by Restrict and binary operations, joined by Fallback.
    const Field boxed = FunctionField([](const Point&) { return 1.0; }, BBox{0, 0, 4, 4});
    ASSERT_TRUE(Restrict(boxed, BBox{2, 2, 9, 9}).domain());
    EXPECT_EQ(Restrict(boxed, BBox{2, 2, 9, 9}).domain()->xmax, 4);
    EXPECT_EQ((boxed + x).domain()->xmin, 0);
    EXPECT_FALSE(Fallback(boxed, x).domain());
    EXPECT_THROW(Clamp(x, 2, 1), Error);
}

TEST(Field, VectorFields) {
    const VectorField v([](const Point& p) { return Point{-p.y, p.x}; });
    EXPECT_EQ(v({1, 0}), (Point{0, 1}));
    EXPECT_DOUBLE_EQ(Angle(v)({1, 0}), pi / 2);
    EXPECT_DOUBLE_EQ(Norm(v)({3, 4}), 5);
    const VectorField pair(Field(1.0), [](const Point& p) { return p.x; });
    EXPECT_EQ(pair({7, 0}), (Point{1, 7}));
    EXPECT_EQ(VectorField(Point{2, 3})({0, 0}), (Point{2, 3}));
    EXPECT_TRUE(std::isnan(Angle(VectorField())({0, 0})));
    const Field f = [](const Point& p) { return p.x * p.x + 3 * p.y; };
    const Point g = Gradient(f, 1e-3)({1, 2});
    EXPECT_NEAR(g.x, 2, 1e-9);
    EXPECT_NEAR(g.y, 3, 1e-9);
    EXPECT_THROW(Gradient(f, 0), Error);
}

TEST(Controlled, ArrangementsAndMappersCheckTheirArity) {
    const ControlledFaceMapper label("label", 1, [](const std::vector<Field>& f) {
        const Field v = f[0];
        return FaceMapper([v](const Face& face) {
            const Point c = Centroid(face);
            return Polyline({c, c + Point{v(c), 0}});
        });
    });
    const ControlledArrangement arr("tiles", 1, [label](const std::vector<Field>& f) {
        return MapToFaces(label(f), GridPartition(StripesProperties(0, 10), StripesProperties(pi / 2, 10), KEEP_OUTSIDE));
    });
    EXPECT_EQ(arr.name(), "tiles");
    EXPECT_EQ(arr.arity(), 1u);
    const Curves out = arr(3.0)(Region::rectangle(0, 0, 30, 30));
    ASSERT_EQ(out.size(), 9u);
    for (const auto& c : out.curves) EXPECT_DOUBLE_EQ(c.points.back().x - c.points.front().x, 3);
    try {
        arr(1.0, 2.0);
        FAIL() << "no error for two fields";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'tiles' takes 1 field, got 2"), std::string::npos) << e.what();
    }
    try {
        label(std::vector<Field>{});
        FAIL() << "no error for no field";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("controlled mapper 'label'"), std::string::npos) << e.what();
    }
}

namespace {

// A controlled mapper reading its field at the centroid shifted by `offset`.
Arrangement reading_at(const Field& f, Point offset) {
    return MapToFaces(
        [f, offset](const Face& face) {
            const double v = f(Centroid(face) + offset);
            return std::isnan(v) ? Nothing() : Polyline({Centroid(face), Centroid(face) + Point{1, 0}});
        },
        GridPartition(StripesProperties(0, 50), StripesProperties(pi / 2, 50), KEEP_OUTSIDE));
}

struct Counts {
    std::size_t reads, violations;
    double worst;
};

Counts check(const Arrangement& a, double margin) {
    LocalityCheck c(margin);
    a(Region::rectangle(0, 0, 200, 200));
    return {c.reads(), c.violations(), c.worst()};
}

}  // namespace

TEST(LocalityCheck, MapperReadingInsideItsFaceIsLocal) {
    ThreadsGuard guard;
    const Field f = [](const Point& p) { return p.x; };
    for (unsigned t : {1u, 2u}) {
        SetThreads(t);
        const Counts inside = check(reading_at(f, {0, 0}), 0);
        EXPECT_EQ(inside.reads, 16u) << t;
        EXPECT_EQ(inside.violations, 0u) << t;
        EXPECT_EQ(inside.worst, 0) << t;
        const Counts far = check(reading_at(f, {1000, 0}), 10);
        EXPECT_EQ(far.reads, 16u) << t;
        EXPECT_EQ(far.violations, 16u) << t;
        EXPECT_NEAR(far.worst, 975, 1e-9) << t;  // 1000 from the centroid, 25 to the cell's side
    }
    // Within the margin is no violation.
    EXPECT_EQ(check(reading_at(f, {40, 0}), 20).violations, 0u);
    EXPECT_EQ(check(reading_at(f, {40, 0}), 10).violations, 16u);
}

TEST(LocalityCheck, ControlledMapperThroughNestedMappers) {
    ThreadsGuard guard;
    SetThreads(2);
    const Field f = [](const Point& p) { return p.y; };
    // Faces of 100 each holding a grid of 25: the inner mapper's window is the small cell.
    const Arrangement inner = MapToFaces(
        [f](const Face& big) {
            const double v = f(Centroid(big));  // read in the big face's window
            (void)v;
            return reading_at(f, {30, 0})(big);  // 30 from a cell of 50: 5 outside
        },
        GridPartition(StripesProperties(0, 100), StripesProperties(pi / 2, 100), KEEP_OUTSIDE));
    LocalityCheck c(1);
    inner(Region::rectangle(0, 0, 200, 200));
    EXPECT_EQ(c.reads(), 4u + 16u);
    EXPECT_EQ(c.violations(), 16u);
    EXPECT_NEAR(c.worst(), 5, 1e-9);
}

TEST(LocalityCheck, ReadsOutsideAnyWindowAreNotChecked) {
    ThreadsGuard guard;
    const Field f = [](const Point& p) { return p.x; };
    LocalityCheck c(0);
    EXPECT_EQ(f({1e6, 0}), 1e6);
    EXPECT_EQ(c.reads(), 0u);
    EXPECT_EQ(c.violations(), 0u);
    reading_at(f, {0, 0})(Region::rectangle(0, 0, 100, 100));  // the mappers close their windows
    const std::size_t after = c.reads();
    f({-5, -5});
    EXPECT_EQ(c.reads(), after);
    {
        FieldWindow w(BBox{0, 0, 10, 10});
        f({5, 5});
        f({13, 14});  // 5 outside
        // Work items follow the window of the thread that starts them.
        SetThreads(2);
        parallel_for(10, [&](std::size_t) { f({20, 10}); });
    }
    EXPECT_EQ(c.reads(), after + 12);
    EXPECT_EQ(c.violations(), 11u);
    EXPECT_NEAR(c.worst(), 10, 1e-12);
    f({1e9, 0});
    EXPECT_EQ(c.reads(), after + 12);
}

TEST(LocalityCheck, NoCheckNoCount) {
    const Field f = [](const Point& p) { return p.x; };
    FieldWindow w(BBox{0, 0, 1, 1});
    {
        LocalityCheck c;
        EXPECT_EQ(f({0.5, 0.5}), 0.5);
        EXPECT_EQ(c.reads(), 1u);  // a live check counts
    }
    EXPECT_EQ(f({100, 0}), 100);  // no check alive: nothing recorded, nothing fails
    LocalityCheck fresh;           // and the read above left nothing behind for the next check
    EXPECT_EQ(fresh.reads(), 0u);
    EXPECT_EQ(fresh.violations(), 0u);
    EXPECT_THROW(LocalityCheck(-1), Error);
}

// AlignToField turns each open curve about its middle onto the field's axis there, keeping
// its length and the sense nearer its own; closed curves and NaN reads leave curves alone.
TEST(AlignToField, TurnsOpenCurvesOntoTheFieldAxis) {
    const Arrangement strokes([](const Region&) {
        Curves c = Polyline({{0, 0}, {2, 0}});            // middle (1, 0)
        c.append(Polyline({{10, 0}, {12, 0}}));           // middle (11, 0): NaN there
        c.append(Polyline({{0, 5}, {1, 5}, {1, 6}}, true));  // closed: left as it is
        c.append(Polyline({{20, 0}, {22, 0}}));           // wants an axis almost reversed
        return c;
    });
    const Field angle = [](const Point& p) {
        if (p.x > 10 && p.x < 12) return double(NAN);
        return p.x > 15 ? M_PI - 0.1 : M_PI / 2;
    };
    const Curves out = AlignToField(strokes, angle)(Region({{-1, -1}, {30, -1}, {30, 10}, {-1, 10}}));
    ASSERT_EQ(out.curves.size(), 4u);
    const auto& v = out.curves[0].points;
    EXPECT_NEAR(v[0].x, 1, 1e-12);
    EXPECT_NEAR(v[0].y, -1, 1e-12);
    EXPECT_NEAR(v[1].x, 1, 1e-12);
    EXPECT_NEAR(v[1].y, 1, 1e-12);
    EXPECT_EQ(out.curves[1].points, (std::vector<Point>{{10, 0}, {12, 0}}));
    EXPECT_EQ(out.curves[2].points, (std::vector<Point>{{0, 5}, {1, 5}, {1, 6}}));
    // The axis pi - 0.1 is the same as -0.1: the curve turns by -0.1, not by pi - 0.1.
    const auto& w = out.curves[3].points;
    EXPECT_NEAR(std::atan2(w[1].y - w[0].y, w[1].x - w[0].x), -0.1, 1e-12);
    EXPECT_NEAR(distance(w[0], w[1]), 2, 1e-12);
}

// IsoLines: marching squares on a global lattice.
TEST(IsoLines, ACircleWithTheHighSideOnTheLeft) {
    const Field r([](const Point& p) { return std::hypot(p.x, p.y); });
    const Curves c = IsoLines(r, 5.0, 0.25)(Region::rectangle(-10, -10, 10, 10));
    ASSERT_EQ(c.curves.size(), 1u);
    const Curve& ring = c.curves[0];
    EXPECT_TRUE(ring.closed);
    for (const Point& p : ring.points) EXPECT_NEAR(std::hypot(p.x, p.y), 5.0, 0.01);
    // Higher values (outside) on the left: the ring runs clockwise.
    EXPECT_LT(signed_area(ring.points), 0);
    EXPECT_NEAR(-signed_area(ring.points), pi * 25, 0.2);
}

TEST(IsoLines, TheLinesOfAPartAreThoseOfTheWhole) {
    const Field f([](const Point& p) { return std::sin(p.x / 3) + std::cos(p.y / 4); });
    auto points = [](const Curves& c) {
        std::set<std::pair<double, double>> s;
        for (const auto& k : c.curves)
            for (const Point& p : k.points) s.insert({p.x, p.y});
        return s;
    };
    const auto whole = points(IsoLines(f, 0.3, 0.5)(Region::rectangle(-20, -20, 20, 20)));
    const auto part = points(IsoLines(f, 0.3, 0.5)(Region::rectangle(-3.3, 1.7, 8.1, 12.9)));
    ASSERT_FALSE(part.empty());
    for (const auto& p : part) EXPECT_TRUE(whole.count(p)) << p.first << " " << p.second;
    // NaN corners give nothing; bad arguments are refused.
    EXPECT_TRUE(IsoLines(Field(), 0.0, 1.0)(Region::rectangle(0, 0, 5, 5)).empty());
    EXPECT_THROW(IsoLines(f, 0.0, 0.0), Error);
    EXPECT_THROW(IsoLines(f, NAN, 1.0), Error);
}

// Creases: ridge and valley lines of a surface on a global lattice.
namespace {
double distance_to_line_x(const Curves& c, double x0) {
    double worst = 0;
    for (const auto& k : c.curves)
        for (const Point& p : k.points) worst = std::max(worst, std::abs(p.x - x0));
    return worst;
}
}  // namespace

TEST(Creases, ARidgeAndAValleyAlongTheirCrestAndFloor) {
    // A ridge along x = 2.3 (a smooth tent), a valley along x = -4.1, on a gentle tilt in y.
    const Field ridge([](const Point& p) { return -std::sqrt(1 + (p.x - 2.3) * (p.x - 2.3)) + 0.05 * p.y; });
    const Field valley([](const Point& p) { return std::sqrt(1 + (p.x + 4.1) * (p.x + 4.1)) + 0.05 * p.y; });
    const Region box = Region::rectangle(-10, -10, 10, 10);
    const Curves r = Creases(ridge, CreaseKind::Ridge, 0.5, 0.1)(box);
    ASSERT_EQ(r.curves.size(), 1u);
    EXPECT_LT(distance_to_line_x(r, 2.3), 0.05);
    EXPECT_GT(r.curves[0].points.size(), 30u);  // across the whole box
    const Curves v = Creases(valley, CreaseKind::Valley, 0.5, 0.1)(box);
    ASSERT_EQ(v.curves.size(), 1u);
    EXPECT_LT(distance_to_line_x(v, -4.1), 0.05);
    // A ridge is no valley, and a plane or a bend weaker than min_bend has none.
    EXPECT_TRUE(Creases(ridge, CreaseKind::Valley, 0.5, 0.1)(box).empty());
    EXPECT_TRUE(Creases(Field([](const Point& p) { return 0.3 * p.x - 0.2 * p.y; }), CreaseKind::Ridge, 0.5, 0.01)(box)
                    .empty());
    EXPECT_TRUE(Creases(ridge, CreaseKind::Ridge, 0.5, 2.0)(box).empty());
}

// Both kinds from one sampling: the ridges then the valleys, each exactly the lines of its own
// kind, labelled with it.
TEST(Creases, BothKindsAreTheTwoSetsOfLinesLabelled) {
    // Crests along x = pi/2 + 2 k pi, floors along x = -pi/2 + 2 k pi, on a gentle tilt.
    const Field surface([](const Point& p) { return std::sin(p.x) + 0.05 * p.y; });
    const Region box = Region::rectangle(-10, -10, 10, 10);
    const Curves r = Creases(surface, CreaseKind::Ridge, 0.5, 0.1)(box);
    const Curves v = Creases(surface, CreaseKind::Valley, 0.5, 0.1)(box);
    ASSERT_EQ(r.curves.size(), 3u);
    ASSERT_EQ(v.curves.size(), 3u);
    for (const auto& k : r.curves)
        for (const Point& p : k.points) EXPECT_NEAR(std::sin(p.x), 1.0, 0.01);
    const Curves both = Creases(surface, CreaseKind::Both, 0.5, 0.1)(box);
    ASSERT_EQ(both.curves.size(), r.curves.size() + v.curves.size());
    for (std::size_t k = 0; k < both.curves.size(); ++k) {
        const bool ridge = k < r.curves.size();
        EXPECT_EQ(both.curves[k].labels.has("ridge"), ridge);
        EXPECT_EQ(both.curves[k].labels.has("valley"), !ridge);
        EXPECT_EQ(both.curves[k].points, ridge ? r.curves[k].points : v.curves[k - r.curves.size()].points);
    }
    EXPECT_TRUE(r.curves[0].labels.empty());
}

TEST(Creases, ASummitRingIsClosedAndAPartDrawsTheWholesLines) {
    // A crater rim: a ridge on the circle of radius 6 (bending by 2 across); its flanks are
    // cones, convex along their contours by slope / radius (under 0.2), below min_bend.
    const Field rim([](const Point& p) {
        const double d = std::hypot(p.x, p.y) - 6;
        return -std::sqrt(0.25 + d * d);
    });
    const Curves whole = Creases(rim, CreaseKind::Ridge, 0.4, 0.3)(Region::rectangle(-10, -10, 10, 10));
    ASSERT_EQ(whole.curves.size(), 1u);
    EXPECT_TRUE(whole.curves[0].closed);
    for (const Point& p : whole.curves[0].points) EXPECT_NEAR(std::hypot(p.x, p.y), 6, 0.1);
    std::set<std::pair<double, double>> all;
    for (const Point& p : whole.curves[0].points) all.insert({p.x, p.y});
    const Curves part = Creases(rim, CreaseKind::Ridge, 0.4, 0.3)(Region::rectangle(1.1, -2.7, 9.3, 3.9));
    ASSERT_FALSE(part.empty());
    for (const auto& k : part.curves)
        for (const Point& p : k.points) EXPECT_TRUE(all.count({p.x, p.y})) << p.x << " " << p.y;
    // NaN gives nothing; bad arguments are refused.
    EXPECT_TRUE(Creases(Field(), CreaseKind::Ridge, 1.0, 0.0)(Region::rectangle(0, 0, 5, 5)).empty());
    EXPECT_THROW(Creases(rim, CreaseKind::Ridge, 0.0, 0.1), Error);
    EXPECT_THROW(Creases(rim, CreaseKind::Ridge, 1.0, -1.0), Error);
}
