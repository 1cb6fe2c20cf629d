// Writers of an extracted partition: the GeoPackage rockhatch reads and the PNG preview.
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>

#include "../gdal_scope.hpp"
#include "../gpkg_file.hpp"
#include "../temp_file.hpp"
#include "carto/error.hpp"
#include "carto/extract.hpp"
#include "carto/output.hpp"
#include "polygons.hpp"

namespace carto {

using extraction::FacePolygon;
using extraction::to_ogr;

void write_partition_gpkg(const Partition& p, const std::string& path, bool overwrite,
                          const std::vector<LabelledLine>* network, bool fixed_controls) {
    check_output(path, overwrite);
    register_gdal();
    TempFile tmp(path, ".gpkg");
    {
        const ReproducibleGpkg reproducible;  // on this thread, for this call (gdal_scope.hpp)
        const QuietGdal quiet;
        const std::unique_ptr<GDALDataset> ds = create_gpkg(tmp.path, path);
        OGRSpatialReference srs = layer_srs(p.crs_wkt);
        auto layer = [&](const char* name, OGRwkbGeometryType t,
                         std::vector<std::pair<const char*, OGRFieldType>> fields) {
            const char* lco[] = {"FID=fid", "GEOMETRY_NAME=geom", nullptr};
            OGRLayer* l = ds->CreateLayer(name, &srs, t, const_cast<char**>(lco));
            if (!l)
                throw Error(Code::OutputExists, "-o '" + path + "': cannot create layer " + name);
            for (auto [n, ft] : fields) {
                OGRFieldDefn fd(n, ft);
                l->CreateField(&fd);
            }
            return l;
        };
        auto put = [&](OGRLayer* l, OGRFeature& f) {
            if (l->CreateFeature(&f) != OGRERR_NONE)
                throw Error(Code::OutputExists, "-o '" + path + "': write failed");
        };
        // Derived controls under names rockhatch does not read unless told (see the header).
        const char* orientation_name = fixed_controls ? "orientation" : "fall_line";
        const char* density_name = fixed_controls ? "density" : "shade";
        OGRLayer* faces = layer("faces", wkbPolygon,
                                {{"id", OFTInteger64},
                                 {orientation_name, OFTReal},
                                 {density_name, OFTReal},
                                 {"area", OFTReal}});
        OGRLayer* lines = layer("lines", wkbLineString, {{"kind", OFTString}});
        OGRLayer* mask = layer("mask", wkbMultiPolygon, {});
        OGRLayer* net = network ? layer("network", wkbLineString, {{"kind", OFTString}}) : nullptr;
        ds->StartTransaction();
        OGRMultiPolygon all;
        for (const RockFace& rf : p.faces) {
            OGRFeature f(faces->GetLayerDefn());
            f.SetField("id", GIntBig(rf.id));
            if (rf.orientation)
                f.SetField(orientation_name,
                           std::round(azimuth_degrees(*rf.orientation) * 100) / 100);
            if (rf.density) f.SetField(density_name, std::round(*rf.density * 1000) / 1000);
            f.SetField("area", std::round(rf.region.area() * 10) / 10);
            std::unique_ptr<OGRPolygon> poly = to_ogr({rf.region.outer(), rf.region.holes()});
            all.addGeometry(poly.get());
            f.SetGeometryDirectly(poly.release());
            put(faces, f);
        }
        auto put_lines = [&](OGRLayer* target, const std::vector<LabelledLine>& ls) {
            for (const LabelledLine& l : ls) {
                OGRFeature f(target->GetLayerDefn());
                f.SetField("kind", kind_name(l.kind));
                auto geom = std::make_unique<OGRLineString>();
                for (const Point& q : l.points) geom->addPoint(q.x, q.y);
                f.SetGeometryDirectly(geom.release());
                put(target, f);
            }
        };
        put_lines(lines, p.lines);
        if (net) put_lines(net, *network);
        std::unique_ptr<OGRGeometry> u(all.UnionCascaded());
        if (u) {
            OGRFeature f(mask->GetLayerDefn());
            f.SetGeometryDirectly(OGRGeometryFactory::forceToMultiPolygon(u.release()));
            put(mask, f);
        }
        ds->CommitTransaction();
    }
    tmp.commit(path);
}

void write_partition_png(const ExtractResult& r, const std::string& path, int pixels) {
    const Raster& hs = r.terrain.hillshade;
    const tex::BBox b = hs.bounds();
    const double upp = std::max(b.width(), b.height()) / pixels;  // ground units per pixel
    const int w = std::max(1, int(std::ceil(b.width() / upp))),
              h = std::max(1, int(std::ceil(b.height() / upp)));
    std::vector<float> rgb(std::size_t(w) * h * 3, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Point q{b.xmin + (x + 0.5) * upp, b.ymax - (y + 0.5) * upp};
            const double v = hs.sample(q);
            float* px = &rgb[(std::size_t(y) * w + x) * 3];
            if (std::isnan(v)) continue;
            const float grey = float(0.3 + 0.7 * v);
            px[0] = px[1] = px[2] = grey;
            const double f = r.faces.nearest(q);
            if (f >= 0) {
                // A light colour per face, from a hash of its index.
                const std::uint64_t hsh = (std::uint64_t(f) + 1) * 0x9E3779B97F4A7C15ULL;
                const float tint[3] = {float(0.55 + 0.45 * ((hsh >> 8) & 255) / 255.0),
                                       float(0.55 + 0.45 * ((hsh >> 24) & 255) / 255.0),
                                       float(0.35 + 0.3 * ((hsh >> 40) & 255) / 255.0)};
                for (int k = 0; k < 3; ++k) px[k] = 0.6f * px[k] + 0.4f * tint[k] * grey * 1.3f;
            }
            // The ridge and thalweg cells, faint (borders or not).
            const Point cell = r.rock.to_pixel(q);
            const int lc = r.line_cells[std::size_t(int(cell.y)) * r.rock.width + int(cell.x)];
            if (lc) {
                const float ink[3] = {lc == 1 ? 1.0f : 0.55f, 0.55f, lc == 2 ? 1.0f : 0.55f};
                for (int k = 0; k < 3; ++k) px[k] = 0.5f * px[k] + 0.5f * ink[k];
            }
        }
    auto stamp = [&](double cx, double cy, double radius, const float* ink) {
        for (int y = std::max(0, int(cy - radius - 1)); y <= std::min(h - 1, int(cy + radius + 1));
             ++y)
            for (int x = std::max(0, int(cx - radius - 1));
                 x <= std::min(w - 1, int(cx + radius + 1)); ++x) {
                const double cover =
                    std::clamp(radius + 0.5 - std::hypot(x + 0.5 - cx, y + 0.5 - cy), 0.0, 1.0);
                float* px = &rgb[(std::size_t(y) * w + x) * 3];
                for (int k = 0; k < 3; ++k) px[k] = float(px[k] * (1 - cover) + ink[k] * cover);
            }
    };
    const float red[3] = {0.85f, 0.05f, 0.05f}, blue[3] = {0.05f, 0.25f, 0.95f},
                grey[3] = {0.25f, 0.25f, 0.25f};
    const double radius = std::max(0.7, pixels / 1600.0);
    for (int pass = 0; pass < 2; ++pass)  // other borders below, ridges and valleys on top
        for (const LabelledLine& l : r.partition.lines) {
            if ((l.kind == LineKind::Other) != (pass == 0)) continue;
            const float* ink = l.kind == LineKind::Ridge    ? red
                               : l.kind == LineKind::Valley ? blue
                                                            : grey;
            for (std::size_t i = 0; i + 1 < l.points.size(); ++i) {
                const double ax = (l.points[i].x - b.xmin) / upp,
                             ay = (b.ymax - l.points[i].y) / upp;
                const double bx = (l.points[i + 1].x - b.xmin) / upp,
                             by = (b.ymax - l.points[i + 1].y) / upp;
                const int n = std::max(1, int(std::ceil(std::hypot(bx - ax, by - ay) * 2)));
                for (int k = 0; k <= n; ++k)
                    stamp(ax + (bx - ax) * k / n, ay + (by - ay) * k / n,
                          pass ? radius * 1.4 : radius * 0.8, ink);
            }
        }
    std::vector<unsigned char> bytes(rgb.size());
    for (std::size_t i = 0; i < rgb.size(); ++i)
        bytes[i] = (unsigned char)std::lround(std::clamp(rgb[i], 0.0f, 1.0f) * 255);
    write_png_pixels(bytes, w, h, 3, path, "--png");
}

}  // namespace carto
