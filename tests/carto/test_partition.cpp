// Hand-made partitions whose shared borders are digitised twice with different vertices
// (issue 11): load_partition snaps them onto each other, neighbours are found across every
// shared segment, valleys are drawn once and ridge shapes fall into the darker face.
#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <thread>

#include "carto/error.hpp"
#include "carto/extract.hpp"
#include "carto/partition.hpp"
#include "carto/pipeline.hpp"

#include "scratch.hpp"

using namespace carto;
namespace fs = std::filesystem;

namespace {

const std::string kSample = RH_SAMPLE_DIR;
// Inside the sample DEM (Lambert-93).
const double X0 = 1004000, Y0 = 6540000;

struct HandFace {
    std::vector<Point> ring;  // relative to (X0, Y0), not closed
    double density = -1;      // < 0: none
};
struct HandLine {
    std::vector<Point> points;
    const char* kind;
};

OGRLineString line_string(const std::vector<Point>& pts) {
    OGRLineString l;
    for (const Point& q : pts) l.addPoint(X0 + q.x, Y0 + q.y);
    return l;
}

// Writes the faces and lines to a GeoPackage in Lambert-93, as a cartographer would.
std::string write_partition(const std::string& name, const std::vector<HandFace>& faces,
                            const std::vector<HandLine>& lines) {
    GDALAllRegister();
    const std::string path = rh_test::scratch(name + ".gpkg");
    fs::remove(path);
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
    std::unique_ptr<GDALDataset> ds(drv->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    OGRSpatialReference srs;
    srs.importFromEPSG(2154);
    OGRLayer* fl = ds->CreateLayer("faces", &srs, wkbPolygon, nullptr);
    OGRFieldDefn dens("density", OFTReal);
    fl->CreateField(&dens);
    OGRFieldDefn orient("orientation", OFTReal);
    fl->CreateField(&orient);
    for (const HandFace& f : faces) {
        OGRFeature feat(fl->GetLayerDefn());
        OGRLinearRing ring;
        for (const Point& q : f.ring) ring.addPoint(X0 + q.x, Y0 + q.y);
        ring.closeRings();
        OGRPolygon poly;
        poly.addRing(&ring);
        feat.SetGeometry(&poly);
        if (f.density >= 0) feat.SetField("density", f.density);
        feat.SetField("orientation", 90.0);  // east-west hatches, across the vertical borders
        EXPECT_EQ(fl->CreateFeature(&feat), OGRERR_NONE);
    }
    OGRLayer* ll = ds->CreateLayer("lines", &srs, wkbLineString, nullptr);
    OGRFieldDefn kind("kind", OFTString);
    ll->CreateField(&kind);
    for (const HandLine& l : lines) {
        OGRFeature feat(ll->GetLayerDefn());
        OGRLineString ls = line_string(l.points);
        feat.SetGeometry(&ls);
        feat.SetField("kind", l.kind);
        EXPECT_EQ(ll->CreateFeature(&feat), OGRERR_NONE);
    }
    return path;
}

std::string lambert93() {
    OGRSpatialReference srs;
    srs.importFromEPSG(2154);
    char* wkt = nullptr;
    srs.exportToWkt(&wkt);
    std::string s(wkt);
    CPLFree(wkt);
    return s;
}

Partition load(const std::string& path) {
    PartitionOptions o;
    o.path = path;
    return load_partition(o, lambert93());
}

const RockFace& face(const Partition& p, std::int64_t id) {
    for (const auto& f : p.faces)
        if (f.id == id) return f;
    throw std::runtime_error("no face " + std::to_string(id));
}

int index_of(const Partition& p, std::int64_t id) { return int(&face(p, id) - p.faces.data()); }

// Segments of the face within `tol` of the vertical line x = X0 + x between y0 and y1.
std::vector<BoundarySegment> on_vertical(const RockFace& f, double x, double y0, double y1, double tol = 0.5) {
    std::vector<BoundarySegment> out;
    for (const auto& s : f.boundary) {
        const Point a = s.a - Point{X0, Y0}, b = s.b - Point{X0, Y0};
        if (std::abs(a.x - x) <= tol && std::abs(b.x - x) <= tol && std::min(a.y, b.y) >= y0 - tol &&
            std::max(a.y, b.y) <= y1 + tol)
            out.push_back(s);
    }
    return out;
}

double length(const std::vector<Point>& pts) {
    double l = 0;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) l += tex::distance(pts[i], pts[i + 1]);
    return l;
}

Drawing draw(const std::string& path, const std::string& style) {
    Options o;
    o.dem = kSample + "/dem.tif";
    o.partition.path = path;
    o.style = style;
    o.threads = 1;
    return hatch(prepare(o), o);
}

// Two squares side by side; their common side x = 100 is digitised by each with its own
// vertices (A: y = 0, 30, 100; B: y = 0, 70, 100), 0.05 to 0.1 off the line.
std::vector<HandFace> two_squares(double density_a = -1, double density_b = -1) {
    return {
        {{{0, 0}, {100, 0}, {100.1, 30}, {100, 100}, {0, 100}}, density_a},
        {{{100.08, -0.06}, {200, 0}, {200, 100}, {99.95, 100.07}, {99.9, 70}}, density_b},
    };
}

// Each side of the shared border has the other face across every segment, and both run
// through the same points.
void expect_shared_border(const Partition& p) {
    const RockFace& a = face(p, 1);
    const RockFace& b = face(p, 2);
    const auto sa = on_vertical(a, 100, 0, 100), sb = on_vertical(b, 100, 0, 100);
    ASSERT_GE(sa.size(), 3u);  // A's side gained B's vertex
    ASSERT_EQ(sa.size(), sb.size());
    for (const auto& s : sa) {
        EXPECT_EQ(s.neighbor, index_of(p, 2));
        EXPECT_TRUE(std::any_of(sb.begin(), sb.end(), [&](const BoundarySegment& t) { return t.a == s.b && t.b == s.a; }));
    }
    for (const auto& s : sb) EXPECT_EQ(s.neighbor, index_of(p, 1));
}

std::vector<std::vector<Point>> rings_of(const Partition& p) {
    std::vector<std::vector<Point>> out;
    for (const auto& f : p.faces) {
        out.push_back(f.region.outer());
        out.insert(out.end(), f.region.holes().begin(), f.region.holes().end());
    }
    return out;
}

}  // namespace

TEST(Partition, BordersDigitisedTwiceAreSnappedAndTheValleyIsDrawnOnce) {
    const std::string path =
        write_partition("valley", two_squares(), {{{{100, 0}, {100, 100}}, "valley"}});
    const Partition p = load(path);
    ASSERT_EQ(p.faces.size(), 2u);
    expect_shared_border(p);
    for (const auto& s : on_vertical(face(p, 1), 100, 0, 100)) EXPECT_EQ(s.kind, LineKind::Valley);
    for (const auto& s : on_vertical(face(p, 2), 100, 0, 100)) EXPECT_EQ(s.kind, LineKind::Valley);
    // Only the shared side is a valley: the outer sides stay "other".
    for (const auto& f : p.faces)
        for (const auto& s : f.boundary)
            if (s.kind == LineKind::Valley) EXPECT_GE(s.neighbor, 0);

    const Drawing d = draw(path, "high-ridges");
    double valley = 0;
    for (const auto& fh : d.faces)
        for (const auto& h : fh.hatches)
            if (h.family == Family::Valley) valley += length(h.points);
    EXPECT_NEAR(valley, 100, 0.5);  // once, not twice
}

TEST(Partition, RidgeShapesFallOnlyIntoTheDarkerFace) {
    // Both faces are darker than mid-grey; B digitised the ridge 0.35 to 0.45 m away from A,
    // with a vertex every 5 m, so that unsnapped its border looks across into the gap
    // (no density there) and it took itself for the darker side.
    std::vector<HandFace> faces = {{{{0, 0}, {100, 0}, {100.1, 30}, {100, 100}, {0, 100}}, 0.9},
                                   {{{200, 0}, {200, 100}}, 0.6}};
    for (int k = 20; k >= 0; --k) faces[1].ring.push_back({100.4 + (k % 2 ? 0.05 : -0.05), 5.0 * k});
    const std::string path = write_partition("ridge", faces, {{{{100.2, 0}, {100.2, 100}}, "ridge"}});
    const Partition p = load(path);
    expect_shared_border(p);
    for (const char* style : {"ridge-triangles", "fine-ridges"}) {
        const Drawing d = draw(path, style);
        ASSERT_EQ(d.faces.size(), 2u);
        for (const auto& fh : d.faces) {
            const auto n = std::count_if(fh.hatches.begin(), fh.hatches.end(),
                                         [](const Hatch& h) { return h.family == Family::Ridge; });
            if (fh.face_id == 1) EXPECT_GT(n, 0) << style << ": no ridge shapes in the dark face";
            else EXPECT_EQ(n, 0) << style << ": ridge shapes in the lighter face";
        }
    }
}

TEST(Partition, AVertexOnAnotherFacesSegmentIsInserted) {
    // A's right side is one segment; B and C meet at (100.2, 50), just off it.
    const std::string path = write_partition(
        "tjunction",
        {{{{0, 0}, {100, 0}, {100, 100}, {0, 100}}},
         {{{100, 0}, {200, 0}, {200, 50}, {100.2, 50}}},
         {{{100.2, 50}, {200, 50}, {200, 100}, {100, 100}}}},
        {{{{0, 0}, {0, 100}}, "ridge"}});
    const Partition p = load(path);
    ASSERT_EQ(p.faces.size(), 3u);
    const RockFace& a = face(p, 1);
    const auto& outer = a.region.outer();
    EXPECT_NE(std::find(outer.begin(), outer.end(), Point{X0 + 100, Y0 + 50}), outer.end());
    const auto lower = on_vertical(a, 100, 0, 50, 0.01), upper = on_vertical(a, 100, 50, 100, 0.01);
    ASSERT_EQ(lower.size(), 1u);
    ASSERT_EQ(upper.size(), 1u);
    EXPECT_EQ(lower[0].neighbor, index_of(p, 2));
    EXPECT_EQ(upper[0].neighbor, index_of(p, 3));
    // B and C moved their common corner onto A's side, and still share their border.
    for (std::int64_t id : {2, 3}) {
        const auto& r = face(p, id).region.outer();
        EXPECT_NE(std::find(r.begin(), r.end(), Point{X0 + 100, Y0 + 50}), r.end());
    }
    for (const auto& s : face(p, 2).boundary)
        if (s.a.y == Y0 + 50 && s.b.y == Y0 + 50) EXPECT_EQ(s.neighbor, index_of(p, 3));
}

TEST(Partition, SharedVerticesAreLeftBitIdentical) {
    // The sample partition (written with shared vertices), read without snapping...
    GDALAllRegister();
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open((kSample + "/partition.gpkg").c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(ds);
    Partition raw;
    for (auto& feat : *ds->GetLayerByName("faces")) {
        const OGRPolygon* poly = feat->GetGeometryRef()->toPolygon();
        auto pts = [](const OGRLinearRing* r) {
            std::vector<Point> v;
            for (int i = 0; i < r->getNumPoints(); ++i) v.push_back({r->getX(i), r->getY(i)});
            return v;
        };
        std::vector<std::vector<Point>> holes;
        for (int k = 0; k < poly->getNumInteriorRings(); ++k) holes.push_back(pts(poly->getInteriorRing(k)));
        RockFace f;
        f.id = feat->GetFID();
        f.region = tex::Region(pts(poly->getExteriorRing()), holes);
        raw.faces.push_back(std::move(f));
    }
    ASSERT_EQ(raw.faces.size(), 20u);
    Partition snapped = raw;
    snap_borders(snapped, 0.5);
    EXPECT_EQ(rings_of(snapped), rings_of(raw));
    EXPECT_TRUE(snapped.notes.empty());
    // ... and as loaded: the same rings, every face with neighbours.
    const Partition loaded = load(kSample + "/partition.gpkg");
    EXPECT_EQ(rings_of(loaded), rings_of(raw));
    for (const RockFace& f : loaded.faces)
        EXPECT_TRUE(std::any_of(f.boundary.begin(), f.boundary.end(), [](const BoundarySegment& b) {
            return b.neighbor >= 0;
        })) << "face " << f.id << " found no neighbour";

    // A partition extracted from the DEM shares its vertices too: snapping changes nothing.
    ExtractOptions eo;
    eo.dem = kSample + "/dem.tif";
    const Partition extracted = extract_partition(eo).partition;
    for (double snap : {0.5, 2.0}) {
        Partition again = extracted;
        snap_borders(again, snap);
        EXPECT_EQ(rings_of(again), rings_of(extracted)) << "snap " << snap;
    }
}

TEST(Partition, ASliverThatCollapsesIsDroppedWithANote) {
    // A thin face digitised on its own between A's straight side and B's side 0.4 away: its
    // corners snap onto A's, its other vertices onto A's side, and nothing is left of it. (A
    // sliver sharing a whole side with A is a proper face and stays: a face never snaps onto
    // itself.)
    const std::string path = write_partition(
        "sliver",
        {{{{0, 0}, {100, 0}, {100, 100}, {0, 100}}},
         {{{100.1, 0.1}, {100.3, 30}, {100.3, 70}, {100.1, 99.9}, {99.9, 50}}},
         {{{100.4, 0}, {200, 0}, {200, 100}, {100.4, 100}}}},
        {{{{100, 0}, {100, 100}}, "valley"}});
    const Partition p = load(path);
    ASSERT_EQ(p.faces.size(), 2u);
    EXPECT_EQ(p.faces[0].id, 1);
    EXPECT_EQ(p.faces[1].id, 3);
    ASSERT_FALSE(p.notes.empty());
    EXPECT_NE(p.notes.back().find("dropped 1 face"), std::string::npos) << p.notes.back();
    EXPECT_NE(p.notes.back().find("id 2"), std::string::npos) << p.notes.back();
    // A and B now share the border.
    for (const auto& s : on_vertical(p.faces[0], 100, 0, 100)) EXPECT_EQ(s.neighbor, 1);
    for (const auto& s : on_vertical(p.faces[1], 100, 0, 100)) EXPECT_EQ(s.neighbor, 0);
    EXPECT_EQ(on_vertical(p.faces[0], 100, 0, 100).size(), 4u);
}

TEST(Partition, SnappingDoesNotDependOnTheOrderOfTheFaces) {
    auto faces = two_squares();
    faces.push_back({{{100, 100}, {200, 100}, {200, 150}, {100.1, 150.2}}});
    const std::vector<HandLine> lines = {{{{100, 0}, {100, 100}}, "valley"}};
    const Partition p = load(write_partition("order1", faces, lines));
    std::reverse(faces.begin(), faces.end());
    const Partition q = load(write_partition("order2", faces, lines));
    ASSERT_EQ(p.faces.size(), q.faces.size());
    for (std::size_t i = 0; i < p.faces.size(); ++i)
        EXPECT_EQ(p.faces[i].region.outer(), q.faces[p.faces.size() - 1 - i].region.outer());
}

// fuzz/fuzz_partition_struct: a face reaching 1e300 made the snapping grid convert
// floor(1e300 / snap) to a 64-bit integer, which overflows, and one from -1e308 to 1e308
// gave NaN rows (undefined behaviour: UBSan's float-cast-overflow in scripts/sanitize.sh).
// Cell indices are clamped first; such faces are read like any other.
TEST(Partition, FacesFarBeyondAnyCrsDoNotOverflowTheSnappingGrid) {
    const std::string path = write_partition(
        "huge", {{{{0, 0}, {1e300, 0}, {1e300, 100}, {0, 100}}}, {{{0, 100}, {100, 100}, {100, 200}, {0, 200}}},
                 // From -1e308 to 1e308 the width overflows to +inf: NaN rows in the grid.
                 {{{-1e308, 300}, {1e308, 300}, {1e308, 400}, {-1e308, 400}}}},
        {{{{0, 100}, {100, 100}}, "ridge"}});
    try {
        const Partition p = load(path);
        EXPECT_EQ(p.faces.size(), 3u);
    } catch (const Error& e) {
        ADD_FAILURE() << e.what();
    }
}

// fuzz/fuzz_partition_struct: NaN coordinates reached the exact regions, the snapping grid
// and the labelling. A face or line with a coordinate that is not finite is refused
// (BadGeometry, exit code 8), naming the feature.
TEST(Partition, CoordinatesThatAreNotFiniteAreRefused) {
    const double nan = std::nan("");
    const std::string faces = write_partition("nan_face", {{{{0, 0}, {100, 0}, {100, nan}, {0, 100}}}},
                                              {{{{0, 0}, {100, 0}}, "ridge"}});
    const std::string lines = write_partition("nan_line", {{{{0, 0}, {100, 0}, {100, 100}, {0, 100}}}},
                                              {{{{0, 0}, {nan, 0}}, "ridge"}});
    for (const std::string& path : {faces, lines}) {
        try {
            load(path);
            ADD_FAILURE() << path << ": accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), Code::BadGeometry) << e.what();
            EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
        }
    }
}

// fuzz_partition_struct: an invalid face with coordinates near the largest doubles kept GEOS's
// repair busy for minutes. Such a face is refused (BadGeometry), naming it; the same
// bow-tie on the map is repaired as before.
TEST(Partition, AnInvalidFaceBeyondAnyMapIsRefusedNotRepairedForever) {
    const double huge = 1.5e308;
    const std::string far = write_partition("far_bowtie", {{{{0, 0}, {huge, 100}, {huge, 0}, {0, 100}}}},
                                            {{{{0, 0}, {0, 100}}, "ridge"}});
    try {
        load(far);
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::BadGeometry) << e.what();
        EXPECT_NE(std::string(e.what()).find("face 1 is invalid and lies beyond any map"), std::string::npos) << e.what();
    }
    const std::string near = write_partition("near_bowtie", {{{{0, 0}, {100, 100}, {100, 0}, {0, 100}}}},
                                             {{{{0, 0}, {0, 100}}, "ridge"}});
    EXPECT_EQ(load(near).faces.size(), 2u);
}

// A partition is read from any path GDAL can stat: a GeoPackage copied into memory
// (/vsimem/) or inside a zip (/vsizip/) reads as the file does; a virtual path that is not
// there is a missing input.
TEST(Partition, AVirtualPathReadsAsTheFile) {
    const std::string file = kSample + "/partition.gpkg";
    const Partition p = load(file);
    ASSERT_EQ(p.faces.size(), 20u);
    const std::string mem = "/vsimem/rockhatch_test_partition.gpkg";
    ASSERT_EQ(CPLCopyFile(mem.c_str(), file.c_str()), 0);
    const Partition q = load(mem);
    VSIUnlink(mem.c_str());
    ASSERT_EQ(q.faces.size(), p.faces.size());
    for (std::size_t i = 0; i < p.faces.size(); ++i) {
        EXPECT_EQ(q.faces[i].id, p.faces[i].id);
        EXPECT_EQ(q.faces[i].region.outer(), p.faces[i].region.outer());
        EXPECT_EQ(q.faces[i].boundary.size(), p.faces[i].boundary.size());
    }
    EXPECT_EQ(q.lines.size(), p.lines.size());
    const std::string zip = "/vsimem/rockhatch_test_partition.zip";
    ASSERT_EQ(CPLCopyFile(("/vsizip/" + zip + "/partition.gpkg").c_str(), file.c_str()), 0);
    const Partition z = load("/vsizip/" + zip + "/partition.gpkg");
    VSIUnlink(zip.c_str());
    ASSERT_EQ(z.faces.size(), p.faces.size());
    EXPECT_EQ(z.faces.back().region.outer(), p.faces.back().region.outer());
    try {
        (void)load("/vsimem/rockhatch_no_such_partition.gpkg");
        FAIL() << "a missing virtual file was read";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::InputMissing);
        EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
    }
}

// Layers in other CRSs are reprojected each by its own transformation, however often and in
// whatever order loads ask for them (the transformations are kept for the process, by both
// CRSs): the sample's faces copied into EPSG:4326, then EPSG:32631, then 4326 again, then
// the working CRS, read on one thread and then on two at once, land on the file's vertices
// (within 1 mm: PROJ's round trip).
TEST(Partition, LayersInOtherCrssEachReadThroughTheirOwnTransformation) {
    const std::string file = kSample + "/partition.gpkg";
    const Partition truth = load(file);
    GDALDatasetUniquePtr src(GDALDataset::Open(file.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    ASSERT_TRUE(src);
    auto copy_in = [&](int epsg) {
        // Every layer of the file (faces and lines), its geometries transformed.
        OGRSpatialReference to;
        to.importFromEPSG(epsg);
        to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("Memory");
        std::unique_ptr<GDALDataset> ds(mem->Create("copy", 0, 0, 0, GDT_Unknown, nullptr));
        for (OGRLayer* in : src->GetLayers()) {
            OGRSpatialReference from(*in->GetSpatialRef());
            from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&from, &to));
            OGRLayer* l = ds->CreateLayer(in->GetName(), &to, in->GetGeomType(), nullptr);
            for (int i = 0; i < in->GetLayerDefn()->GetFieldCount(); ++i) l->CreateField(in->GetLayerDefn()->GetFieldDefn(i));
            in->ResetReading();
            for (auto& f : *in) {
                std::unique_ptr<OGRFeature> g(f->Clone());
                if (g->GetGeometryRef()) g->GetGeometryRef()->transform(ct.get());
                EXPECT_EQ(l->CreateFeature(g.get()), OGRERR_NONE);
            }
        }
        return ds;
    };
    auto expect_on_truth = [&](const Partition& p, const std::string& what) {
        ASSERT_EQ(p.faces.size(), truth.faces.size()) << what;
        double worst = 0;
        for (std::size_t i = 0; i < p.faces.size(); ++i) {
            ASSERT_EQ(p.faces[i].region.outer().size(), truth.faces[i].region.outer().size()) << what;
            for (std::size_t k = 0; k < p.faces[i].region.outer().size(); ++k)
                worst = std::max(worst, distance(p.faces[i].region.outer()[k], truth.faces[i].region.outer()[k]));
        }
        EXPECT_LT(worst, 1e-3) << what;
    };
    const auto wgs84 = copy_in(4326), utm = copy_in(32631), same = copy_in(2154);
    PartitionOptions o;
    o.path = "copy";
    for (auto* ds : {wgs84.get(), utm.get(), wgs84.get(), same.get(), utm.get()})
        expect_on_truth(load_partition(*ds, o, lambert93()), ds->GetLayer(0)->GetSpatialRef()->GetName());
    Partition a, b;
    std::thread t1([&] { a = load_partition(*wgs84, o, lambert93()); });
    std::thread t2([&] { b = load_partition(*utm, o, lambert93()); });
    t1.join();
    t2.join();
    expect_on_truth(a, "4326 on a thread");
    expect_on_truth(b, "32631 on a thread");
}

// An invalid face is GEOS's repair of it every time it is read: the reader keeps each repair
// for the process by the face's exact coordinates, so two bow ties with the same bounding box
// and the same number of vertices, read in turn, each get their own repair, read after read,
// with the note of the repair each time.
TEST(Partition, AnInvalidFaceReadAgainIsRepairedAsTheFirstTime) {
    const HandLine ridge{{{0, 0}, {0, 100}}, "ridge"};
    // Crossings at (50, 50) and (33.3, 33.3).
    const std::string a = write_partition("bowtie_a", {{{{0, 0}, {100, 100}, {100, 0}, {0, 100}}}}, {ridge});
    const std::string b = write_partition("bowtie_b", {{{{0, 0}, {100, 100}, {100, 0}, {0, 50}}}}, {ridge});
    auto has_vertex = [](const Partition& p, double x, double y) {
        for (const auto& r : rings_of(p))
            for (const Point& q : r)
                if (distance(q, Point{X0 + x, Y0 + y}) < 1e-6) return true;
        return false;
    };
    auto repaired_note = [](const Partition& p) {
        return std::find(p.notes.begin(), p.notes.end(), "repaired 1 invalid face polygon(s)") != p.notes.end();
    };
    const Partition first_a = load(a), first_b = load(b);
    ASSERT_EQ(first_a.faces.size(), 2u);
    ASSERT_EQ(first_b.faces.size(), 2u);
    EXPECT_TRUE(has_vertex(first_a, 50, 50));
    EXPECT_FALSE(has_vertex(first_a, 100.0 / 3, 100.0 / 3));
    EXPECT_TRUE(has_vertex(first_b, 100.0 / 3, 100.0 / 3));
    EXPECT_FALSE(has_vertex(first_b, 50, 50));
    EXPECT_TRUE(repaired_note(first_a));
    EXPECT_TRUE(repaired_note(first_b));
    for (int round = 0; round < 2; ++round)
        for (const auto& [path, first] : {std::pair{a, &first_a}, std::pair{b, &first_b}}) {
            const Partition again = load(path);
            EXPECT_EQ(rings_of(again), rings_of(*first)) << path;
            ASSERT_EQ(again.faces.size(), first->faces.size());
            for (std::size_t i = 0; i < again.faces.size(); ++i) {
                EXPECT_EQ(again.faces[i].id, first->faces[i].id);
                EXPECT_EQ(again.faces[i].boundary.size(), first->faces[i].boundary.size());
            }
            EXPECT_EQ(again.notes, first->notes) << path;
        }
}

// The line layers are found before any face is read: a partition without them is refused for
// that, at once, even when a face would have been refused (its density out of [0, 1]) or
// repaired.
TEST(Partition, WithoutLineLayersNoFaceIsRead) {
    GDALAllRegister();
    OGRSpatialReference srs;
    srs.importFromEPSG(2154);
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("Memory");
    std::unique_ptr<GDALDataset> ds(mem->Create("nolines", 0, 0, 0, GDT_Unknown, nullptr));
    OGRLayer* fl = ds->CreateLayer("faces", &srs, wkbPolygon, nullptr);
    OGRFieldDefn dens("density", OFTReal);
    fl->CreateField(&dens);
    OGRFeature feat(fl->GetLayerDefn());
    OGRLinearRing ring;
    for (const Point& q : std::vector<Point>{{0, 0}, {100, 100}, {100, 0}, {0, 100}, {0, 0}}) ring.addPoint(X0 + q.x, Y0 + q.y);
    OGRPolygon poly;
    poly.addRing(&ring);
    feat.SetGeometry(&poly);
    feat.SetField("density", 2.0);
    ASSERT_EQ(fl->CreateFeature(&feat), OGRERR_NONE);
    PartitionOptions o;
    o.path = "nolines";
    try {
        load_partition(*ds, o, lambert93());
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), Code::BadLayer) << e.what();
        EXPECT_NE(std::string(e.what()).find("no line layer with a 'kind' field"), std::string::npos) << e.what();
    }
}
