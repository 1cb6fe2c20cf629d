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

const char* const kKeys[] = {"OGR_CURRENT_DATE", "OGR_SQLITE_JOURNAL", "OGR_SQLITE_SYNCHRONOUS", "OGR_SQLITE_PRAGMA",
                             "CPL_LOG"};

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

// The page size of a GeoPackage, as SQLite reports it.
int page_size(const std::string& path) {
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
    if (!ds) return -1;
    OGRLayer* rs = ds->ExecuteSQL("PRAGMA page_size", nullptr, nullptr);
    if (!rs) return -1;
    std::unique_ptr<OGRFeature> f(rs->GetNextFeature());
    const int n = f ? f->GetFieldAsInteger(0) : -1;
    ds->ReleaseResultSet(rs);
    return n;
}

// A run's GeoPackage has SQLite's largest pages (its rows go in with a sixteenth of the page
// writes); a page size the host asks for wins, and the host's setting is left as it was.
TEST(GdalSettings, AGpkgIsWrittenInLargePagesUnlessTheHostAsksOtherwise) {
    GDALAllRegister();
    const fs::path dir = fresh_dir("pages");
    const std::string plain = (dir / "plain.gpkg").string();
    write_gpkg(small_drawing(300), plain);
    EXPECT_EQ(page_size(plain), 65536);
    // The index and the rows read back whole from the large pages.
    {
        std::unique_ptr<GDALDataset> ds(GDALDataset::Open(plain.c_str(), GDAL_OF_VECTOR));
        ASSERT_TRUE(ds);
        OGRLayer* fill = ds->GetLayerByName("hatch_fill");
        ASSERT_TRUE(fill);
        EXPECT_EQ(fill->GetFeatureCount(), 300);
        fill->SetSpatialFilterRect(1000010.2, 6500000, 1000012.2, 6500001);
        EXPECT_EQ(fill->GetFeatureCount(), 3);  // the hatches starting at x + 10, 11, 12 (GDAL also checks the geometry)
    }
    CPLSetConfigOption("OGR_SQLITE_PRAGMA", "page_size=8192");
    const std::vector<std::string> before = settings();
    const std::string host = (dir / "host.gpkg").string();
    write_gpkg(small_drawing(300), host);
    EXPECT_EQ(page_size(host), 8192);
    EXPECT_EQ(settings(), before);
    CPLSetConfigOption("OGR_SQLITE_PRAGMA", nullptr);
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

namespace {

// Every row of a table as text (hex of the geometry blob, the fields), in fid order, and
// what GDAL keeps of the table (extent, feature count), read through GDAL's SQL.
std::vector<std::string> table_rows(GDALDataset& ds, const std::string& table, const std::string& columns) {
    std::vector<std::string> rows;
    OGRLayer* rs = ds.ExecuteSQL(("SELECT " + columns + " FROM \"" + table + "\" ORDER BY fid").c_str(), nullptr, nullptr);
    if (!rs) return {"no table " + table};
    for (auto& f : *rs) {
        std::string row;
        for (int i = 0; i < f->GetFieldCount(); ++i) row += std::string(f->GetFieldAsString(i)) + "|";
        rows.push_back(row);
    }
    ds.ReleaseResultSet(rs);
    for (const char* sql : {"SELECT printf('%!.17g %!.17g %!.17g %!.17g', min_x, min_y, max_x, max_y) FROM gpkg_contents",
                            "SELECT feature_count FROM gpkg_ogr_contents"}) {
        OGRLayer* meta = ds.ExecuteSQL((std::string(sql) + " WHERE table_name = '" + table + "'").c_str(), nullptr, nullptr);
        if (!meta) return {"no metadata of " + table};
        for (auto& f : *meta) rows.push_back(std::string("meta ") + f->GetFieldAsString(0));
        ds.ReleaseResultSet(meta);
    }
    return rows;
}

// An empty drawing in Lambert 93 by the style "test".
Drawing test_drawing() {
    GDALAllRegister();
    Drawing d;
    d.crs_wkt = epsg_wkt(2154);
    d.style = "test";
    return d;
}

std::unique_ptr<OGRLineString> ogr_line(const std::vector<Point>& pts, bool ring) {
    std::unique_ptr<OGRLineString> l(ring ? new OGRLinearRing() : new OGRLineString());
    for (const Point& p : pts) l->addPoint(p.x, p.y);
    return l;
}

}  // namespace

// The rows carto inserts itself (SQLite statements, blobs it encodes) are those GDAL writes
// for the same features: the same blob bytes (header, flags, envelope, WKB), fields, extent
// and feature count; and OGR reads every point back exactly.
TEST(HatchGpkg, RowsAreTheBlobsAndFieldsGdalWrites) {
    const fs::path dir = fresh_dir("blobs");
    Drawing d = test_drawing();
    const std::vector<Point> line{{1000000.1234567891, 6500000.000000001}, {1000000.5 + 1.0 / 3, 6500001.7}, {999999.25, 6500003}};
    const std::vector<Point> ring{{1000010, 6500010}, {1000012.1, 6500010}, {1000011, 6500012.3}};
    const std::vector<Point> stone{{1000020, 6500020}, {1000021, 6500020}, {1000021, 6500021}};
    d.faces.push_back({7, {{line, false, Family::Fill},
                           {ring, true, Family::Fill},          // closed: the first point repeated
                           {{{1000005, 6500005}}, false, Family::Ridge},  // one point: no feature
                           {{{1000006, 6500006}}, true, Family::Ridge},   // closed: two points
                           {line, false, Family::Cliff}}});    // a family drawn by some styles only
    d.faces.push_back({3, {{stone, true, Family::Stone}, {ring, false, Family::Ridge}, {line, false, Family::Fill}}});
    d.crests = std::vector<CrestOrnament>{{0, 42, {{{1000030, 6500030}, {1000034, 6500030}, {1000034, 6500034}, {1000030, 6500034}},
                                                   {{1000031, 6500031}, {1000031, 6500032}, {1000032, 6500032}}}}};
    d.fingerprints = Fingerprints{{{"version", "v"}}, {{7, "a"}, {3, "b"}}};
    d.bounds = {999999, 6500000, 1000040, 6500040};
    const std::string mine = (dir / "mine.gpkg").string();
    write_gpkg(d, mine, false);

    // The same features written by GDAL's own driver, feature by feature.
    const std::string ref = (dir / "gdal.gpkg").string();
    {
        std::unique_ptr<GDALDataset> ds(GetGDALDriverManager()->GetDriverByName("GPKG")->Create(ref.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        ASSERT_TRUE(ds);
        OGRSpatialReference srs;
        srs.importFromWkt(d.crs_wkt.c_str());
        srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        const char* lco[] = {"SPATIAL_INDEX=NO", "FID=fid", "GEOMETRY_NAME=geom", nullptr};
        for (Family fam : {Family::Fill, Family::Ridge, Family::Stone, Family::Cliff}) {
            OGRLayer* l = ds->CreateLayer((std::string("hatch_") + family_name(fam)).c_str(), &srs,
                                          family_filled(fam) ? wkbPolygon : wkbLineString, const_cast<char**>(lco));
            ASSERT_TRUE(l);
            for (auto [name, type] : {std::pair{"face_id", OFTInteger64}, {"family", OFTString}, {"style", OFTString}, {"width_mm", OFTReal}}) {
                OGRFieldDefn fd(name, type);
                l->CreateField(&fd);
            }
            for (const auto& face : d.faces)
                for (const auto& h : face.hatches) {
                    if (h.family != fam) continue;
                    std::vector<Point> pts = h.points;
                    if (h.closed) pts.push_back(pts.front());
                    if (pts.size() < 2) continue;
                    OGRFeature f(l->GetLayerDefn());
                    f.SetField(0, GIntBig(face.face_id));
                    f.SetField(1, family_name(fam));
                    f.SetField(2, "test");
                    f.SetField(3, family_width_mm(fam));
                    if (family_filled(fam)) {
                        auto* poly = new OGRPolygon();
                        poly->addRingDirectly(static_cast<OGRLinearRing*>(ogr_line(pts, true).release()));
                        f.SetGeometryDirectly(poly);
                    } else {
                        f.SetGeometryDirectly(ogr_line(pts, false).release());
                    }
                    ASSERT_EQ(l->CreateFeature(&f), OGRERR_NONE);
                }
        }
        OGRLayer* c = ds->CreateLayer("crest", &srs, wkbPolygon, const_cast<char**>(lco));
        OGRFieldDefn id("ridge_id", OFTInteger64), style("style", OFTString);
        c->CreateField(&id);
        c->CreateField(&style);
        OGRFeature f(c->GetLayerDefn());
        f.SetField(0, GIntBig(42));
        f.SetField(1, "test");
        auto* poly = new OGRPolygon();
        for (const auto& r : (*d.crests)[0].rings) {
            std::vector<Point> pts = r;
            pts.push_back(r.front());
            poly->addRingDirectly(static_cast<OGRLinearRing*>(ogr_line(pts, true).release()));
        }
        f.SetGeometryDirectly(poly);
        ASSERT_EQ(c->CreateFeature(&f), OGRERR_NONE);
    }
    std::unique_ptr<GDALDataset> a(GDALDataset::Open(mine.c_str(), GDAL_OF_VECTOR));
    std::unique_ptr<GDALDataset> b(GDALDataset::Open(ref.c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(a && b);
    const std::string hatch_cols = "hex(geom), face_id, family, style, printf('%!.17g', width_mm)";
    for (const char* t : {"hatch_fill", "hatch_ridge", "hatch_stone", "hatch_cliff"}) {
        const auto rows = table_rows(*a, t, hatch_cols);
        EXPECT_EQ(rows, table_rows(*b, t, hatch_cols)) << t;
        EXPECT_GE(rows.size(), 3u) << t;
    }
    EXPECT_EQ(table_rows(*a, "crest", "hex(geom), ridge_id, style"), table_rows(*b, "crest", "hex(geom), ridge_id, style"));
    EXPECT_EQ(table_rows(*a, "rockhatch_faces", "face_id, fingerprint"),
              (std::vector<std::string>{"7|a|", "3|b|", "meta 0.0 0.0 0.0 0.0", "meta 2"}));  // no extent (NULL)
    // hatch_valley and hatch_cross are written empty (the rock families always are); no other.
    EXPECT_EQ(a->GetLayerCount(), 8);
    EXPECT_EQ(a->GetLayerByName("hatch_cross")->GetFeatureCount(), 0);
    EXPECT_FALSE(a->GetLayerByName("hatch_hachure"));

    // OGR reads the points back exactly, face by face.
    OGRLayer* fill = a->GetLayerByName("hatch_fill");
    std::vector<std::vector<Point>> got;
    for (auto& f : *fill) {
        const OGRLineString* ls = f->GetGeometryRef()->toLineString();
        std::vector<Point>& pts = got.emplace_back();
        for (int i = 0; i < ls->getNumPoints(); ++i) pts.push_back({ls->getX(i), ls->getY(i)});
    }
    std::vector<Point> closed = ring;
    closed.push_back(ring.front());
    ASSERT_EQ(got.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
        const std::vector<Point>& want = k == 1 ? closed : line;
        ASSERT_EQ(got[k].size(), want.size());
        for (std::size_t i = 0; i < want.size(); ++i) {
            EXPECT_EQ(got[k][i].x, want[i].x);
            EXPECT_EQ(got[k][i].y, want[i].y);
        }
    }
}

namespace {

// The first value of the first row of an SQL query through GDAL (SQLite's functions and
// GDAL's spatial ones), as text.
std::string sql_value(GDALDataset& ds, const std::string& sql) {
    OGRLayer* rs = ds.ExecuteSQL(sql.c_str(), nullptr, "SQLITE");
    if (!rs) return "no result for " + sql;
    std::unique_ptr<OGRFeature> f(rs->GetNextFeature());
    const std::string v = f ? f->GetFieldAsString(0) : "no row";
    ds.ReleaseResultSet(rs);
    return v;
}

}  // namespace

// The R-tree of a layer with many rows is written while they go in, a chunk of rows at a
// time, and its top levels at the end: it must be a valid index of every row (rtreecheck),
// each row under a box that holds its geometry, and a window search missing none.
TEST(HatchGpkg, TheSpatialIndexWrittenAsTheRowsGoInIndexesEveryRow) {
    const fs::path dir = fresh_dir("rtree");
    Drawing d = test_drawing();
    // 120 faces of 1,000 short strokes in a row (120,000 fill rows: several chunks and a last
    // partial one), and a few ridge rows (a layer small enough to be packed at the end).
    for (int k = 0; k < 120; ++k) {
        FaceHatches face{k + 1, {}};
        const double x0 = 1000000 + 400.0 * (k % 12), y0 = 6500000 + 400.0 * (k / 12);
        for (int i = 0; i < 1000; ++i) {
            const double x = x0 + 12.0 * (i % 30), y = y0 + 11.0 * (i / 30);
            face.hatches.push_back({{{x, y}, {x + 3 + 0.001 * i, y + 7}}, false, Family::Fill});
        }
        if (k % 10 == 0) face.hatches.push_back({{{x0, y0}, {x0 + 100, y0}}, false, Family::Ridge});
        d.faces.push_back(std::move(face));
    }
    d.bounds = {1000000, 6500000, 1005000, 6504400};
    const std::string path = (dir / "many.gpkg").string();
    write_gpkg(d, path, true);
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(ds);
    for (const char* t : {"hatch_fill", "hatch_ridge"}) {
        const std::string rtree = std::string("rtree_") + t + "_geom";
        EXPECT_EQ(sql_value(*ds, "SELECT rtreecheck('" + rtree + "')"), "ok") << t;
        EXPECT_EQ(sql_value(*ds, "SELECT count(*) FROM " + rtree), sql_value(*ds, std::string("SELECT count(*) FROM ") + t)) << t;
        // Every row under its own box, and that box holds the row's geometry.
        EXPECT_EQ(sql_value(*ds, std::string("SELECT count(*) FROM ") + t + " h JOIN " + rtree +
                                     " r ON r.id = h.fid WHERE r.minx <= ST_MinX(h.geom) AND r.maxx >= ST_MaxX(h.geom) "
                                     "AND r.miny <= ST_MinY(h.geom) AND r.maxy >= ST_MaxY(h.geom)"),
                  sql_value(*ds, std::string("SELECT count(*) FROM ") + t))
            << t;
    }
    EXPECT_EQ(sql_value(*ds, "SELECT count(*) FROM hatch_fill"), "120000");
    // A window search through the index misses none of the rows that meet the window (its
    // boxes are floats rounded outwards: it may find a few more).
    for (const auto& corner : {std::pair{1000250.0, 6500250.0}, {1002013.0, 6503170.0}, {1004500.0, 6503700.0}}) {
        const double x = corner.first, y = corner.second;
        auto within = [&](const std::string& minx, const std::string& maxx, const std::string& miny,
                          const std::string& maxy) {
            return maxx + " >= " + std::to_string(x) + " AND " + minx + " <= " + std::to_string(x + 300) + " AND " + maxy +
                   " >= " + std::to_string(y) + " AND " + miny + " <= " + std::to_string(y + 300);
        };
        const std::string meets = within("ST_MinX(geom)", "ST_MaxX(geom)", "ST_MinY(geom)", "ST_MaxY(geom)");
        const std::string by_rows = sql_value(*ds, "SELECT count(*) FROM hatch_fill WHERE " + meets);
        const std::string found = sql_value(*ds, "SELECT count(*) FROM hatch_fill WHERE " + meets +
                                                     " AND fid IN (SELECT id FROM rtree_hatch_fill_geom WHERE " +
                                                     within("minx", "maxx", "miny", "maxy") + ")");
        EXPECT_EQ(found, by_rows) << x << " " << y;
        EXPECT_NE(by_rows, "0") << x << " " << y;
    }
    // The tree has levels above its leaves (the leaves of several chunks under one root).
    EXPECT_NE(sql_value(*ds, "SELECT count(*) FROM rtree_hatch_fill_geom_parent"), "0");
}
