// Publishing (issue 42): the georeferenced PDF (true scale, a layer per family, the families'
// widths on paper, the page) and the vector tiles (each zoom level its own drawing, one tile
// layer per family, a folder or an MBTiles file), read back through GDAL.
#include <cpl_conv.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "carto/error.hpp"
#include "carto/publish.hpp"
#include "carto/raster.hpp"

#include "scratch.hpp"

using namespace carto;
namespace fs = std::filesystem;

namespace {

using rh_test::fresh_dir;

std::string bytes(const fs::path& p) { return rh_test::file_bytes(p); }

// A drawing 1 km x 500 m in Lambert-93 (100 x 50 mm at 1:10000): `n` short fill strokes
// and one ridge stroke.
Drawing drawing(int n, double scale = 10000) {
    Drawing d;
    d.crs_wkt = epsg_wkt(2154);
    d.style = "test";
    d.scale = scale;
    FaceHatches f{7, {}};
    for (int i = 0; i < n; ++i) {
        const double x = 1000000.0 + 10 + (980.0 * i) / std::max(1, n - 1);
        f.hatches.push_back({{{x, 6500100}, {x + 3, 6500400}}, false, Family::Fill});
    }
    f.hatches.push_back({{{1000100, 6500250}, {1000900, 6500260}}, false, Family::Ridge});
    d.faces.push_back(f);
    d.bounds = {1000000, 6500000, 1001000, 6500500};
    return d;
}

// The line widths a PDF's page content sets ("<w> w"), from its Flate streams.
std::set<double> line_widths(const fs::path& pdf) {
    const std::string b = bytes(pdf);
    std::set<double> widths;
    std::size_t at = 0;
    while ((at = b.find("stream", at)) != std::string::npos) {
        std::size_t start = at + 6;
        if (b.compare(start, 2, "\r\n") == 0) start += 2;
        else if (b[start] == '\n') start += 1;
        else {
            at = start;
            continue;
        }
        const std::size_t end = b.find("endstream", start);
        if (end == std::string::npos) break;
        std::size_t out_size = 0;
        void* raw = CPLZLibInflate(b.data() + start, end - start, nullptr, 0, &out_size);
        if (raw) {
            const std::string text(static_cast<char*>(raw), out_size);
            VSIFree(raw);
            static const std::regex w(R"(([0-9.]+) w\n)");
            for (auto it = std::sregex_iterator(text.begin(), text.end(), w); it != std::sregex_iterator(); ++it)
                widths.insert(std::stod((*it)[1]));
        }
        at = end + 9;  // past "endstream"
    }
    return widths;
}

struct Closer {
    void operator()(GDALDataset* d) const { GDALClose(d); }
};
using Ds = std::unique_ptr<GDALDataset, Closer>;

Ds open(const fs::path& p, unsigned flags, const std::vector<std::string>& oo = {}) {
    std::vector<const char*> opts;
    for (const auto& o : oo) opts.push_back(o.c_str());
    opts.push_back(nullptr);
    return Ds(static_cast<GDALDataset*>(GDALOpenEx(p.c_str(), flags | GDAL_OF_READONLY, nullptr, opts.data(), nullptr)));
}

}  // namespace

TEST(Page, NamesIsoSizesAndSizesInMillimetres) {
    const PageSize a3 = parse_page("a3");
    EXPECT_EQ(a3.name, "A3");
    EXPECT_EQ(a3.width_mm, 297);
    EXPECT_EQ(a3.height_mm, 420);
    const PageSize custom = parse_page("700x500");
    EXPECT_EQ(custom.width_mm, 500);  // portrait: the shorter side first
    EXPECT_EQ(custom.height_mm, 700);
    for (const char* bad : {"A9", "", "x", "10x", "0x10", "-5x10", "10x10mm", "9000x10"}) {
        try {
            parse_page(bad);
            ADD_FAILURE() << bad << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), Code::Usage);
            EXPECT_NE(std::string(e.what()).find("--page"), std::string::npos) << e.what();
        }
    }
}

TEST(Pdf, IsGeoreferencedAtTrueScaleWithALayerAndTheWidthOfEachFamily) {
    GDALAllRegister();
    const fs::path dir = fresh_dir("publish_pdf");
    const Drawing d = drawing(40);
    write_pdf(d, (dir / "map.pdf").string());
    // Read as a raster at 72 dpi, a pixel is a PDF unit: the page is the frame at 1:10000
    // (100 x 50 mm), and the pixel's ground size is that of a point at that scale.
    Ds ds = open(dir / "map.pdf", GDAL_OF_RASTER, {"DPI=72"});
    ASSERT_TRUE(ds);
    EXPECT_NEAR(ds->GetRasterXSize(), 100 * 72 / 25.4, 1.0);
    EXPECT_NEAR(ds->GetRasterYSize(), 50 * 72 / 25.4, 1.0);
    double gt[6];
    ASSERT_EQ(ds->GetGeoTransform(gt), CE_None);
    const double ground_per_point = 25.4 / 72 / 1000 * 10000;
    EXPECT_NEAR(gt[0], 1000000, ground_per_point);
    EXPECT_NEAR(gt[3], 6500500, ground_per_point);
    EXPECT_NEAR(gt[1] * ds->GetRasterXSize(), 1000, 1e-3 * 1000);  // the frame's width, within the page's rounding
    const OGRSpatialReference* crs = ds->GetSpatialRef();
    ASSERT_TRUE(crs);
    EXPECT_STREQ(crs->GetAuthorityCode(nullptr), "2154");
    // One optional-content layer per family the drawing has (the rock families always).
    std::set<std::string> layers;
    for (char** m = ds->GetMetadata("LAYERS"); m && *m; ++m) layers.insert(std::string(*m).substr(std::string(*m).find('=') + 1));
    EXPECT_EQ(layers, (std::set<std::string>{"fill", "ridge", "valley", "cross"}));
    // The strokes are the families' widths on paper: 0.10 mm and 0.12 mm are 0.2835 and 0.3402
    // PDF units.
    const std::set<double> widths = line_widths(dir / "map.pdf");
    for (Family f : {Family::Fill, Family::Ridge, Family::Valley, Family::Cross})
        EXPECT_TRUE(std::any_of(widths.begin(), widths.end(), [&](double w) {
            return std::abs(w - pdf_line_width(family_width_mm(f))) < 1e-4;
        })) << family_name(f);
    EXPECT_EQ(widths.size(), 4u);
    // Nothing left beside it (the GeoPackage and composition it was made from).
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(Pdf, CentresTheDrawingOnAPageTurnedToFitAndRefusesOneTooSmall) {
    GDALAllRegister();
    const fs::path dir = fresh_dir("publish_pdf_page");
    const Drawing d = drawing(10);
    // 100 x 50 mm on A5 (148 x 210): fits upright; on 60x120 only turned.
    write_pdf(d, (dir / "a5.pdf").string(), parse_page("A5"));
    Ds a5 = open(dir / "a5.pdf", GDAL_OF_RASTER, {"DPI=72"});
    ASSERT_TRUE(a5);
    EXPECT_NEAR(a5->GetRasterXSize(), 148 * 72 / 25.4, 1.0);
    EXPECT_NEAR(a5->GetRasterYSize(), 210 * 72 / 25.4, 1.0);
    double gt[6];
    ASSERT_EQ(a5->GetGeoTransform(gt), CE_None);
    // The page's left edge is (148 - 100) / 2 = 24 mm, 240 m at 1:10000, left of the frame.
    EXPECT_NEAR(gt[0], 1000000 - 240, 1.0);
    EXPECT_NEAR(gt[3], 6500500 + (210 - 50) / 2.0 * 10, 1.0);
    write_pdf(d, (dir / "turned.pdf").string(), parse_page("60x120"));
    Ds turned = open(dir / "turned.pdf", GDAL_OF_RASTER, {"DPI=72"});
    ASSERT_TRUE(turned);
    EXPECT_GT(turned->GetRasterXSize(), turned->GetRasterYSize());
    try {
        write_pdf(d, (dir / "small.pdf").string(), parse_page("40x90"));
        ADD_FAILURE() << "a page smaller than the drawing accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::Usage);
        EXPECT_NE(std::string(e.what()).find("100 x 50 mm"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "small.pdf"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(Pdf, SameDrawingSameBytes) {
    const fs::path dir = fresh_dir("publish_pdf_bytes");
    fs::create_directories(dir / "again");
    write_pdf(drawing(30), (dir / "map.pdf").string());
    write_pdf(drawing(30), (dir / "again" / "map.pdf").string());
    EXPECT_EQ(bytes(dir / "map.pdf"), bytes(dir / "again" / "map.pdf"));
}

TEST(ZoomLevels, ScaleHalvesPerLevelAndShrinksWithLatitude) {
    // OGC's well-known scale set: zoom 13 at the equator is 1:68,247.
    EXPECT_NEAR(zoom_scale(13, 0), 68247.3, 1.0);
    EXPECT_NEAR(zoom_scale(16, 0), 8530.9, 0.5);
    EXPECT_NEAR(zoom_scale(12, 45.9) / zoom_scale(13, 45.9), 2.0, 1e-12);
    EXPECT_NEAR(zoom_scale(13, 60) / zoom_scale(13, 0), 0.5, 1e-12);
    const ZoomRange r = parse_zoom_range("12-16");
    EXPECT_EQ(r.min, 12);
    EXPECT_EQ(r.max, 16);
    EXPECT_EQ(parse_zoom_range("14").max, 14);
    for (const char* bad : {"16-12", "23", "0-23", "a", "-3", "12-", "1.5"}) {
        try {
            parse_zoom_range(bad);
            ADD_FAILURE() << bad << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), Code::Usage);
            EXPECT_NE(std::string(e.what()).find("--zoom"), std::string::npos);
        }
    }
}

TEST(VectorTiles, EachZoomLevelShowsItsOwnDrawing) {
    GDALAllRegister();
    const fs::path dir = fresh_dir("publish_tiles");
    // Zoom 14 drawn with 10 strokes, zoom 15 with 60: as a run draws each level at its scale.
    write_gpkg(drawing(10), (dir / "z14.gpkg").string(), false);
    write_gpkg(drawing(60), (dir / "z15.gpkg").string(), false);
    const std::vector<ZoomDrawing> levels{{14, (dir / "z14.gpkg").string()}, {15, (dir / "z15.gpkg").string()}};
    const TileStats s = write_vector_tiles(levels, (dir / "rock.mbtiles").string(), "test");
    EXPECT_GT(s.tiles, 0u);
    EXPECT_LE(s.largest, 500000u);
    EXPECT_EQ(s.features, 10u + 1 + 60 + 1);
    EXPECT_EQ(mbtiles_stats((dir / "rock.mbtiles").string()).tiles, s.tiles);
    for (const auto& [zoom, strokes] : {std::pair{14, 10}, std::pair{15, 60}}) {
        Ds ds = open(dir / "rock.mbtiles", GDAL_OF_VECTOR, {"ZOOM_LEVEL=" + std::to_string(zoom)});
        ASSERT_TRUE(ds);
        // How the levels were drawn, for the page that shows them.
        ASSERT_TRUE(ds->GetMetadataItem("pixel_mm"));
        EXPECT_STREQ(ds->GetMetadataItem("pixel_mm"), "0.28");
        EXPECT_STREQ(ds->GetMetadataItem("tile_px"), "256");
        OGRLayer* fill = ds->GetLayerByName("fill");
        ASSERT_TRUE(fill) << "zoom " << zoom;
        ASSERT_TRUE(ds->GetLayerByName("ridge"));
        // A stroke cut by a tile's edge is in both tiles (in two pieces): between the level's
        // stroke count and twice it.
        int count = 0;
        for (auto& f : *fill) {
            EXPECT_DOUBLE_EQ(f->GetFieldAsDouble("width_mm"), family_width_mm(Family::Fill));
            EXPECT_EQ(f->GetFieldAsInteger64("face_id"), 7);
            ++count;
        }
        EXPECT_GE(count, strokes) << "zoom " << zoom;
        EXPECT_LE(count, 2 * strokes) << "zoom " << zoom;
    }
    // A folder of z/x/y.pbf tiles, written as the MVT driver reads it back.
    write_vector_tiles(levels, (dir / "folder/").string(), "test");
    EXPECT_TRUE(fs::exists(dir / "folder" / "metadata.json"));
    EXPECT_TRUE(fs::is_directory(dir / "folder" / "15"));
    // Replacing a folder that is not one of tiles is refused.
    fs::create_directories(dir / "mine");
    std::ofstream(dir / "mine" / "notes.txt") << "keep";
    EXPECT_THROW(write_vector_tiles(levels, (dir / "mine").string(), "test"), Error);
    EXPECT_TRUE(fs::exists(dir / "mine" / "notes.txt"));
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".part-"), std::string::npos) << e.path();
}
