// Outputs (issue 17): no output onto an input or onto another output, however spelt, and the
// GDAL settings of a write (timestamp, SQLite journal, quiet errors) scoped to the call, so
// that a host program (QGIS, a user's Python) keeps its own.
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "carto/error.hpp"
#include "carto/output.hpp"
#include "carto/raster.hpp"

#include "scratch.hpp"

using namespace carto;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = rh_test::fresh_dir(name);
    fs::create_directories(dir / "sub");
    return dir;
}

std::string bytes(const fs::path& p) { return rh_test::file_bytes(p); }

// The message of the OutputExists error check_outputs throws (nullopt when it accepts).
std::optional<std::string> refusal(const std::vector<FileArg>& in, const std::vector<FileArg>& out) {
    try {
        check_outputs(in, out, true);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::OutputExists) << e.what();
        return std::string(e.what());
    }
    return std::nullopt;
}

Drawing small_drawing(std::size_t hatches) {
    Drawing d;
    d.crs_wkt = epsg_wkt(2154);
    d.style = "test";
    FaceHatches f{1, {}};
    for (std::size_t i = 0; i < hatches; ++i)
        f.hatches.push_back({{{1000000.0 + double(i), 6500000}, {1000000.5 + double(i), 6500001}}, false, Family::Fill});
    d.faces.push_back(f);
    d.bounds = {1000000, 6500000, 1000000 + double(hatches) + 1, 6500001};
    return d;
}

const char* const kKeys[] = {"OGR_CURRENT_DATE", "OGR_SQLITE_JOURNAL", "OGR_SQLITE_SYNCHRONOUS", "CPL_LOG"};

// Every option carto sets, as the process (global) and this thread see it.
std::vector<std::string> settings() {
    std::vector<std::string> v;
    for (const char* k : kKeys) {
        const char* g = CPLGetConfigOption(k, nullptr);
        const char* t = CPLGetThreadLocalConfigOption(k, nullptr);
        v.push_back(std::string(k) + "=" + (g ? g : "<unset>") + "/" + (t ? t : "<unset>"));
    }
    return v;
}

int g_host_errors = 0;
void host_handler(CPLErr, CPLErrorNum, const char*) { ++g_host_errors; }

}  // namespace

TEST(CheckOutputs, RefusesAnInputHoweverItIsSpelt) {
    const fs::path dir = fresh_dir("spelt");
    const fs::path input = dir / "faces.gpkg";
    std::ofstream(input) << "the user's partition";
    fs::create_symlink(input, dir / "link.gpkg");
    fs::create_hard_link(input, dir / "hard.gpkg");
    const std::string in = input.string();
    for (const std::string out : {in, (dir / "." / "faces.gpkg").string(), (dir / "sub" / ".." / "faces.gpkg").string(),
                                  (dir / "link.gpkg").string(), (dir / "hard.gpkg").string()}) {
        const auto msg = refusal({{"--dem", (dir / "none.tif").string()}, {"--partition", in}}, {{"-o", out}});
        ASSERT_TRUE(msg) << out;
        EXPECT_NE(msg->find("-o '" + out + "'"), std::string::npos) << *msg;
        EXPECT_NE(msg->find("--partition '" + in + "'"), std::string::npos) << *msg;
        EXPECT_EQ(msg->find('\n'), std::string::npos);
    }
    // A relative spelling, from the folder of the input.
    const fs::path cwd = fs::current_path();
    fs::current_path(dir / "sub");
    EXPECT_TRUE(refusal({{"--script", "../faces.gpkg"}}, {{"-o", "./../sub/../faces.gpkg"}}));
    fs::current_path(cwd);
    EXPECT_EQ(bytes(input), "the user's partition");
}

TEST(CheckOutputs, RefusesTwoOutputsThatAreOneFile) {
    const fs::path dir = fresh_dir("twice");
    const std::string a = (dir / "out.svg").string(), b = (dir / "sub" / ".." / "out.svg").string();
    const auto msg = refusal({}, {{"-o", a}, {"-o", b}});
    ASSERT_TRUE(msg);
    EXPECT_NE(msg->find(a), std::string::npos);
    EXPECT_NE(msg->find(b), std::string::npos);
    // An existing output and a link to it.
    std::ofstream(a) << "old";
    fs::create_symlink(a, dir / "link.svg");
    EXPECT_TRUE(refusal({}, {{"-o", a}, {"--png", (dir / "link.svg").string()}}));
}

TEST(CheckOutputs, AcceptsOtherFilesAndLeavesMissingInputsToTheirReader) {
    const fs::path dir = fresh_dir("other");
    std::ofstream(dir / "dem.tif") << "dem";
    const std::string dem = (dir / "dem.tif").string();
    EXPECT_FALSE(refusal({{"--dem", dem}, {"--slope", ""}, {"--partition", (dir / "missing.gpkg").string()}},
                         {{"-o", (dir / "missing.gpkg").string()}, {"-o", (dir / "out.svg").string()}, {"--png", ""}}));
    // Without --overwrite an existing output is still refused, named by its option.
    try {
        check_outputs({}, {{"--png", dem}}, false);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("--png '" + dem + "': the file exists", 0), 0u) << e.what();
    }
}

TEST(GdalSettings, WriteGpkgPutsBackTheHostsOptionsAndErrorHandler) {
    GDALAllRegister();
    const fs::path dir = fresh_dir("settings");
    // The host's own values, globally and on this thread.
    CPLSetConfigOption("OGR_SQLITE_JOURNAL", "WAL");
    CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", "2024-05-06T07:08:09.000Z");
    CPLPushErrorHandler(host_handler);
    const std::vector<std::string> before = settings();

    const std::string path = (dir / "h.gpkg").string();
    write_gpkg(small_drawing(3), path);
    EXPECT_EQ(settings(), before);
    // The fixed timestamp still reaches the file (the same run writes the same bytes).
    {
        std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
        ASSERT_TRUE(ds);
        OGRLayer* rs = ds->ExecuteSQL("SELECT DISTINCT last_change FROM gpkg_contents", nullptr, nullptr);
        ASSERT_TRUE(rs);
        std::unique_ptr<OGRFeature> f(rs->GetNextFeature());
        ASSERT_TRUE(f);
        EXPECT_STREQ(f->GetFieldAsString(0), "2000/01/01 00:00:00+00");  // OGR_CURRENT_DATE, as OGR reads it
        ds->ReleaseResultSet(rs);
    }
    const std::string first = bytes(path);
    write_gpkg(small_drawing(3), (dir / "again.gpkg").string());
    EXPECT_EQ(bytes(dir / "again.gpkg"), first);

    // Cancelled in the middle of the write: the same, and nothing left behind.
    EXPECT_THROW(write_gpkg(small_drawing(5000), (dir / "c.gpkg").string(), true, [](double) { return false; }),
                 Error);
    EXPECT_FALSE(fs::exists(dir / "c.gpkg"));
    EXPECT_EQ(settings(), before);
    // A failed read (no such raster) leaves CPL_LOG and the handler too.
    EXPECT_THROW(read_raster((dir / "none.tif").string(), "--dem"), Error);
    EXPECT_EQ(settings(), before);

    // The host's handler is still the one GDAL calls.
    const int errors = g_host_errors;
    CPLError(CE_Warning, CPLE_AppDefined, "a message of the host");
    EXPECT_EQ(g_host_errors, errors + 1);
    CPLPopErrorHandler();
    CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", nullptr);
    CPLSetConfigOption("OGR_SQLITE_JOURNAL", nullptr);
}

// A hatch GeoPackage keeps its drawing's frame, which can be larger than its hatches (the
// faces' extent, the DEM's for a terrain style); an SVG drawn back from it, or from tiles
// merged into one, has that frame, exactly: a tiled run's SVG is framed as the whole run's.
TEST(HatchGpkg, KeepsTheDrawingsFrameThroughReadAndMerge) {
    const fs::path dir = fresh_dir("frame");
    Drawing a = small_drawing(3), b = small_drawing(2);
    a.bounds = {999999.875, 6499998.1, 1000010.3, 6500003.7};  // beyond the hatches on every side
    b.faces[0].face_id = 2;
    for (auto& h : b.faces[0].hatches)
        for (auto& p : h.points) p.y += 50;
    b.bounds = {1000000, 6500040.25, 1000004, 6500090.5};
    write_gpkg(a, (dir / "a.gpkg").string());
    write_gpkg(b, (dir / "b.gpkg").string());
    const Drawing ra = read_gpkg((dir / "a.gpkg").string(), 10000);
    EXPECT_EQ(ra.bounds.xmin, a.bounds.xmin);
    EXPECT_EQ(ra.bounds.ymin, a.bounds.ymin);
    EXPECT_EQ(ra.bounds.xmax, a.bounds.xmax);
    EXPECT_EQ(ra.bounds.ymax, a.bounds.ymax);
    write_svg(a, (dir / "a.svg").string());
    write_svg(ra, (dir / "ra.svg").string());
    EXPECT_EQ(bytes(dir / "ra.svg"), bytes(dir / "a.svg"));

    EXPECT_EQ(merge_gpkg({(dir / "a.gpkg").string(), (dir / "b.gpkg").string()}, (dir / "m.gpkg").string()), 5u);
    const Drawing m = read_gpkg((dir / "m.gpkg").string(), 10000);
    EXPECT_EQ(m.bounds.xmin, 999999.875);
    EXPECT_EQ(m.bounds.ymin, 6499998.1);
    EXPECT_EQ(m.bounds.xmax, 1000010.3);
    EXPECT_EQ(m.bounds.ymax, 6500090.5);

    // A file without the frame (an older version's): the hatches' extent, as before.
    {
        std::unique_ptr<GDALDataset> ds(GDALDataset::Open((dir / "b.gpkg").string().c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE));
        ASSERT_TRUE(ds);
        ASSERT_NE(ds->GetMetadataItem("RH_FRAME"), nullptr);
        ds->SetMetadataItem("RH_FRAME", nullptr);
    }
    const Drawing rb = read_gpkg((dir / "b.gpkg").string(), 10000);
    EXPECT_EQ(rb.bounds.xmin, 1000000.0);
    EXPECT_EQ(rb.bounds.ymin, 6500050.0);
    EXPECT_EQ(rb.bounds.xmax, 1000001.5);
    EXPECT_EQ(rb.bounds.ymax, 6500051.0);
}
