// libFuzzer target: the partition reader on valid GeoPackages built from the fuzzer's bytes
// (FuzzedDataProvider): a few polygon faces with holes, density and orientation attributes,
// ridge / valley lines (one labelled layer or one layer per kind), orientation lines, a
// density layer, odd CRSs and coordinates, and the reader's options. This reaches the
// reader's geometry code (repair, snapping, labelling) far more often than raw bytes do.
// The only expected failure is carto::Error.
#include <fuzzer/FuzzedDataProvider.h>
#include <cpl_vsi.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>

#include "carto/error.hpp"
#include "carto/partition.hpp"
#include "fuzz_common.hpp"

namespace {

const double X0 = 1004000, Y0 = 6540000;  // inside the sample, Lambert-93

double coord(FuzzedDataProvider& in) {
    switch (in.ConsumeIntegralInRange<int>(0, 15)) {
        case 0: return in.ConsumeFloatingPoint<double>();  // anything, huge values included
        case 1: return std::numeric_limits<double>::quiet_NaN();
        case 2: return in.ConsumeFloatingPointInRange<double>(-100, 100);
        default: return double(in.ConsumeIntegralInRange<int>(-8, 8)) * in.PickValueInArray({0.25, 1.0, 10.0, 100.0});
    }
}

OGRLinearRing ring(FuzzedDataProvider& in) {
    OGRLinearRing r;
    const int n = in.ConsumeIntegralInRange<int>(0, 10);
    for (int i = 0; i < n; ++i) r.addPoint(X0 + coord(in), Y0 + coord(in));
    if (in.ConsumeBool()) r.closeRings();
    return r;
}

OGRLineString line(FuzzedDataProvider& in) {
    OGRLineString l;
    const int n = in.ConsumeIntegralInRange<int>(0, 6);
    for (int i = 0; i < n; ++i) l.addPoint(X0 + coord(in), Y0 + coord(in));
    return l;
}

std::string label(FuzzedDataProvider& in) {
    if (in.ConsumeIntegralInRange<int>(0, 9) == 0) return in.ConsumeRandomLengthString(12);
    return in.PickValueInArray({"ridge", "valley", "other", "thalweg", "", "crête", "Ridge", "boundary"});
}

std::unique_ptr<OGRSpatialReference> epsg(int code) {
    auto s = std::make_unique<OGRSpatialReference>();
    s->importFromEPSG(code);
    return s;
}

// A layer's CRS (nullptr: none). Each CRS is read from PROJ's database once (a lookup per
// input took most of the time) and never copied here: the in-memory layer keeps its own copy.
OGRSpatialReference* srs(FuzzedDataProvider& in) {
    const int c = in.ConsumeIntegralInRange<int>(0, 7);
    if (c == 0) return nullptr;  // no CRS
    static const std::unique_ptr<OGRSpatialReference> known[3] = {epsg(4326), epsg(32632), epsg(2154)};
    return known[c == 1 ? 0 : c == 2 ? 1 : 2].get();
}

void real_field(OGRFeature& f, const char* name, FuzzedDataProvider& in) {
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
        case 0: break;  // unset
        case 1: f.SetField(name, in.ConsumeFloatingPoint<double>()); break;
        case 2: f.SetFieldNull(f.GetFieldIndex(name)); break;
        default: f.SetField(name, in.ConsumeFloatingPointInRange<double>(0, 1)); break;
    }
}

// The dataset the bytes describe, in OGR's in-memory driver (a GeoPackage, even in /vsimem/,
// costs an SQLite schema per input: 36 inputs a second instead of thousands); nullptr when
// it cannot be made.
std::unique_ptr<GDALDataset> build(FuzzedDataProvider& in, carto::PartitionOptions& o) {
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("Memory");
    std::unique_ptr<GDALDataset> ds(drv ? drv->Create("fuzz", 0, 0, 0, GDT_Unknown, nullptr) : nullptr);
    if (!ds) return nullptr;
    // Faces.
    OGRSpatialReference* const fsrs = srs(in);
    const bool multi = in.ConsumeBool();
    OGRLayer* fl = ds->CreateLayer("faces", fsrs, multi ? wkbMultiPolygon : wkbPolygon, nullptr);
    for (const char* name : {"density", "orientation"}) {
        OGRFieldDefn d(name, OFTReal);
        fl->CreateField(&d);
    }
    OGRFieldDefn idf("fid2", OFTInteger64);
    fl->CreateField(&idf);
    const int nfaces = in.ConsumeIntegralInRange<int>(0, 6);
    for (int i = 0; i < nfaces; ++i) {
        OGRFeature feat(fl->GetLayerDefn());
        OGRPolygon poly;
        OGRLinearRing outer = ring(in);
        poly.addRing(&outer);
        for (int h = in.ConsumeIntegralInRange<int>(0, 2); h > 0; --h) {
            OGRLinearRing hole = ring(in);
            poly.addRing(&hole);
        }
        if (multi) {
            OGRMultiPolygon mp;
            mp.addGeometry(&poly);
            if (in.ConsumeBool()) {
                OGRPolygon p2;
                OGRLinearRing r2 = ring(in);
                p2.addRing(&r2);
                mp.addGeometry(&p2);
            }
            feat.SetGeometry(&mp);
        } else {
            feat.SetGeometry(&poly);
        }
        real_field(feat, "density", in);
        real_field(feat, "orientation", in);
        feat.SetField("fid2", GIntBig(in.ConsumeIntegral<std::int64_t>()));
        // A feature the layer refuses (the fuzzer's values may be odd) is one fewer: the reader
        // is what is tested, not the writer. So for every CreateFeature below.
        (void)fl->CreateFeature(&feat);
    }
    // Lines: one labelled layer, or layers named after their kind.
    OGRSpatialReference* const lsrs = in.ConsumeBool() ? srs(in) : fsrs;
    if (in.ConsumeBool()) {
        OGRLayer* ll = ds->CreateLayer("lines", lsrs, in.ConsumeBool() ? wkbLineString : wkbMultiLineString, nullptr);
        OGRFieldDefn kind("kind", OFTString);
        ll->CreateField(&kind);
        for (int n = in.ConsumeIntegralInRange<int>(0, 6); n > 0; --n) {
            OGRFeature feat(ll->GetLayerDefn());
            OGRLineString l = line(in);
            if (wkbFlatten(ll->GetGeomType()) == wkbMultiLineString) {
                OGRMultiLineString ml;
                ml.addGeometry(&l);
                feat.SetGeometry(&ml);
            } else {
                feat.SetGeometry(&l);
            }
            if (in.ConsumeBool()) feat.SetField("kind", label(in).c_str());
            (void)ll->CreateFeature(&feat);
        }
    } else {
        for (const char* name : {"ridges", "valleys"}) {
            if (!in.ConsumeBool()) continue;
            OGRLayer* ll = ds->CreateLayer(name, lsrs, wkbLineString, nullptr);
            for (int n = in.ConsumeIntegralInRange<int>(0, 4); n > 0; --n) {
                OGRFeature feat(ll->GetLayerDefn());
                OGRLineString l = line(in);
                feat.SetGeometry(&l);
                (void)ll->CreateFeature(&feat);
            }
        }
    }
    // Orientation lines.
    if (in.ConsumeBool()) {
        OGRLayer* ol = ds->CreateLayer("orientation", fsrs, wkbLineString, nullptr);
        for (int n = in.ConsumeIntegralInRange<int>(0, 4); n > 0; --n) {
            OGRFeature feat(ol->GetLayerDefn());
            OGRLineString l = line(in);
            feat.SetGeometry(&l);
            (void)ol->CreateFeature(&feat);
        }
    }
    // A density layer of points or polygons.
    if (in.ConsumeBool()) {
        const bool points = in.ConsumeBool();
        OGRLayer* dl = ds->CreateLayer("dens", fsrs, points ? wkbPoint : wkbPolygon, nullptr);
        OGRFieldDefn d("density", OFTReal);
        dl->CreateField(&d);
        for (int n = in.ConsumeIntegralInRange<int>(0, 4); n > 0; --n) {
            OGRFeature feat(dl->GetLayerDefn());
            if (points) {
                OGRPoint pt(X0 + coord(in), Y0 + coord(in));
                feat.SetGeometry(&pt);
            } else {
                OGRPolygon poly;
                OGRLinearRing r = ring(in);
                poly.addRing(&r);
                feat.SetGeometry(&poly);
            }
            real_field(feat, "density", in);
            (void)dl->CreateFeature(&feat);
        }
        o.density_layer = "dens";
    }
    o.snap = in.PickValueInArray({0.5, 0.5, 0.01, 2.0, 50.0, 1e-9});
    o.repair = in.ConsumeIntegralInRange<int>(0, 3) != 0;
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0) o.id_field = "fid2";
    return ds;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::quiet_gdal();
    FuzzedDataProvider in(data, size);
    // Built and read in memory: the reader takes the open dataset (fuzz_partition_raw covers
    // the GeoPackage bytes).
    carto::PartitionOptions o;
    o.path = "fuzz";
    if (const std::unique_ptr<GDALDataset> ds = build(in, o)) {
        try {
            (void)carto::load_partition(*ds, o, fuzz::working_wkt());
        } catch (const carto::Error&) {
        }
    }
    return 0;
}
