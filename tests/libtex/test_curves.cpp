// Curves utilities and the adjacency built-ins on curves (tables 3.4 and 3.6).
#include <random>
#include <set>
#include <gtest/gtest.h>

#include "helpers.hpp"

using namespace tex;

namespace {

Curves element() {
    Curves c = Polyline({{0, 0}, {10, 0}, {10, 4}});
    c.points.push_back({{0, 0}, Labels{"start"}});
    c.points.push_back({{10, 4}, Labels{"end"}});
    return c;
}

void expect_near(const Point& a, const Point& b) {
    EXPECT_NEAR(a.x, b.x, 1e-9);
    EXPECT_NEAR(a.y, b.y, 1e-9);
}

}  // namespace

TEST(Curves, MatchPointsSendsSourcesToTargets) {
    const Curves c = element();
    const Point t1{100, 50}, t2{80, 90};
    const Curves m = MatchPoints(c, PointLabeled(c, "start"), PointLabeled(c, "end"), t1, t2);
    expect_near(PointLabeled(m, "start"), t1);
    expect_near(PointLabeled(m, "end"), t2);
    // A similarity: lengths scale uniformly.
    const double s = distance(t1, t2) / distance({0, 0}, {10, 4});
    EXPECT_NEAR(th::length(m), th::length(c) * s, 1e-9);
}

TEST(Curves, MatchPointsRejectsCoincidentSources) {
    EXPECT_TEX_ERROR(MatchPoints(element(), {1, 1}, {1, 1}, {0, 0}, {1, 0}), "MatchPoints", "coincide");
}

TEST(Curves, MatchPointTranslates) {
    const Curves m = MatchPoint(element(), {10, 0}, {0, 0});
    expect_near(m.curves[0].points[0], {-10, 0});
    expect_near(PointLabeled(m, "end"), {0, 4});
}

TEST(Curves, ScaleAndRotateAboutTheBoundingBoxCentre) {
    const Curves c = element();
    const Point centre = BBoxCenter(c);
    expect_near(centre, {5, 2});
    const Curves s = Scale(c, 2);
    expect_near(BBoxCenter(s), centre);
    EXPECT_NEAR(BBoxWidth(s), 20, 1e-12);
    EXPECT_NEAR(BBoxHeight(s), 8, 1e-12);
    const Curves r = Rotate(c, pi / 2);
    expect_near(BBoxCenter(r), centre);
    EXPECT_NEAR(BBoxWidth(r), 4, 1e-9);
    EXPECT_NEAR(BBoxHeight(r), 10, 1e-9);
    EXPECT_NEAR(th::length(r), th::length(c), 1e-9);
}

TEST(Curves, MirrorSwapsSideLabels) {
    Curves c = Polyline({{0, 0}, {1, 0}});
    c.curves[0].left = Labels{"l"};
    const Curves m = Scale(c, -1, 1);
    EXPECT_TRUE(m.curves[0].right.has("l"));
    EXPECT_TRUE(m.curves[0].left.empty());
}

TEST(Curves, AppendNothingAndLabelledCurves) {
    Curves a = element();
    a.curves[0].labels.add("body");
    const Curves b = Append(a, Translate(Polyline({{0, 0}, {1, 1}}), {5, 5}));
    EXPECT_EQ(b.curves.size(), 2u);
    EXPECT_TRUE(Nothing().empty());
    EXPECT_EQ(CurveLabeled(b, "body").curves.size(), 1u);
    EXPECT_TEX_ERROR(CurveLabeled(b, "tail"), "CurveLabeled", "'tail'");
    EXPECT_TEX_ERROR(PointLabeled(b, "middle"), "PointLabeled", "no point labelled 'middle'");
}

TEST(Random, UnkeyedRandomIsKeyedByScope) {
    double a1, a2, b1;
    {
        RandomScope s(42);
        a1 = Random(0, 1);
        a2 = Random(0, 1);
    }
    {
        RandomScope s(42);
        b1 = Random(0, 1);
    }
    EXPECT_EQ(a1, b1);
    EXPECT_NE(a1, a2);
    EXPECT_GE(a1, 0);
    EXPECT_LT(a1, 1);
}

TEST(Curves, MatchPointsLandsExactlyOnItsTargets) {
    // Targets of a GridPartition(pi/3, -pi/3) whose rounded similarity misses the second
    // one by an ulp: an element matched between two vertices must end on them.
    const Point t1{115.47005383792514, 999.99999999999977}, t2{346.41016151377551, 999.99999999999977};
    Curves bar = Polyline({{0, 0}, {30, 5}, {100, 0}});
    bar.points.push_back({{100, 0}, Labels{"end"}});
    const Curves m = MatchPoints(bar, {0, 0}, {100, 0}, t1, t2);
    EXPECT_EQ(m.curves[0].points.front(), t1);
    EXPECT_EQ(m.curves[0].points.back(), t2);
    EXPECT_EQ(PointLabeled(m, "end"), t2);
    const Curves one = MatchPoint(bar, {100, 0}, t2);
    EXPECT_EQ(one.curves[0].points.back(), t2);
}

// Labels keep a few ids inline and more on the heap: the set behaves the same across the
// change of storage (sorted, unique, merge, remove, copy, move).
TEST(Labels, SetSemanticsAcrossInlineAndHeapStorage) {
    std::vector<std::string> names = {"e", "b", "g", "a", "f", "c", "d"};
    Labels l;
    std::set<LabelId> want;
    for (const auto& n : names) {
        l.add(n);
        l.add(n);  // twice: no duplicate
        want.insert(intern_label(n));
        ASSERT_EQ(l.ids(), std::vector<LabelId>(want.begin(), want.end()));
    }
    for (const auto& n : names) EXPECT_TRUE(l.has(n));
    EXPECT_FALSE(l.has("not a label of this set"));
    Labels small{"a", "zz"};
    Labels merged = small;
    merged.merge(l);
    EXPECT_EQ(merged.size(), 8u);
    EXPECT_TRUE(merged.has("zz"));
    Labels moved = std::move(merged);
    EXPECT_EQ(moved.size(), 8u);
    for (const auto& n : names) {
        moved.remove(intern_label(n));
        EXPECT_FALSE(moved.has(n));
    }
    EXPECT_EQ(moved, Labels({"zz"}));
    EXPECT_NE(moved, small);
    Labels three{"x", "y", "z"};
    Labels four = three;
    four.add("w");
    EXPECT_EQ(four.names(), (std::vector<std::string>{"w", "x", "y", "z"}));
    four.remove(intern_label("w"));
    EXPECT_EQ(four, three);
    // Heap sets copied and moved over heap and inline sets: each keeps its own ids (the
    // sanitizer pass checks that no array is lost or freed twice).
    Labels big = l, other{"p", "q", "r", "s"};
    other = big;
    big.add("h");
    EXPECT_EQ(other, l);
    EXPECT_EQ(big.size(), 8u);
    const Labels& self = other;
    other = self;
    EXPECT_EQ(other, l);
    other = std::move(big);
    EXPECT_EQ(other.size(), 8u);
    EXPECT_TRUE(other.has("h"));
    three = other;
    EXPECT_EQ(three, other);
    three = Labels{"x"};
    EXPECT_EQ(three.names(), (std::vector<std::string>{"x"}));
    // An inline set copied over a heap set (its array freed) and into a fresh one.
    const Labels two{"m", "n"};
    Labels heap = l;
    heap = two;
    EXPECT_EQ(heap, two);
    heap.add("o");
    EXPECT_EQ(heap.names(), (std::vector<std::string>{"m", "n", "o"}));
    const Labels copy(two);
    EXPECT_EQ(copy.names(), (std::vector<std::string>{"m", "n"}));
    EXPECT_EQ(sizeof(Labels), 16u);
}

TEST(CurvesInPlace, SameBytesAsTheCopyingOperators) {
    // The jitter mapper moves its curve in place; the points must be those MatchPoints and
    // Scale give, bit for bit, with the labels and labelled points along.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1e5, 1e5), small(-3, 3);
    for (int k = 0; k < 200; ++k) {
        Curves c;
        Curve cv;
        const int n = 2 + k % 5;
        for (int i = 0; i < n; ++i) cv.points.push_back({u(rng), u(rng)});
        cv.closed = k % 3 == 0;
        cv.labels.add("edge");
        cv.left.add("l");
        cv.right.add("r");
        c.curves.push_back(cv);
        c.points.push_back({cv.points[0], Labels{}});
        const Point s1 = cv.points.front(), s2 = cv.points.back();
        const Point t1 = s1 + Point{small(rng), small(rng)}, t2 = s2 + Point{small(rng), small(rng)};
        Curves moved = c;
        detail::match_points_in_place(moved, s1, s2, t1, t2);
        const Curves copied = MatchPoints(c, s1, s2, t1, t2);
        ASSERT_EQ(moved.curves[0].points, copied.curves[0].points);
        EXPECT_EQ(moved.curves[0].points.front(), t1);
        EXPECT_EQ(moved.points[0].point, copied.points[0].point);
        EXPECT_EQ(moved.curves[0].left, copied.curves[0].left);
        const double gap = 0.5 + 0.4 * (k % 4) / 3.0;
        Curves shortened = moved;
        detail::scale_in_place(shortened, gap);
        EXPECT_EQ(shortened.curves[0].points, Scale(copied, gap).curves[0].points);
    }
    Curves c = Polyline({{0, 0}, {1, 1}});
    EXPECT_THROW(detail::match_points_in_place(c, {2, 2}, {2, 2}, {0, 0}, {1, 0}), Error);
}
