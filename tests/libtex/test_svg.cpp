// ImportSVG / ExportSVG (table 3.6).
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <random>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "helpers.hpp"

#include "scratch.hpp"

using namespace tex;

TEST(ImportSVG, ElementsAndLabelledPoints) {
    const Curves c = ParseSVG(R"svg(<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape">
      <g transform="translate(10,0)">
        <line x1="0" y1="0" x2="10" y2="0"/>
        <polyline points="0,10 10,10 10,20"/>
        <polygon points="0,30 10,30 10,40"/>
        <rect x="0" y="50" width="4" height="2"/>
        <circle cx="0" cy="0" r="5"/>
        <circle data-label="start" cx="1" cy="2" r="1"/>
        <ellipse inkscape:label="end" cx="3" cy="4" rx="1" ry="2"/>
        <path data-label="body" d="M0,0 h5 v5 z"/>
      </g>
    </svg>)svg");
    ASSERT_EQ(c.curves.size(), 6u);
    EXPECT_EQ(c.curves[0].points.front(), Point(10, 0));
    EXPECT_EQ(c.curves[0].points.back(), Point(20, 0));
    EXPECT_FALSE(c.curves[1].closed);
    EXPECT_TRUE(c.curves[2].closed);
    EXPECT_NEAR(th::length(Curves{{c.curves[3]}, {}, ""}), 12, 1e-12);
    EXPECT_NEAR(th::length(Curves{{c.curves[4]}, {}, ""}), 2 * pi * 5, 0.05);
    EXPECT_EQ(PointLabeled(c, "start"), Point(11, 2));
    EXPECT_EQ(PointLabeled(c, "end"), Point(13, 4));
    EXPECT_TRUE(c.curves[5].closed);
    EXPECT_EQ(CurveLabeled(c, "body").curves.size(), 1u);
}

TEST(ImportSVG, BezierCurvesAreFlattenedCloseToTheCurve) {
    // A quarter circle as an arc and as a cubic: both end where they should and stay near
    // radius 100.
    const Curves a = ParseSVG(R"svg(<svg><path d="M100,0 A100,100 0 0 1 0,100"/></svg>)svg");
    const Curves b = ParseSVG(R"svg(<svg><path d="M100,0 C100,55.2285 55.2285,100 0,100"/></svg>)svg");
    for (const Curves* c : {&a, &b}) {
        ASSERT_EQ(c->curves.size(), 1u);
        const auto& pts = c->curves[0].points;
        EXPECT_GT(pts.size(), 8u);
        EXPECT_NEAR(pts.front().x, 100, 1e-9);
        EXPECT_NEAR(pts.back().y, 100, 1e-9);
        for (const auto& p : pts) EXPECT_NEAR(norm(p), 100, 0.1);
        EXPECT_NEAR(th::length(*c), pi * 50, 0.5);
    }
    // Relative commands, smooth continuations and quadratic curves.
    const Curves s = ParseSVG(R"svg(<svg><path d="m0,0 c10,-10 20,-10 30,0 s20,10 30,0 q15,15 30,0 t30,0 l10,0"/></svg>)svg");
    EXPECT_NEAR(s.curves[0].points.back().x, 130, 1e-9);
    EXPECT_NEAR(s.curves[0].points.back().y, 0, 1e-9);
}

TEST(ImportSVG, ErrorsNameTheFile) {
    EXPECT_TEX_ERROR(ImportSVG("/nonexistent/zig.svg"), "ImportSVG", "'/nonexistent/zig.svg': cannot open");
    EXPECT_TEX_ERROR(ParseSVG("<svg><path d='M0,0 L1,1'>", "broken.svg"), "'broken.svg'", "not well-formed");
    EXPECT_TEX_ERROR(ParseSVG("<html/>", "page.svg"), "page.svg", "root element");
    EXPECT_TEX_ERROR(ParseSVG("<svg><path d='M0,0 X1,1'/></svg>", "bad.svg"), "bad.svg", "unknown path command 'X'");
    EXPECT_TEX_ERROR(ParseSVG("<svg></svg>", "empty.svg"), "empty.svg", "no curve");
    const Curves c = ParseSVG("<svg><line x1='0' y1='0' x2='1' y2='0'/></svg>", "zig.svg");
    EXPECT_TEX_ERROR(PointLabeled(c, "start"), "no point labelled 'start'", "'zig.svg'");
}

TEST(ExportSVG, DeterministicAtomicOutput) {
    const std::string path = rh_test::scratch("grid.svg"), again = rh_test::scratch("grid_again.svg");
    auto grid = [] { return GridPartition(StripesProperties(0.1, 33), StripesProperties(1.7, 41), CROP_ADD_BOUNDARY); };
    auto read = [](const std::string& file) {
        std::ifstream in(file, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    const Arrangement a = grid();
    const Curves written = ExportSVG(a, 500, path);
    const std::string text = read(path);
    // Deterministic: the same arrangement, built again from scratch and written to another
    // file, gives the same bytes.
    ExportSVG(grid(), 500, again);
    EXPECT_EQ(read(again), text);
    EXPECT_NE(text.find("viewBox=\"0 0 500 500\""), std::string::npos);
    EXPECT_EQ(text.find("-0,"), std::string::npos);
    // Atomic: no temporary file is left behind.
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
    EXPECT_FALSE(std::filesystem::exists(again + ".tmp"));
    // The exported file imports back to the curves written, point for point, each coordinate
    // to the three decimals the file holds (within half a thousandth, and a little rounding).
    const Curves back = ImportSVG(path);
    ASSERT_EQ(back.curves.size(), written.curves.size());
    ASSERT_GT(written.curves.size(), 10u);
    for (std::size_t i = 0; i < written.curves.size(); ++i) {
        const auto &p = back.curves[i].points, &q = written.curves[i].points;
        EXPECT_EQ(back.curves[i].closed, written.curves[i].closed) << "curve " << i;
        ASSERT_EQ(p.size(), q.size()) << "curve " << i;
        for (std::size_t k = 0; k < p.size(); ++k) {
            EXPECT_NEAR(p[k].x, q[k].x, 5e-4 + 1e-9) << "curve " << i << ", point " << k;
            EXPECT_NEAR(p[k].y, q[k].y, 5e-4 + 1e-9) << "curve " << i << ", point " << k;
        }
    }
    EXPECT_TEX_ERROR(ExportSVG(a, 500, (rh_test::scratch_dir() / "missing_dir" / "x.svg").string()), "ExportSVG",
                     "cannot write");
}

namespace {

// A 300 x 300 square frame with a 100 x 100 square hole, drawn as an SVG would be.
Curves square_frame_with_hole() {
    return ParseSVG(R"svg(<svg><rect x="100" y="100" width="300" height="300"/>
        <rect x="200" y="200" width="100" height="100"/>
        <line x1="0" y1="0" x2="50" y2="50"/></svg>)svg", "frame.svg");
}

bool near_boundary(const Point& p, const Region& r, double eps) {
    auto near_ring = [&](const std::vector<Point>& ring) {
        for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
            const Point a = ring[j], b = ring[i], d = b - a;
            const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
            if (distance(p, a + d * t) <= eps) return true;
        }
        return false;
    };
    if (near_ring(r.outer())) return true;
    for (const auto& h : r.holes())
        if (near_ring(h)) return true;
    return false;
}

}  // namespace

TEST(ExportSVGinDomain, FrameRegionTakesTheLargestRingAndItsHoles) {
    const Region r = FrameRegion(square_frame_with_hole());
    EXPECT_DOUBLE_EQ(r.area(), 300.0 * 300 - 100.0 * 100);
    EXPECT_EQ(r.holes().size(), 1u);
    EXPECT_TRUE(r.contains({150, 150}));
    EXPECT_FALSE(r.contains({250, 250}));
    EXPECT_FALSE(r.contains({50, 50}));
}

TEST(ExportSVGinDomain, CutsToTheFrameAndDrawsIt) {
    const Curves frame = square_frame_with_hole();
    const Region r = FrameRegion(frame);
    const Arrangement a = GridPartition(StripesProperties(0.3, 17), StripesProperties(1.9, 23), KEEP_OUTSIDE);
    const Curves c = EvaluateInDomain(a, frame);
    // The frame's two rings come last, as the region's boundary.
    ASSERT_GE(c.curves.size(), 3u);
    const Curves rings = r.boundary();
    for (std::size_t k = 0; k < 2; ++k) {
        const Curve& got = c.curves[c.curves.size() - 2 + k];
        EXPECT_TRUE(got.closed);
        EXPECT_EQ(got.points, rings.curves[k].points);
    }
    // Nothing lies outside the frame or in its hole: every point and every segment's
    // midpoint is inside the region (or on its boundary, up to rounding).
    BBox texture_box;
    for (std::size_t i = 0; i + 2 < c.curves.size(); ++i) {
        const auto& pts = c.curves[i].points;
        for (std::size_t k = 0; k < pts.size(); ++k) {
            texture_box.add(pts[k]);
            EXPECT_TRUE(r.contains(pts[k]) || near_boundary(pts[k], r, 1e-6)) << pts[k].x << "," << pts[k].y;
            if (k + 1 < pts.size()) {
                const Point m = (pts[k] + pts[k + 1]) / 2;
                EXPECT_TRUE(r.contains(m) || near_boundary(m, r, 1e-6)) << m.x << "," << m.y;
            }
        }
    }
    // The texture fills the frame: its pieces reach the frame on every side.
    EXPECT_NEAR(texture_box.xmin, 100, 1e-6);
    EXPECT_NEAR(texture_box.ymin, 100, 1e-6);
    EXPECT_NEAR(texture_box.xmax, 400, 1e-6);
    EXPECT_NEAR(texture_box.ymax, 400, 1e-6);
}

TEST(ExportSVGinDomain, InDomainIgnoresTheWindowAndMergeKeepsBothInputs) {
    const Curves frame = square_frame_with_hole();
    const Arrangement a = GridPartition(StripesProperties(0.3, 17), StripesProperties(1.9, 23), KEEP_OUTSIDE);
    const std::string expected = ToSVG(EvaluateInDomain(a, frame), 500);
    EXPECT_EQ(ToSVG(InDomain(a, frame)(Region::rectangle(0, 0, 500, 500)), 500), expected);
    EXPECT_EQ(ToSVG(InDomain(a, frame)(Region::rectangle(300, 300, 310, 310)), 500), expected);
    const Arrangement b = StripesPartition(StripesProperties(1.0, 40));
    const Region w = Region::rectangle(0, 0, 500, 500);
    // Merging keeps every curve of both inputs: as many curves as the two together, as long.
    const Curves ca = a(w), cb = b(w), merged = Merge(a, b)(w);
    ASSERT_GT(ca.curves.size(), 0u);
    ASSERT_GT(cb.curves.size(), 0u);
    EXPECT_EQ(merged.curves.size(), ca.curves.size() + cb.curves.size());
    EXPECT_NEAR(th::length(merged), th::length(ca) + th::length(cb), 1e-9 * th::length(merged));
}

TEST(ExportSVGinDomain, WritesTheFilledFrameWithAViewBoxAroundIt) {
    const std::string path = rh_test::scratch("filled.svg");
    const Curves frame = square_frame_with_hole();
    const Arrangement a = GridPartition(StripesProperties(0.3, 17), StripesProperties(1.9, 23), KEEP_OUTSIDE);
    const Curves written = ExportSVGinDomain(a, frame, path, 10);
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    BBox view;
    view.add(Point{90, 90});
    view.add(Point{410, 410});
    EXPECT_EQ(text, ToSVG(written, view));
    EXPECT_NE(text.find("width=\"320\" height=\"320\" viewBox=\"90 90 320 320\""), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
    EXPECT_EQ(ToSVG(written, 500), ToSVG(EvaluateInDomain(a, frame), 500));
    EXPECT_TEX_ERROR(ExportSVGinDomain(a, frame, path, -1), "ExportSVGinDomain", "margin");
}

TEST(ExportSVGinDomain, AFrameWithoutAClosedCurveIsAnError) {
    const Arrangement a = StripesPartition(StripesProperties(0.0, 20));
    const Curves open = ParseSVG("<svg><path d='M0,0 L100,0 L100,100'/></svg>", "open.svg");
    EXPECT_TEX_ERROR(EvaluateInDomain(a, open), "ExportSVGinDomain", "'open.svg' has no closed curve");
    EXPECT_TEX_ERROR(ExportSVGinDomain(a, open, "/tmp/never_written.svg"), "ExportSVGinDomain", "no closed curve");
    EXPECT_TEX_ERROR(InDomain(a, open), "InDomain", "no closed curve");
    EXPECT_FALSE(std::filesystem::exists("/tmp/never_written.svg"));
    // A closed curve outside the largest one: a frame bounds one region.
    const Curves two = ParseSVG("<svg><rect x='0' y='0' width='100' height='100'/>"
                                "<rect x='200' y='0' width='50' height='50'/></svg>", "two.svg");
    EXPECT_TEX_ERROR(EvaluateInDomain(a, two), "ExportSVGinDomain", "outside its largest one");
}

TEST(ImportSVG, FaceLabelsGoOnTheInsideOfClosedCurves) {
    // A rect (drawn clockwise on screen), the same polygon run the other way, a mirrored
    // circle, and an open path whose face label is ignored.
    const Curves c = ParseSVG(R"svg(<svg>
        <rect x="0" y="0" width="100" height="100" data-face-label="ship"/>
        <polygon points="300,0 300,100 200,100 200,0" data-face-label="ship"/>
        <g transform="scale(-1,1)"><circle cx="-450" cy="50" r="40" data-face-label="chip"/></g>
        <path d="M0,300 L100,300 L100,400" data-face-label="wire"/>
        </svg>)svg");
    ASSERT_EQ(c.curves.size(), 4u);
    EXPECT_TRUE(c.curves[3].left.empty() && c.curves[3].right.empty());
    const MapPtr m = PlanarMap::induce(c);
    int ships = 0, chips = 0;
    for (std::size_t i = 0; i < m->faces().size(); ++i) {
        const Face f(m, int(i));
        if (m->faces()[i].unbounded) {
            EXPECT_FALSE(HasLabel(f, "ship") || HasLabel(f, "chip") || HasLabel(f, "wire"));
            continue;
        }
        const Point p = Centroid(f);
        if (HasLabel(f, "ship")) {
            ++ships;
            EXPECT_LT(p.x, 300);
        }
        if (HasLabel(f, "chip")) {
            ++chips;
            EXPECT_NEAR(p.x, 450, 1);
        }
    }
    EXPECT_EQ(ships, 2);
    EXPECT_EQ(chips, 1);
}

// fuzz/fuzz_svg: an arc whose radius dwarfs the flattening tolerance made the number of
// pieces +inf before it became an int (undefined behaviour: UBSan's float-cast-overflow
// in scripts/sanitize.sh and scripts/fuzz.sh). The arc is flattened in at most 256 pieces.
TEST(ImportSVG, AHugeArcRadiusGivesABoundedNumberOfPieces) {
    const Curves c = ParseSVG("<svg><path d='M0,0 L40,0 A10 1e199 30 1 0 50 50'/></svg>", "arc.svg");
    ASSERT_EQ(c.curves.size(), 1u);
    EXPECT_LE(c.curves[0].points.size(), 2u + 256u);
    EXPECT_EQ(c.curves[0].points.back(), (Point{50, 50}));
    const Curves e = ParseSVG("<svg><circle cx='0' cy='0' r='1e300'/><line x1='0' y1='0' x2='1' y2='1'/></svg>", "c.svg");
    EXPECT_EQ(e.curves.size(), 2u);
}

// fuzz/fuzz_svg: NaN and infinite coordinates ("nan", "inf", 1e999, or finite numbers that
// overflow in a transform) reached the curves, and from them the exact planar maps. They
// are refused with an error naming the file.
TEST(ImportSVG, CoordinatesThatAreNotFiniteAreRefused) {
    EXPECT_TEX_ERROR(ParseSVG("<svg><path d='M0,0 L nan,1 L1,1'/></svg>", "n.svg"), "n.svg", "not a finite number");
    EXPECT_TEX_ERROR(ParseSVG("<svg><polyline points='0,0 1e999,1'/></svg>", "i.svg"), "i.svg", "not a finite number");
    EXPECT_TEX_ERROR(ParseSVG("<svg><line x1='inf' y1='0' x2='1' y2='0'/></svg>", "l.svg"), "l.svg", "x1 'inf'");
    EXPECT_TEX_ERROR(ParseSVG("<svg><g transform='scale(1e300)'><rect x='1e10' y='0' width='1' height='1'/></g></svg>",
                              "t.svg"),
                     "t.svg", "out of range once transformed");
    EXPECT_TEX_ERROR(ParseSVG("<svg><circle cx='1e308' cy='0' r='1' data-label='start' transform='scale(10)'/></svg>",
                              "p.svg"),
                     "p.svg", "out of range once transformed");
}

// The export's number formatting must write the bytes std::to_chars (fixed, three decimals)
// writes, trimmed: SVG outputs are compared byte for byte across versions.
namespace {
std::string reference_number(double v) {
    char buf[400];
    if (std::abs(v) < 5e-4 || !std::isfinite(v)) v = 0;
    const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 3);
    std::size_t n = std::size_t(res.ptr - buf);
    while (n > 0 && buf[n - 1] == '0') --n;
    if (n > 0 && buf[n - 1] == '.') --n;
    return std::string(buf, n);
}
std::string fast_number(double v) {
    std::string s;
    append_svg_number(s, v);
    return s;
}
}  // namespace

TEST(SvgNumber, SameTextAsToCharsEverywhere) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> expo(-5, 17), unit(0, 1);
    std::size_t checked = 0;
    for (int i = 0; i < 2'000'000; ++i) {
        const double mag = std::pow(10.0, expo(rng));
        const double v = (unit(rng) < 0.5 ? -1 : 1) * mag * unit(rng);
        ASSERT_EQ(fast_number(v), reference_number(v)) << std::hexfloat << v;
        ++checked;
    }
    // Exact ties at the fourth decimal (k / 16, k / 2048), their neighbours, the 5e-4 cut,
    // powers of two around the fallback, special values.
    for (long k = -40000; k <= 40000; ++k)
        for (double v : {k / 16.0, k / 2048.0, 1e6 + k / 16.0, k * 0.0005, k * 0.001}) {
            for (double w : {v, std::nextafter(v, -1e300), std::nextafter(v, 1e300)})
                ASSERT_EQ(fast_number(w), reference_number(w)) << std::hexfloat << w;
            checked += 3;
        }
    for (int e = -12; e <= 70; ++e)
        for (double f : {1.0, 1.5, 0.9999999999, 1.0000000001}) {
            const double v = std::ldexp(f, e);
            ASSERT_EQ(fast_number(v), reference_number(v)) << std::hexfloat << v;
            ASSERT_EQ(fast_number(-v), reference_number(-v)) << std::hexfloat << -v;
        }
    for (double v : {0.0, -0.0, 5e-4, -5e-4, 4.9999e-4, 1e300, -1e300, std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::denorm_min()})
        EXPECT_EQ(fast_number(v), reference_number(v)) << v;
    EXPECT_EQ(fast_number(1e300).size(), 301u);
    EXPECT_EQ(fast_number(0.0625), reference_number(0.0625));  // a tie: half to even
    EXPECT_EQ(fast_number(12.3456), "12.346");
    EXPECT_EQ(fast_number(-2.5), "-2.5");
    EXPECT_EQ(fast_number(7.0), "7");
    EXPECT_GT(checked, 2'000'000u);
}
