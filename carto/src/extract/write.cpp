// Writers of an extracted partition: the GeoPackage rockhatch reads and the PNG preview.
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>

#include "../gdal_scope.hpp"
#include "../gpkg_file.hpp"
#include "../preview.hpp"
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
    GpkgWriter out(path, p.crs_wkt, true);
    // Derived controls under names rockhatch does not read unless told (see the header).
    const char* orientation_name = fixed_controls ? "orientation" : "fall_line";
    const char* density_name = fixed_controls ? "density" : "shade";
    const int faces = out.add_layer("faces", wkbPolygon,
                                    {{"id", OFTInteger64}, {orientation_name, OFTReal}, {density_name, OFTReal},
                                     {"area", OFTReal}});
    const int lines = out.add_layer("lines", wkbLineString, {{"kind", OFTString}});
    const int mask = out.add_layer("mask", wkbMultiPolygon, {});
    const int net = network ? out.add_layer("network", wkbLineString, {{"kind", OFTString}}) : -1;
    out.begin();
    OGRMultiPolygon all;
    for (const RockFace& rf : p.faces) {
        OGRFeature f(out.definition(faces));
        f.SetField("id", GIntBig(rf.id));
        if (rf.orientation)
            f.SetField(orientation_name, std::round(azimuth_degrees(*rf.orientation) * 100) / 100);
        if (rf.density) f.SetField(density_name, std::round(*rf.density * 1000) / 1000);
        f.SetField("area", std::round(rf.region.area() * 10) / 10);
        std::unique_ptr<OGRPolygon> poly = to_ogr({rf.region.outer(), rf.region.holes()});
        all.addGeometry(poly.get());
        f.SetGeometryDirectly(poly.release());
        out.put(faces, f);
    }
    auto put_lines = [&](int target, const std::vector<LabelledLine>& ls) {
        for (const LabelledLine& l : ls) {
            OGRFeature f(out.definition(target));
            f.SetField("kind", kind_name(l.kind));
            auto geom = std::make_unique<OGRLineString>();
            for (const Point& q : l.points) geom->addPoint(q.x, q.y);
            f.SetGeometryDirectly(geom.release());
            out.put(target, f);
        }
    };
    put_lines(lines, p.lines);
    if (network) put_lines(net, *network);
    if (std::unique_ptr<OGRGeometry> u(all.UnionCascaded()); u) {
        OGRFeature f(out.definition(mask));
        f.SetGeometryDirectly(OGRGeometryFactory::forceToMultiPolygon(u.release()));
        out.put(mask, f);
    }
    out.end();
    out.commit();
}

void write_partition_png(const ExtractResult& r, const std::string& path, int pixels) {
    const Raster& hs = r.terrain.hillshade;
    Preview pv(hs.bounds(), pixels, 3, "--png '" + path + "'");
    const tex::PixelGrid& g = pv.grid();
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const Point q = g.Centre(x, y);
            const double v = hs.sample(q);
            if (std::isnan(v)) continue;
            float* px = pv.at(x, y);
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
    // Borders: the others thin and grey below, ridges (red) and thalwegs (blue) on top.
    const double line = std::max(1.4, pixels / 800.0) * g.pixel;  // ground units
    tex::StrokeCoverage other(g, 0.8 * line), ridge(g, 1.4 * line), valley(g, 1.4 * line);
    for (const LabelledLine& l : r.partition.lines)
        (l.kind == LineKind::Ridge ? ridge : l.kind == LineKind::Valley ? valley : other).Add(l.points, false);
    const std::pair<const tex::StrokeCoverage*, std::array<float, 3>> layers[] = {
        {&other, {0.25f, 0.25f, 0.25f}}, {&ridge, {0.85f, 0.05f, 0.05f}}, {&valley, {0.05f, 0.25f, 0.95f}}};
    for (const auto& [strokes, ink] : layers) {
        std::vector<float> cover = pv.blank();
        strokes->Render(cover);
        pv.over(cover, ink);
    }
    pv.write_png(path, "--png");
}

}  // namespace carto
