// ImportSVG / ExportSVG (table 3.6).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "helpers.hpp"

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
    const auto dir = std::filesystem::temp_directory_path() / "libtex_svg_test";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "grid.svg").string();
    const Arrangement a = GridPartition(StripesProperties(0.1, 33), StripesProperties(1.7, 41), CROP_ADD_BOUNDARY);
    ExportSVG(a, 500, path);
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, ToSVG(a(Region::rectangle(0, 0, 500, 500)), 500));
    EXPECT_NE(text.find("viewBox=\"0 0 500 500\""), std::string::npos);
    EXPECT_EQ(text.find("-0,"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
    // The exported file imports back to the same number of curves.
    EXPECT_EQ(ImportSVG(path).curves.size(), a(Region::rectangle(0, 0, 500, 500)).curves.size());
    EXPECT_TEX_ERROR(ExportSVG(a, 500, (dir / "missing_dir" / "x.svg").string()), "ExportSVG", "cannot write");
    std::filesystem::remove_all(dir);
}
