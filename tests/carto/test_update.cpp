// rockhatch update on the sample: a run keeps one fingerprint per face; an update redraws
// exactly the faces whose inputs changed, with the bytes a whole run writes, leaves every
// other feature (hand edits included) as it is, and refuses a file of another style.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogrsf_frmts.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "carto/error.hpp"
#include "carto/output.hpp"
#include "carto/pipeline.hpp"
#include "carto/update.hpp"

#include "scratch.hpp"

using namespace carto;
namespace fs = std::filesystem;

namespace {

struct TempDir {
    fs::path path;
    TempDir() {
        path = rh_test::scratch_dir() / "update";
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    std::string operator/(const std::string& name) const { return (path / name).string(); }
};

Options sample_options(const std::string& partition, const std::string& out) {
    Options o;
    o.dem = std::string(RH_SAMPLE_DIR) + "/dem.tif";
    o.partition.path = partition;
    o.threads = 2;
    o.outputs = {out};
    o.overwrite = true;
    return o;
}

// Every feature of the hatch layers: fid -> (layer, face id, style, geometry WKB).
using Feature = std::tuple<std::string, std::int64_t, std::string, std::string>;
std::map<std::pair<std::string, GIntBig>, Feature> features(const std::string& path) {
    GDALAllRegister();
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
    std::map<std::pair<std::string, GIntBig>, Feature> out;
    for (OGRLayer* l : ds->GetLayers()) {
        const std::string name = l->GetName();
        if (name.rfind("hatch_", 0) != 0) continue;
        for (auto& f : *l) {
            std::string wkb(std::size_t(f->GetGeometryRef()->WkbSize()), '\0');
            f->GetGeometryRef()->exportToWkb(wkbNDR, reinterpret_cast<unsigned char*>(wkb.data()));
            out[{name, f->GetFID()}] = {name, f->GetFieldAsInteger64("face_id"), f->GetFieldAsString("style"), wkb};
        }
    }
    return out;
}

// The features of each face, as a sorted list (fids aside).
std::map<std::int64_t, std::multiset<Feature>> by_face(const std::map<std::pair<std::string, GIntBig>, Feature>& fs) {
    std::map<std::int64_t, std::multiset<Feature>> out;
    for (const auto& [key, f] : fs) out[std::get<1>(f)].insert(f);
    return out;
}

// Moves the first vertex of face `fid`'s outer ring by (dx, dy) in the partition file.
void move_vertex(const std::string& partition, GIntBig fid, double dx, double dy) {
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(partition.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE));
    OGRLayer* faces = ds->GetLayerByName("faces");
    std::unique_ptr<OGRFeature> f(faces->GetFeature(fid));
    ASSERT_TRUE(f);
    OGRPolygon* poly = f->GetGeometryRef()->toPolygon();
    OGRLinearRing* ring = poly->getExteriorRing();
    const int last = ring->getNumPoints() - 1;
    // The middle vertex: the ring's closing point stays as it is.
    const int k = last / 2;
    ring->setPoint(k, ring->getX(k) + dx, ring->getY(k) + dy);
    ASSERT_EQ(faces->SetFeature(f.get()), OGRERR_NONE);
}

}  // namespace

TEST(Update, RunKeepsOneFingerprintPerFaceAndAnUnchangedUpdateTouchesNothing) {
    TempDir dir;
    const std::string out = dir / "h.gpkg";
    const Stats s = run(sample_options(std::string(RH_SAMPLE_DIR) + "/partition.gpkg", out));
    const auto fp = read_fingerprints(out, "-o");
    ASSERT_TRUE(fp);
    EXPECT_EQ(fp->faces.size(), s.faces);
    // The version number and the digest of the drawing's sources: 0.1.0+ and 12 hex digits.
    const std::string version = fp->run.at("version"), number = std::string(RH_VERSION_STRING_TEST) + "+";
    EXPECT_EQ(version.rfind(number, 0), 0u) << version;
    EXPECT_EQ(version.size(), number.size() + 12) << version;
    EXPECT_EQ(version.find_first_not_of("0123456789abcdef", number.size()), std::string::npos) << version;
    EXPECT_EQ(fp->run.at("style"), "rock");
    const auto before = features(out);
    const UpdateReport r = update(sample_options(std::string(RH_SAMPLE_DIR) + "/partition.gpkg", out), {});
    EXPECT_EQ(r.faces, s.faces);
    EXPECT_EQ(r.redrawn, 0u);
    EXPECT_EQ(r.deleted, 0u);
    EXPECT_EQ(r.written, 0u);
    EXPECT_EQ(features(out), before);
}

TEST(Update, RedrawsTheEditedFacesAsAWholeRunAndKeepsHandEditsElsewhere) {
    TempDir dir;
    const std::string part = dir / "partition.gpkg", out = dir / "h.gpkg", whole = dir / "whole.gpkg";
    fs::copy_file(std::string(RH_SAMPLE_DIR) + "/partition.gpkg", part);
    run(sample_options(part, out));
    // A hand edit in some face: one of its features deleted.
    auto before = features(out);
    const auto first = before.begin();
    const std::int64_t hand_face = std::get<1>(first->second);
    {
        std::unique_ptr<GDALDataset> ds(GDALDataset::Open(out.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE));
        ASSERT_EQ(ds->GetLayerByName(first->first.first.c_str())->DeleteFeature(first->first.second), OGRERR_NONE);
    }
    before = features(out);
    // A face far from the hand edit is edited.
    const auto faces_before = by_face(before);
    std::int64_t edited = -1;
    for (auto it = faces_before.rbegin(); it != faces_before.rend(); ++it)
        if (it->first != hand_face && it->first > 0) {
            edited = it->first;
            break;
        }
    ASSERT_GT(edited, 0);
    move_vertex(part, edited, 3.0, -2.0);
    const UpdateReport r = update(sample_options(part, out), {});
    EXPECT_GE(r.redrawn, 1u);
    EXPECT_LT(r.redrawn, r.faces);
    const std::set<std::int64_t> redrawn(r.redrawn_ids.begin(), r.redrawn_ids.end());
    EXPECT_TRUE(redrawn.count(edited));
    EXPECT_GT(r.written, 0u);

    // Each redrawn face: the features of a whole run; every other: as before.
    run(sample_options(part, whole));
    const auto after = by_face(features(out)), full = by_face(features(whole));
    for (const auto& [face, fs] : full) {
        if (redrawn.count(face)) {
            EXPECT_EQ(after.at(face), fs) << "face " << face;
        } else if (faces_before.count(face)) {
            EXPECT_EQ(after.at(face), faces_before.at(face)) << "face " << face;
        }
    }
    if (!redrawn.count(hand_face)) EXPECT_EQ(after.at(hand_face).size(), full.at(hand_face).size() - 1);
    // The frame (the faces' boxes as drawn, the others' as the file kept them) is the run's.
    const tex::BBox fu = read_gpkg(out, 10000).bounds, fw = read_gpkg(whole, 10000).bounds;
    EXPECT_TRUE(fu.xmin == fw.xmin && fu.ymin == fw.ymin && fu.xmax == fw.xmax && fu.ymax == fw.ymax)
        << fu.xmin << " " << fu.ymin << " " << fu.xmax << " " << fu.ymax << " against " << fw.xmin << " " << fw.ymin
        << " " << fw.xmax << " " << fw.ymax;
    // The same update again: nothing to do.
    EXPECT_EQ(update(sample_options(part, out), {}).redrawn, 0u);
    // --reset: every face, the whole run's features.
    const UpdateReport all = update(sample_options(part, out), {true, {}});
    EXPECT_EQ(all.redrawn, all.faces);
    EXPECT_EQ(by_face(features(out)), full);
}

namespace {

// Adds `dz` to the cells of a raster file within `radius` cells of the cell holding (x, y)
// (in the raster's CRS).
void raise_cells(const std::string& path, double x, double y, int radius, float dz) {
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
    ASSERT_TRUE(ds);
    double gt[6];
    ds->GetGeoTransform(gt);
    const int c = int((x - gt[0]) / gt[1]), r = int((y - gt[3]) / gt[5]), side = 2 * radius + 1;
    std::vector<float> v(std::size_t(side) * side);
    GDALRasterBand* b = ds->GetRasterBand(1);
    ASSERT_EQ(b->RasterIO(GF_Read, c - radius, r - radius, side, side, v.data(), side, side, GDT_Float32, 0, 0), CE_None);
    for (float& z : v) z += dz;
    ASSERT_EQ(b->RasterIO(GF_Write, c - radius, r - radius, side, side, v.data(), side, side, GDT_Float32, 0, 0), CE_None);
}

}  // namespace

// A DEM in degrees (the sample's warped to EPSG:4326), as a user's often is: the fingerprints
// read its cells as the file holds them, the redrawn faces are drawn from a window of it. After
// a few cells are raised, the faces redrawn and every other one hold a whole run's bytes of
// the edited DEM (a face whose drawing changed and was not redrawn would differ), and faces
// far from the edit are left alone. With a PNG beside the file (the whole run's preparation)
// the same holds.
TEST(Update, ADemEditInDegreesRedrawsWhatItReachesWithAWholeRunsBytes) {
    TempDir dir;
    const std::string dem = dir / "dem_4326.tif", out = dir / "h.gpkg", whole = dir / "whole.gpkg";
    {
        GDALAllRegister();
        std::unique_ptr<GDALDataset> src(GDALDataset::Open((std::string(RH_SAMPLE_DIR) + "/dem.tif").c_str(), GDAL_OF_RASTER));
        ASSERT_TRUE(src);
        const char* args[] = {"-t_srs", "EPSG:4326", "-r", "bilinear", "-of", "GTiff", nullptr};
        GDALWarpAppOptions* wo = GDALWarpAppOptionsNew(const_cast<char**>(args), nullptr);
        GDALDatasetH in = GDALDataset::ToHandle(src.get());
        GDALDatasetH made = GDALWarp(dem.c_str(), nullptr, 1, &in, wo, nullptr);
        GDALWarpAppOptionsFree(wo);
        ASSERT_TRUE(made);
        GDALClose(made);
    }
    const std::string part = std::string(RH_SAMPLE_DIR) + "/partition.gpkg";
    Options o = sample_options(part, out);
    o.dem = dem;
    o.relief_radius = 40;  // a reach shorter than the sample, so that an edit leaves faces alone
    o.scale = 5000;
    run(o);
    const auto before = by_face(features(out));
    // Raise 5 x 5 cells at the middle of the DEM.
    {
        std::unique_ptr<GDALDataset> ds(GDALDataset::Open(dem.c_str(), GDAL_OF_RASTER));
        double gt[6];
        ds->GetGeoTransform(gt);
        const double x = gt[0] + gt[1] * ds->GetRasterXSize() / 2, y = gt[3] + gt[5] * ds->GetRasterYSize() / 2;
        ds.reset();
        raise_cells(dem, x, y, 2, 40.0f);
    }
    const UpdateReport r = update(o, {});
    EXPECT_GE(r.redrawn, 1u);
    EXPECT_LT(r.redrawn, r.faces);
    const std::set<std::int64_t> redrawn(r.redrawn_ids.begin(), r.redrawn_ids.end());
    Options w = o;
    w.outputs = {whole};
    run(w);
    const auto after = by_face(features(out)), full = by_face(features(whole));
    EXPECT_EQ(after, full);
    std::size_t changed = 0;
    for (const auto& [face, fs] : full) changed += before.count(face) && before.at(face) != fs;
    EXPECT_GT(changed, 0u);  // the edit did change some drawing
    for (const auto& [face, fs] : full)
        if (!redrawn.count(face)) EXPECT_EQ(before.at(face), fs) << "face " << face << " changed, not redrawn";

    // Again, a PNG beside the file.
    const std::string png = dir / "h.png";
    o.outputs = {out, png};
    update(o, {});
    {
        std::unique_ptr<GDALDataset> ds(GDALDataset::Open(dem.c_str(), GDAL_OF_RASTER));
        double gt[6];
        ds->GetGeoTransform(gt);
        const double x = gt[0] + gt[1] * ds->GetRasterXSize() / 3, y = gt[3] + gt[5] * ds->GetRasterYSize() / 3;
        ds.reset();
        raise_cells(dem, x, y, 2, -30.0f);
    }
    const UpdateReport again = update(o, {});
    EXPECT_GE(again.redrawn, 1u);
    EXPECT_TRUE(fs::exists(png));
    run(w);
    EXPECT_EQ(by_face(features(out)), by_face(features(whole)));
}

// The fingerprints digest the partition as digitised, the drawing reads it snapped: a vertex
// moved within the snap (0.5 m) of where it was changes the digitised faces, and the update's
// faces, redrawn from a snapped neighbourhood, and the others are a whole run's, frame included.
TEST(Update, AVertexMovedWithinTheSnapGivesAWholeRunsDrawing) {
    TempDir dir;
    const std::string part = dir / "partition.gpkg", out = dir / "h.gpkg", whole = dir / "whole.gpkg";
    fs::copy_file(std::string(RH_SAMPLE_DIR) + "/partition.gpkg", part);
    run(sample_options(part, out));
    const auto faces = by_face(features(out));
    const std::int64_t edited = std::next(faces.begin(), std::ptrdiff_t(faces.size() / 2))->first;
    move_vertex(part, edited, 0.3, -0.2);
    const UpdateReport r = update(sample_options(part, out), {});
    EXPECT_GE(r.redrawn, 1u);
    EXPECT_LT(r.redrawn, r.faces);
    run(sample_options(part, whole));
    EXPECT_EQ(by_face(features(out)), by_face(features(whole)));
    const tex::BBox fu = read_gpkg(out, 10000).bounds, fw = read_gpkg(whole, 10000).bounds;
    EXPECT_TRUE(fu.xmin == fw.xmin && fu.ymin == fw.ymin && fu.xmax == fw.xmax && fu.ymax == fw.ymax);
    EXPECT_EQ(update(sample_options(part, out), {}).redrawn, 0u);
}

TEST(Update, RemovedFacesLoseTheirFeaturesAndAskedFacesAreRedrawn) {
    TempDir dir;
    const std::string part = dir / "partition.gpkg", out = dir / "h.gpkg";
    fs::copy_file(std::string(RH_SAMPLE_DIR) + "/partition.gpkg", part);
    run(sample_options(part, out));
    const auto before = by_face(features(out));
    const std::int64_t gone = before.rbegin()->first;
    {
        std::unique_ptr<GDALDataset> ds(GDALDataset::Open(part.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE));
        ASSERT_EQ(ds->GetLayerByName("faces")->DeleteFeature(gone), OGRERR_NONE);
    }
    const std::int64_t asked = before.begin()->first;
    const UpdateReport r = update(sample_options(part, out), {false, {asked}});
    EXPECT_EQ(r.removed, 1u);
    EXPECT_EQ(r.removed_ids, std::vector<std::int64_t>{gone});
    const std::set<std::int64_t> redrawn(r.redrawn_ids.begin(), r.redrawn_ids.end());
    EXPECT_TRUE(redrawn.count(asked));
    const auto after = by_face(features(out));
    EXPECT_FALSE(after.count(gone));
    EXPECT_EQ(after.at(asked), before.at(asked));  // same inputs: same bytes
    // An unknown face is refused by name.
    try {
        update(sample_options(part, out), {false, {999999}});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::Usage);
        EXPECT_NE(std::string(e.what()).find("--face 999999"), std::string::npos) << e.what();
    }
}

// A face redrawn whose features were edited by hand: the features drawn again as they were keep
// their fids; the one deleted by hand comes back and the one moved by hand is replaced. The undo
// file holds just those (the moved feature, the fid written) and puts the file back.
TEST(Update, KeepsWhatIsDrawnAgainAndItsUndoFileHoldsOnlyWhatChanged) {
    TempDir dir;
    const std::string part = std::string(RH_SAMPLE_DIR) + "/partition.gpkg", out = dir / "h.gpkg",
                      undo = dir / "undo.gpkg";
    run(sample_options(part, out));
    const auto drawn = features(out);
    // Face A: two of its fill features, one deleted by hand, one moved by hand.
    std::vector<GIntBig> fids;
    std::int64_t face = -1;
    for (const auto& [key, f] : drawn)
        if (key.first == "hatch_fill" && (face < 0 || std::get<1>(f) == face) && fids.size() < 2) {
            face = std::get<1>(f);
            fids.push_back(key.second);
        }
    ASSERT_EQ(fids.size(), 2u);
    {
        std::unique_ptr<GDALDataset> ds(GDALDataset::Open(out.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE));
        OGRLayer* fill = ds->GetLayerByName("hatch_fill");
        ASSERT_EQ(fill->DeleteFeature(fids[0]), OGRERR_NONE);
        std::unique_ptr<OGRFeature> f(fill->GetFeature(fids[1]));
        OGRLineString* line = f->GetGeometryRef()->toLineString();
        line->setPoint(0, line->getX(0) + 1.5, line->getY(0));
        ASSERT_EQ(fill->SetFeature(f.get()), OGRERR_NONE);
    }
    const auto edited = features(out);
    std::size_t of_face = 0;
    for (const auto& [key, f] : drawn) of_face += std::get<1>(f) == face;
    const UpdateReport r = update(sample_options(part, out), {false, {face}, undo});
    EXPECT_EQ(r.redrawn_ids, std::vector<std::int64_t>{face});
    EXPECT_EQ(r.deleted, 1u);  // the moved one
    EXPECT_EQ(r.written, 2u);  // the deleted one and the moved one, as drawn
    EXPECT_EQ(r.kept, of_face - 2);
    const auto after = features(out);
    for (const auto& [key, f] : drawn)
        if (key.second != fids[0] && key.second != fids[1]) EXPECT_EQ(after.at(key), f);  // same fid, same bytes
    EXPECT_EQ(by_face(after), by_face(drawn));
    // The undo file: the moved feature and the two fids written, nothing of what stayed.
    {
        std::unique_ptr<GDALDataset> u(GDALDataset::Open(undo.c_str(), GDAL_OF_VECTOR));
        ASSERT_TRUE(u);
        std::size_t kept_there = 0;
        for (OGRLayer* l : u->GetLayers())
            if (std::string(l->GetName()).rfind("hatch_", 0) == 0) kept_there += std::size_t(l->GetFeatureCount());
        EXPECT_EQ(kept_there, 1u);
        EXPECT_EQ(u->GetLayerByName("rockhatch_written")->GetFeatureCount(), 2);
    }
    const FaceReplacement back = restore_faces(out, undo);
    EXPECT_EQ(back.deleted, 2u);
    EXPECT_EQ(back.written, 1u);
    EXPECT_EQ(by_face(features(out)), by_face(edited));
}

TEST(Update, RefusesAnotherStyleUnlessResetAndLeavesTheFileOnCancel) {
    TempDir dir;
    const std::string part = std::string(RH_SAMPLE_DIR) + "/partition.gpkg", out = dir / "h.gpkg";
    run(sample_options(part, out));
    const auto before = features(out);
    Options other = sample_options(part, out);
    other.style = "noisy";
    try {
        update(other, {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::Usage);
        EXPECT_NE(std::string(e.what()).find("style rock"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("--reset"), std::string::npos) << e.what();
    }
    EXPECT_EQ(features(out), before);
    // Cancelled while hatching, then while writing: the file as it was.
    for (const char* stage : {"hatching", "writing"}) {
        try {
            update(other, {true, {}}, [&](double, const std::string& s) { return s != stage; });
            FAIL() << "no error";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), Code::Cancelled);
        }
        EXPECT_EQ(features(out), before) << stage;
    }
    const UpdateReport r = update(other, {true, {}});
    EXPECT_EQ(r.redrawn, r.faces);
    EXPECT_EQ(read_fingerprints(out, "-o")->run.at("style"), "noisy");
}

TEST(Update, RefusesFilesWithoutFingerprintsAndPlansThatKeepNone) {
    TempDir dir;
    const std::string part = std::string(RH_SAMPLE_DIR) + "/partition.gpkg", out = dir / "h.gpkg";
    Options o = sample_options(part, out);
    try {
        update(o, {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::InputMissing);
    }
    o.crest_ornament = "default";
    try {
        update(o, {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::Usage);
        EXPECT_NE(std::string(e.what()).find("--crest-ornament"), std::string::npos) << e.what();
    }
}
