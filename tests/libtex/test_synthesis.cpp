// SynthesizeAlongCurve / SynthesizeInRectangle (seed 002): the topology guarantees checked on
// the output polygons by an independent count (nesting of the contours after a test that no
// two segments meet), lengths, closure, determinism and errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "libtex/tex.hpp"

using namespace tex;

namespace {

const std::string kElements = RH_SYNTH_ELEMENTS;

Curves exemplar(const std::string& name) { return ImportSVG(kElements + "/" + name + ".svg"); }

// ---- An independent count on the final polygons ----

bool crosses(const Point& a, const Point& b, const Point& c, const Point& d) {
    auto orient = [](const Point& p, const Point& q, const Point& r) {
        const double v = cross(q - p, r - p);
        return v > 0 ? 1 : (v < 0 ? -1 : 0);
    };
    auto on = [](const Point& p, const Point& q, const Point& r) {  // r on segment pq (collinear)
        return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
               r.y <= std::max(p.y, q.y);
    };
    const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (o1 != o2 && o3 != o4) return true;
    return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) ||
           (o4 == 0 && on(c, d, b));
}

// Number of pairs of segments that touch or cross (neighbours along a contour excepted).
int intersections(const Curves& c) {
    struct Seg {
        Point a, b;
        std::size_t ring, i, n;
        double xmin, xmax;
    };
    std::vector<Seg> s;
    for (std::size_t r = 0; r < c.curves.size(); ++r) {
        const auto& p = c.curves[r].points;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const Point& a = p[i];
            const Point& b = p[(i + 1) % p.size()];
            s.push_back({a, b, r, i, p.size(), std::min(a.x, b.x), std::max(a.x, b.x)});
        }
    }
    std::sort(s.begin(), s.end(), [](const Seg& u, const Seg& v) { return u.xmin < v.xmin; });
    int hits = 0;
    for (std::size_t i = 0; i < s.size(); ++i)
        for (std::size_t j = i + 1; j < s.size() && s[j].xmin <= s[i].xmax; ++j) {
            if (s[i].ring == s[j].ring) {
                const std::size_t n = s[i].n;
                if ((s[i].i + 1) % n == s[j].i || (s[j].i + 1) % n == s[i].i) continue;
            }
            if (crosses(s[i].a, s[i].b, s[j].a, s[j].b)) ++hits;
        }
    return hits;
}

bool inside(const std::vector<Point>& ring, const Point& p) {
    bool in = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
        if ((ring[i].y > p.y) != (ring[j].y > p.y) &&
            p.x < (ring[j].x - ring[i].x) * (p.y - ring[i].y) / (ring[j].y - ring[i].y) + ring[i].x)
            in = !in;
    return in;
}

struct Topo {
    int components = 0, holes = 0;
    bool oriented = true;  // contours at even depth counter-clockwise, at odd depth clockwise
};

// With no two contours meeting, the nesting depth of each contour decides what it bounds:
// even depth an outer boundary (one component), odd depth a hole.
Topo count(const Curves& c) {
    Topo t;
    for (std::size_t i = 0; i < c.curves.size(); ++i) {
        EXPECT_TRUE(c.curves[i].closed);
        int depth = 0;
        for (std::size_t j = 0; j < c.curves.size(); ++j)
            if (j != i && inside(c.curves[j].points, c.curves[i].points[0])) ++depth;
        const bool ccw = signed_area(c.curves[i].points) > 0;
        if (depth % 2 == 0) ++t.components;
        else ++t.holes;
        if (ccw != (depth % 2 == 0)) t.oriented = false;
    }
    return t;
}

double perimeter(const std::vector<Point>& p, bool closed) {
    double l = 0;
    for (std::size_t i = 1; i < p.size(); ++i) l += distance(p[i - 1], p[i]);
    if (closed) l += distance(p.back(), p.front());
    return l;
}

std::vector<Point> circle(Point c, double r, int n = 256) {
    std::vector<Point> p;
    for (int i = 0; i < n; ++i) p.push_back(c + Point{std::cos(2 * pi * i / n), std::sin(2 * pi * i / n)} * r);
    return p;
}

std::vector<Point> wave(double length, double amp, int n = 200) {
    std::vector<Point> p;
    for (int i = 0; i <= n; ++i) {
        const double x = length * i / n;
        p.push_back({x, amp * std::sin(2 * pi * x / (length / 1.5))});
    }
    return p;
}

// Winding number of a closed polyline around p.
int winding(const std::vector<Point>& ring, const Point& p) {
    double a = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const Point u = ring[i] - p, v = ring[(i + 1) % ring.size()] - p;
        a += std::atan2(cross(u, v), dot(u, v));
    }
    return int(std::lround(a / (2 * pi)));
}

std::string bytes(const Curves& c) { return ToSVG(c, c.bbox().expanded(1)); }

SynthesisOptions fine(std::optional<int> comps, std::optional<int> holes) {
    SynthesisOptions o;
    o.components = comps;
    o.holes = holes;
    o.event_grouping = 0.03;
    o.seed = 7;
    return o;
}

}  // namespace

// ---- The guarantees, as a table: exemplar x curve x length x constraint ----

struct Case {
    std::string exemplar;
    bool closed;
    double length;  // of the curve (open: wave length; closed: circle circumference)
    std::optional<int> components, holes;
    double band = 40;
    Slicing slicing = Slicing::Topology;
};

class Guarantees : public ::testing::TestWithParam<Case> {};

TEST_P(Guarantees, OutputHasTheRequestedTopology) {
    const Case& k = GetParam();
    SynthesisOptions o = fine(k.components, k.holes);
    o.slicing = k.slicing;
    o.slicing_lines = 9;
    const Curves curve = k.closed ? Polyline(circle({0, 0}, k.length / (2 * pi)), true) : Polyline(wave(k.length, 60));
    const double L = perimeter(curve.curves[0].points, k.closed);
    SynthesisReport rep;
    const Curves out = SynthesizeAlongCurve(exemplar(k.exemplar), curve, k.band, o, &rep);
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(intersections(out), 0);
    const Topo t = count(out);
    EXPECT_TRUE(t.oriented);
    if (k.components) EXPECT_EQ(t.components, *k.components);
    if (k.holes) EXPECT_EQ(t.holes, *k.holes);
    EXPECT_EQ(t.components, rep.components);
    EXPECT_EQ(t.holes, rep.holes);
    // The natural length of the chosen pieces is within the tolerance of the curve's.
    EXPECT_LE(std::abs(rep.natural_length - L), o.length_tolerance * L + 1e-9) << rep.natural_length << " vs " << L;
    EXPECT_GT(rep.pieces_in_result, 1);
}

INSTANTIATE_TEST_SUITE_P(
    Synthesis, Guarantees,
    ::testing::Values(
        Case{"synth_vine", false, 1500, 1, std::nullopt}, Case{"synth_vine", false, 1500, 1, 0},
        Case{"synth_vine", false, 3000, 1, 2}, Case{"synth_vine", false, 800, 1, 0},
        Case{"synth_vine", true, 1500, 1, 0}, Case{"synth_vine", true, 2500, 1, std::nullopt},
        Case{"synth_ladder", false, 1200, 1, 1, 40, Slicing::Uniform},
        Case{"synth_ladder", false, 2000, std::nullopt, std::nullopt},
        Case{"synth_beads", false, 2000, 3, std::nullopt}, Case{"synth_ladder", true, 1600, 1, std::nullopt},
        Case{"synth_beads", false, 1200, std::nullopt, std::nullopt},
        Case{"synth_beads", false, 1500, 1, std::nullopt},
        Case{"synth_beads", true, 1400, std::nullopt, std::nullopt},
        Case{"synth_ladder", false, 1500, 1, 2, 40, Slicing::Uniform},
        Case{"synth_vine", true, 2000, 1, std::nullopt, 40, Slicing::Uniform}));

TEST(Synthesis, ClosedPatternGoesRoundTheCurve) {
    SynthesisOptions o = fine(1, std::nullopt);
    o.closed_pattern = true;
    const Curves curve = Polyline(circle({500, 500}, 300), true);
    SynthesisReport rep;
    const Curves out = SynthesizeAlongCurve(exemplar("synth_ladder"), curve, 40, o, &rep);
    EXPECT_EQ(intersections(out), 0);
    const Topo t = count(out);
    EXPECT_EQ(t.components, 1);
    EXPECT_TRUE(t.oriented);
    EXPECT_TRUE(rep.closed_pattern);
    // Some outer contour winds once round the centre (it is a ring), and the centre is
    // outside the pattern.
    int rings = 0;
    for (const Curve& c : out.curves)
        if (signed_area(c.points) > 0 && winding(c.points, {500, 500}) == 1) ++rings;
    EXPECT_EQ(rings, 1);
    int total = 0;
    for (const Curve& c : out.curves) total += winding(c.points, {500, 500});
    EXPECT_EQ(total, 0);
}

TEST(Synthesis, NoHolesOnACircleMeansTheRingIsBroken) {
    const Curves curve = Polyline(circle({0, 0}, 250), true);
    const Curves out = SynthesizeAlongCurve(exemplar("synth_vine"), curve, 40, fine(1, 0));
    int total = 0;
    for (const Curve& c : out.curves) total += winding(c.points, {0, 0});
    EXPECT_EQ(total, 0);
    EXPECT_EQ(count(out).holes, 0);
}

TEST(Synthesis, PatternStaysInTheBandAndSpansTheCurve) {
    const Curves curve = Polyline({{0, 0}, {1000, 0}});
    const Curves out = SynthesizeAlongCurve(exemplar("synth_vine"), curve, 50, fine(1, std::nullopt));
    const BBox b = out.bbox();
    // The pieces at the ends keep a margin of 1% of the exemplar's width (pieces.cpp).
    EXPECT_GE(b.xmin, 0);
    EXPECT_LE(b.xmin, 10);
    EXPECT_LE(b.xmax, 1000);
    EXPECT_GE(b.xmax, 990);
    // The exemplar is scaled so that its height is the band's, and along a straight curve
    // its y is the distance to the curve: the pattern fills the band of half-height 25 exactly
    // (to rounding), never beyond it.
    EXPECT_NEAR(b.ymin, -25, 1e-9);
    EXPECT_NEAR(b.ymax, 25, 1e-9);
}

TEST(Synthesis, SeamsTurnOntoOneTangent) {
    // A strip waving up and down, cut across at 13 places: pieces from different phases meet
    // at seams where their boundaries slope differently. Stitching moves the ends to one
    // point and turns both sides onto the average direction there, so no vertex of the
    // result (away from the end caps) turns by more than 10 degrees; without the turn,
    // 10 to 16 vertices do (up to 14 degrees). The topology and validity stay.
    std::vector<Point> ring;
    const int n = 300;
    for (int i = 0; i <= n; ++i) ring.push_back({6.0 * i / n, 0.5 * std::sin(pi * 6.0 * i / n) - 0.15});
    for (int i = n; i >= 0; --i) ring.push_back({6.0 * i / n, 0.5 * std::sin(pi * 6.0 * i / n) + 0.15});
    const Curves strip = Polyline(ring, true);
    SynthesisOptions o;
    o.components = 1;
    o.slicing = Slicing::Uniform;
    o.slicing_lines = 13;
    const double L = 1200;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        o.seed = seed;
        const Curves out = SynthesizeAlongCurve(strip, Polyline({{0, 0}, {L, 0}}), 40, o);
        EXPECT_EQ(intersections(out), 0);
        EXPECT_EQ(count(out).components, 1);
        int sharp = 0;
        double worst = 0;
        for (const auto& c : out.curves) {
            const auto& p = c.points;
            for (std::size_t i = 0; i < p.size(); ++i) {
                if (p[i].x < 0.05 * L || p[i].x > 0.95 * L) continue;  // the end caps' corners
                const Point a = p[(i + p.size() - 1) % p.size()], b = p[i], d = p[(i + 1) % p.size()];
                const double turn =
                    std::abs(std::remainder(std::atan2(d.y - b.y, d.x - b.x) - std::atan2(b.y - a.y, b.x - a.x), 2 * pi));
                worst = std::max(worst, turn * 180 / pi);
                sharp += turn * 180 / pi > 10;
            }
        }
        EXPECT_EQ(sharp, 0) << "seed " << seed << ": turns up to " << worst << " degrees";
    }
}

TEST(Synthesis, SameSeedSameBytesAtAnyThreadCount) {
    const Curves curve = Polyline(wave(1500, 50));
    SetThreads(1);
    const std::string a = bytes(SynthesizeAlongCurve(exemplar("synth_vine"), curve, 40, fine(1, std::nullopt)));
    SetThreads(2);
    const std::string b = bytes(SynthesizeAlongCurve(exemplar("synth_vine"), curve, 40, fine(1, std::nullopt)));
    SetThreads(0);
    EXPECT_EQ(a, b);
    SynthesisOptions other = fine(1, std::nullopt);
    other.seed = 8;
    other.randomness = 0.5;
    SynthesisOptions same = fine(1, std::nullopt);
    same.randomness = 0.5;
    EXPECT_NE(bytes(SynthesizeAlongCurve(exemplar("synth_vine"), curve, 40, same)),
              bytes(SynthesizeAlongCurve(exemplar("synth_vine"), curve, 40, other)));
}

TEST(Synthesis, AutocorrelationPenaltyKeepsTheGuarantees) {
    SynthesisOptions o = fine(1, 0);
    o.autocorrelation = 0.5;
    const Curves out = SynthesizeAlongCurve(exemplar("synth_vine"), Polyline(wave(2000, 40)), 40, o);
    EXPECT_EQ(intersections(out), 0);
    const Topo t = count(out);
    EXPECT_EQ(t.components, 1);
    EXPECT_EQ(t.holes, 0);
}

TEST(Synthesis, SlicingCutsBetweenGroupsOfEvents) {
    // The ladder's events: its two ends and where each of its four holes starts and ends;
    // the end of one hole and the start of the next lie a rung apart (8 of 600).
    const Curves line = Polyline({{0, 0}, {1500, 0}});
    auto pieces = [&](SynthesisOptions o) {
        o.components = std::nullopt;
        SynthesisReport rep;
        SynthesizeAlongCurve(exemplar("synth_ladder"), line, 40, o, &rep);
        return rep.pieces_in_exemplar;
    };
    SynthesisOptions o;
    o.event_grouping = 0.03;  // groups: the left end, 64, 200, 260, 420, 536, the right end
    EXPECT_EQ(pieces(o), 7);
    o.event_grouping = 0.2;  // groups: {0, 64}, {200, 260}, {420, 536, 600}
    EXPECT_EQ(pieces(o), 3);
    o.slicing = Slicing::Uniform;
    o.slicing_lines = 5;
    EXPECT_EQ(pieces(o), 6);
}

// ---- The event grouping chosen from the exemplar (defaults on ordinary exemplars) ----

// Five exemplars of scripts/synth_exemplars.py, each with its events closer together than
// the seed's 0.2 W: that grouping leaves each of them one piece, which cannot make one
// component along a long curve.
class Defaults : public ::testing::TestWithParam<std::string> {};

TEST_P(Defaults, SucceedWithTheRequestedTopology) {
    const Curves ex = exemplar(GetParam());
    for (bool closed : {false, true}) {
        const Curves curve = closed ? Polyline(circle({0, 0}, 1600 / (2 * pi)), true) : Polyline(wave(1500, 60));
        SynthesisReport rep;
        const Curves out = SynthesizeAlongCurve(ex, curve, 40, SynthesisOptions{}, &rep);
        EXPECT_EQ(intersections(out), 0);
        const Topo t = count(out);
        EXPECT_TRUE(t.oriented);
        EXPECT_EQ(t.components, 1) << (closed ? "closed" : "open");
        EXPECT_EQ(t.holes, rep.holes);
        EXPECT_GT(rep.pieces_in_result, 2);
        // The seed's grouping was tried first and refused; a finer one was kept.
        EXPECT_GE(rep.groupings_tried, 2);
        EXPECT_LT(rep.event_grouping, 0.2);
        // Typed back in as the option, the chosen grouping gives the same pattern.
        SynthesisOptions o;
        o.event_grouping = rep.event_grouping;
        EXPECT_EQ(bytes(SynthesizeAlongCurve(ex, curve, 40, o)), bytes(out));
    }
    // The seed's grouping, asked for explicitly, still refuses, naming the grouping that works.
    SynthesisOptions seed;
    seed.event_grouping = 0.2;
    try {
        SynthesizeAlongCurve(ex, Polyline(wave(1500, 60)), 40, seed);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("exemplar's 1 pieces gives 1 component"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("; event_grouping=0.0"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("leave event_grouping unset"), std::string::npos) << e.what();
    }
}

INSTANTIATE_TEST_SUITE_P(Synthesis, Defaults,
                         ::testing::Values("synth_rungs", "synth_bar_beads", "synth_rings", "synth_truss", "synth_dots"));

TEST(Synthesis, DefaultsMeetHoleAndComponentCounts) {
    // Counts other than the default request, with the grouping still chosen automatically.
    struct Ask {
        const char* name;
        std::optional<int> components, holes;
    };
    for (const Ask& a : {Ask{"synth_rungs", 1, 20}, Ask{"synth_rings", 1, 40}, Ask{"synth_truss", 1, 30},
                         Ask{"synth_dots", std::nullopt, std::nullopt}, Ask{"synth_bar_beads", 1, 0}}) {
        SynthesisOptions o;
        o.components = a.components;
        o.holes = a.holes;
        SynthesisReport rep;
        const Curves out = SynthesizeAlongCurve(exemplar(a.name), Polyline(wave(1500, 60)), 40, o, &rep);
        EXPECT_EQ(intersections(out), 0) << a.name;
        const Topo t = count(out);
        if (a.components) EXPECT_EQ(t.components, *a.components) << a.name;
        if (a.holes) EXPECT_EQ(t.holes, *a.holes) << a.name;
        EXPECT_EQ(t.components, rep.components) << a.name;
        EXPECT_EQ(t.holes, rep.holes) << a.name;
    }
}

TEST(Synthesis, TheSeedsGroupingIsKeptWhereItWorks) {
    // The project's ladder makes one component at 0.2 W: unset, the option gives the same
    // pieces and the same bytes as 0.2, with no other grouping tried.
    const Curves curve = Polyline(wave(1500, 60));
    SynthesisOptions seed;
    seed.event_grouping = 0.2;
    SynthesisReport automatic, explicit_;
    const std::string a = bytes(SynthesizeAlongCurve(exemplar("synth_ladder"), curve, 40, SynthesisOptions{}, &automatic));
    const std::string b = bytes(SynthesizeAlongCurve(exemplar("synth_ladder"), curve, 40, seed, &explicit_));
    EXPECT_EQ(a, b);
    EXPECT_EQ(automatic.event_grouping, 0.2);
    EXPECT_EQ(automatic.groupings_tried, 1);
    EXPECT_EQ(automatic.pieces_in_exemplar, 3);
    EXPECT_EQ(explicit_.groupings_tried, 1);
    // An explicit grouping is used as given, even where another would make more pieces.
    SynthesisOptions fine_grouping;
    fine_grouping.event_grouping = 0.03;
    SynthesisReport f;
    SynthesizeAlongCurve(exemplar("synth_ladder"), curve, 40, fine_grouping, &f);
    EXPECT_EQ(f.pieces_in_exemplar, 7);
    EXPECT_EQ(f.event_grouping, 0.03);
}

TEST(Synthesis, ErrorsNameWhatToChange) {
    auto message = [](const Curves& ex, const SynthesisOptions& o) {
        try {
            SynthesizeAlongCurve(ex, Polyline(wave(2000, 10)), 40, o);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    auto has = [](const std::string& m, const std::string& word) {
        EXPECT_NE(m.find(word), std::string::npos) << "'" << word << "' not in: " << m;
    };
    // A band running straight through (a zig-zag strip): events only at its ends, so no
    // grouping cuts it; uniform slicing does.
    std::vector<Point> top, ring;
    for (int i = 0; i <= 30; ++i) top.push_back({20.0 * i, 10.0 * (i % 2) + 5});
    for (const Point& p : top) ring.push_back(p - Point{0, 8});
    ring.insert(ring.end(), top.rbegin(), top.rend());
    const std::string zigzag = message(Polyline(ring, true), SynthesisOptions{});
    has(zigzag, "no event_grouping can cut it");
    has(zigzag, "slicing=uniform (slicing_lines=8) meets it");
    // Automatic groupings all tried on a ladder asked for no hole (every ladder has one).
    SynthesisOptions no_hole;
    no_hole.holes = 0;
    const std::string ladder = message(exemplar("synth_ladder"), no_hole);
    has(ladder, "no sequence of the exemplar's 3 to ");
    has(ladder, "pieces (event_grouping 0.2 to ");
    has(ladder, "gives 1 component(s), 0 hole(s)");
    has(ladder, "try slicing=uniform");
    // An explicit grouping too coarse for the exemplar: the error gives one that works.
    SynthesisOptions coarse;
    coarse.event_grouping = 0.2;
    has(message(exemplar("synth_vine"), coarse), "; event_grouping=0.07 meets it");
    // Not in (0, 1]: named, with the way back to the automatic choice.
    for (double bad : {0.0, -0.1, 1.5, std::nan("")}) {
        SynthesisOptions o;
        o.event_grouping = bad;
        has(message(exemplar("synth_vine"), o), "event_grouping must be in (0, 1] or unset");
    }
}

TEST(Synthesis, ThinPortalFilterDropsCutsThroughTheString) {
    // The beads' string is 3 of the exemplar's 34 units: 3.5 at a band of 40. Cutting only
    // where portals are wider leaves fewer pieces.
    SynthesisOptions o = fine(std::nullopt, std::nullopt);
    o.slicing = Slicing::Uniform;
    o.slicing_lines = 20;
    SynthesisReport with, without;
    SynthesizeAlongCurve(exemplar("synth_beads"), Polyline(wave(1500, 40)), 40, o, &without);
    o.thin_portal = 5;
    const Curves out = SynthesizeAlongCurve(exemplar("synth_beads"), Polyline(wave(1500, 40)), 40, o, &with);
    EXPECT_LT(with.pieces_in_exemplar, without.pieces_in_exemplar);
    EXPECT_EQ(intersections(out), 0);
}

TEST(Synthesis, Rectangle) {
    SynthesisOptions o = fine(1, std::nullopt);
    const Curves out = SynthesizeInRectangle(exemplar("synth_ladder"), 600, 400, 60, o);
    EXPECT_EQ(intersections(out), 0);
    const Topo t = count(out);
    EXPECT_EQ(t.components, 1);
    EXPECT_TRUE(t.oriented);
    const BBox b = out.bbox();
    EXPECT_GE(b.ymin, 0);
    EXPECT_LE(b.ymax, 400);
    EXPECT_GT(b.height(), 0.9 * 400);
    // The second pass lays the strip across the whole width as its band: the pattern fills
    // [0, 600] exactly (to rounding), as it fills [0, 400] but for the end margins.
    EXPECT_NEAR(b.xmin, 0, 1e-9);
    EXPECT_NEAR(b.xmax, 600, 1e-9);
    EXPECT_GT(b.width(), 0.9 * 600);
}

// ---- Requests that cannot be met, and bad input ----

TEST(Synthesis, ImpossibleRequestIsAnError) {
    // Two separate discs: one component cannot be as long as the curve.
    try {
        SynthesizeAlongCurve(exemplar("synth_two_blobs"), Polyline(wave(2000, 10)), 40, fine(1, std::nullopt));
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.op(), "SynthesizeAlongCurve");
        EXPECT_NE(std::string(e.what()).find("1 component"), std::string::npos) << e.what();
    }
    // Both ends of the ladder join its rails: every ladder pattern has a hole.
    EXPECT_THROW(SynthesizeAlongCurve(exemplar("synth_ladder"), Polyline(wave(1200, 10)), 40, fine(1, 0)), Error);
    // A pattern with no hole cannot go all the way round a circle.
    SynthesisOptions o = fine(1, 0);
    o.closed_pattern = true;
    EXPECT_THROW(SynthesizeAlongCurve(exemplar("synth_ladder"), Polyline(circle({0, 0}, 300), true), 40, o), Error);
}

TEST(Synthesis, ACurveTooTightForTheBandIsAnError) {
    // A circle of radius 15 under a band of 40: the pattern would fold over the centre.
    SynthesisOptions o = fine(std::nullopt, std::nullopt);
    try {
        SynthesizeAlongCurve(exemplar("synth_ladder"), Polyline(circle({0, 0}, 15), true), 40, o);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("turns too tightly"), std::string::npos) << e.what();
    }
    // A sharp corner of a polyline, on the side the pattern faces.
    const Curves corner = Polyline({{0, 0}, {300, 0}, {300, 12}, {0, 12}});
    EXPECT_THROW(SynthesizeAlongCurve(exemplar("synth_ladder"), corner, 40, o), Error);
}

TEST(Synthesis, BadInputIsAnError) {
    const Curves ex = exemplar("synth_vine");
    const Curves line = Polyline({{0, 0}, {100, 0}});
    auto fails = [&](auto f, const std::string& word) {
        try {
            f();
            ADD_FAILURE() << "expected an error about " << word;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
        }
    };
    fails([&] { SynthesizeAlongCurve(ex, line, 0); }, "band_height");
    fails([&] { SynthesizeAlongCurve(ex, line, std::nan("")); }, "band_height");
    fails([&] { SynthesizeAlongCurve(Polyline({{0, 0}, {1, 1}}), line, 10); }, "no closed curve");
    fails([&] { SynthesizeAlongCurve(ex, Curves{}, 10); }, "exactly one polyline");
    fails([&] { SynthesizeAlongCurve(ex, Polyline({{0, 0}, {0, 0}}), 10); }, "too few distinct points");
    fails([&] { SynthesizeAlongCurve(ex, Polyline({{0, 0}, {5, 0}}, true), 10); }, "too few distinct points");
    SynthesisOptions o;
    o.components = 0;
    fails([&] { SynthesizeAlongCurve(ex, line, 10, o); }, "components");
    o = {};
    o.holes = -1;
    fails([&] { SynthesizeAlongCurve(ex, line, 10, o); }, "holes");
    o = {};
    o.closed_pattern = true;
    fails([&] { SynthesizeAlongCurve(ex, line, 10, o); }, "closed_pattern");
    o = {};
    o.slicing = Slicing::Uniform;
    o.slicing_lines = 0;
    fails([&] { SynthesizeAlongCurve(ex, line, 10, o); }, "slicing_lines");
    o = {};
    o.autocorrelation = -1;
    fails([&] { SynthesizeAlongCurve(ex, line, 10, o); }, "autocorrelation");
    // Crossing outlines are not polygons with holes.
    Curves bowtie = Polyline({{0, 0}, {10, 10}, {10, 0}, {0, 20}}, true);
    fails([&] { SynthesizeAlongCurve(bowtie, line, 10); }, "cross");
    fails([&] { SynthesizeInRectangle(ex, -1, 10, 5); }, "width");
}
