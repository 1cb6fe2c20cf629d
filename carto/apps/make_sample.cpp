// rh_make_sample: writes the bundled synthetic sample (data/sample_montblanc).
//
// The terrain is synthetic: a pyramidal peak placed at the Aiguille du Moine (Lambert-93)
// with sharp ridges radiating from the summit and V-shaped couloirs between them, at
// alpine heights, with a little deterministic roughness and a NoData corner. Because the
// generator builds the ridges and thalwegs itself, it also writes them as ground truth.
//
//   rh_make_sample -o DIR [--size METRES] [--cell METRES] [--overwrite]
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "carto/error.hpp"
#include "carto/raster.hpp"
#include "carto/terrain.hpp"
#include "libtex/random.hpp"
#include "libtex/region.hpp"

namespace fs = std::filesystem;
using carto::Point;

namespace {

// The massif, in metres around the summit.
constexpr double kSummitX = 1004100, kSummitY = 6539900;  // Aiguille du Moine, Lambert-93
constexpr double kSummitZ = 3412;
constexpr int kRidges = 5;
constexpr double kPhase = 0.35;       // angle of the first ridge (radians)
constexpr double kRockInner = 60;     // rock faces from 60 m ...
constexpr double kRockMid = 480;      // ... split at 480 m ...
constexpr double kRockOuter = 950;    // ... to 950 m from the summit

// Ridges bend a little with distance.
double bend(double r) { return 0.16 * std::sin(r / 320.0); }

// Value noise (bilinear over a hashed lattice), amplitude 1.
double value_noise(double x, double y, double wavelength, std::uint64_t salt) {
    const double fx = x / wavelength, fy = y / wavelength;
    const long long ix = (long long)std::floor(fx), iy = (long long)std::floor(fy);
    const double tx = fx - ix, ty = fy - iy;
    auto v = [&](long long a, long long b) {
        const std::uint64_t h = tex::hash_combine(tex::hash_combine(salt, std::uint64_t(a)), std::uint64_t(b));
        return 2 * tex::unit_from_hash(h) - 1;
    };
    const double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
    return (v(ix, iy) * (1 - sx) + v(ix + 1, iy) * sx) * (1 - sy) + (v(ix, iy + 1) * (1 - sx) + v(ix + 1, iy + 1) * sx) * sy;
}

double elevation(double x, double y) {
    const double dx = x - kSummitX, dy = y - kSummitY;
    const double r = std::hypot(dx, dy), phi = std::atan2(dy, dx);
    // Mean profile: 78% slope near the top, easing to a glacier floor at about 2250 m.
    const double base = std::max(2250.0 + 0.05 * r, kSummitZ - 0.78 * r + 0.00012 * r * r);
    // Ridge / couloir relief: a triangle wave around the summit, sharp at both ends.
    const double u = kRidges * (phi - kPhase - bend(r)) / (2 * M_PI);
    const double f = u - std::floor(u);
    const double tri = 2 * std::abs(2 * f - 1) - 1;  // +1 on ridges, -1 in couloirs
    const double relief = 0.22 * r * (1 - std::exp(-r / 120.0));
    const double noise = 7 * value_noise(x, y, 45, 11) + 2.5 * value_noise(x, y, 13, 12);
    return base + relief * (tri - 1) * 0.5 + noise;
}

// Truth lines: the ridge k (tri = +1) and the couloir k (tri = -1) as polylines in r.
std::vector<Point> ray(int k, bool ridge, double r0, double r1, double step) {
    std::vector<Point> pts;
    for (double r = r0; r <= r1 + 1e-9; r += step) {
        const double phi = kPhase + bend(r) + (2 * M_PI * (k + (ridge ? 0.0 : 0.5))) / kRidges;
        pts.push_back({kSummitX + r * std::cos(phi), kSummitY + r * std::sin(phi)});
    }
    return pts;
}

std::vector<Point> arc(double r, double phi0, double phi1, double step) {
    std::vector<Point> pts;
    const int n = std::max(2, int(std::ceil(std::abs(phi1 - phi0) * r / step)));
    for (int i = 0; i <= n; ++i) {
        const double phi = phi0 + (phi1 - phi0) * i / n;
        pts.push_back({kSummitX + r * std::cos(phi), kSummitY + r * std::sin(phi)});
    }
    return pts;
}

double angle_at(int k, bool ridge, double r) {
    return kPhase + bend(r) + (2 * M_PI * (k + (ridge ? 0.0 : 0.5))) / kRidges;
}

OGRLineString linestring(const std::vector<Point>& pts) {
    OGRLineString ls;
    for (const auto& p : pts) ls.addPoint(p.x, p.y);
    return ls;
}

struct Gpkg {
    std::unique_ptr<GDALDataset> ds;
    OGRSpatialReference srs;
    Gpkg(const std::string& path) {
        GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
        ds.reset(drv->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        if (!ds) throw carto::Error(carto::Code::OutputExists, "cannot create '" + path + "'");
        srs.importFromEPSG(2154);
        srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    }
    OGRLayer* layer(const char* name, OGRwkbGeometryType t, std::vector<std::pair<const char*, OGRFieldType>> fields) {
        OGRLayer* l = ds->CreateLayer(name, &srs, t, nullptr);
        for (auto [n, ft] : fields) {
            OGRFieldDefn f(n, ft);
            l->CreateField(&f);
        }
        return l;
    }
};

}  // namespace

int main(int argc, char** argv) {
    std::string out;
    double size = 2400, cell = 5;
    bool overwrite = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-o" && i + 1 < argc) out = argv[++i];
        else if (a == "--size" && i + 1 < argc) size = std::atof(argv[++i]);
        else if (a == "--cell" && i + 1 < argc) cell = std::atof(argv[++i]);
        else if (a == "--overwrite") overwrite = true;
        else {
            std::cerr << "usage: rh_make_sample -o DIR [--size METRES] [--cell METRES] [--overwrite]\n";
            return 2;
        }
    }
    if (out.empty() || !(size >= 500) || !(cell > 0) || size / cell > 20000) {
        std::cerr << "rh_make_sample: -o DIR is required; --size >= 500 and --cell > 0\n";
        return 2;
    }
    try {
        GDALAllRegister();
        CPLSetConfigOption("OGR_CURRENT_DATE", "2000-01-01T00:00:00.000Z");  // reproducible bytes
        fs::create_directories(out);
        const std::string dem_path = out + "/dem.tif", part_path = out + "/partition.gpkg", truth_path = out + "/truth.gpkg";
        for (const auto& p : {dem_path, part_path, truth_path})
            if (fs::exists(p)) {
                if (!overwrite) throw carto::Error(carto::Code::OutputExists, "'" + p + "' exists (use --overwrite)");
                fs::remove(p);
            }
        // One massif per 2400 m: a --size of 4800 repeats it on a 2 x 2 grid of summits (four
        // times the area and the faces, for the scaling benchmark).
        const int copies = std::max(1, int(std::floor(size / 2400.0)));
        carto::Raster dem;
        dem.width = dem.height = int(std::round(size / cell));
        const double x0 = kSummitX - 1200, y1 = kSummitY + 1200;  // copies extend east and south
        dem.gt = {x0, cell, 0, y1, 0, -cell};
        dem.crs_wkt = carto::epsg_wkt(2154);
        dem.data.resize(std::size_t(dem.width) * dem.height);
        for (int r = 0; r < dem.height; ++r)
            for (int c = 0; c < dem.width; ++c) {
                const Point w = dem.to_world(c + 0.5, r + 0.5);
                // Which copy of the massif: shift the point into the first one.
                const double cx = std::floor((w.x - x0) / 2400.0), cy = std::floor((y1 - w.y) / 2400.0);
                const double lx = w.x - cx * 2400.0, ly = w.y + cy * 2400.0;
                double z = elevation(lx, ly);
                // A NoData corner (missing survey) in the south-east of each copy.
                if (lx - kSummitX > 1000 && kSummitY - ly > 1000) z = std::nan("");
                dem.at(c, r) = float(z);
            }
        carto::write_geotiff(dem, dem_path);
        const carto::Terrain terrain = carto::compute_terrain(dem);

        Gpkg part(part_path + ".part.gpkg"), truth(truth_path + ".part.gpkg");
        OGRLayer* faces = part.layer("faces", wkbPolygon, {{"face_id", OFTInteger64}, {"density", OFTReal}});
        OGRLayer* lines = part.layer("lines", wkbLineString, {{"kind", OFTString}});
        OGRLayer* orient = part.layer("orientation", wkbLineString, {{"face_id", OFTInteger64}});
        OGRLayer* ridges = truth.layer("ridges", wkbLineString, {{"ridge", OFTInteger}});
        OGRLayer* thalwegs = truth.layer("thalwegs", wkbLineString, {{"thalweg", OFTInteger}});
        const double step = 10;
        std::int64_t face_id = 1;
        for (int cy = 0; cy < copies; ++cy)
            for (int cx = 0; cx < copies; ++cx) {
                const Point shift{cx * 2400.0, -cy * 2400.0};
                auto moved = [&](std::vector<Point> pts) {
                    for (auto& p : pts) p += shift;
                    return pts;
                };
                auto add_line = [&](OGRLayer* l, const char* field, const char* kind, const std::vector<Point>& pts) {
                    OGRFeature f(l->GetLayerDefn());
                    if (kind) f.SetField(field, kind);
                    OGRLineString ls = linestring(pts);
                    f.SetGeometry(&ls);
                    if (l->CreateFeature(&f) != OGRERR_NONE) throw carto::Error(carto::Code::OutputExists, "cannot write a line");
                };
                for (int k = 0; k < kRidges; ++k) {
                    add_line(lines, "kind", "ridge", moved(ray(k, true, kRockInner, kRockOuter, step)));
                    add_line(lines, "kind", "valley", moved(ray(k, false, kRockInner, kRockOuter, step)));
                    add_line(ridges, "ridge", nullptr, moved(ray(k, true, 0, 1200, step)));
                    add_line(thalwegs, "thalweg", nullptr, moved(ray(k, false, 0, 1200, step)));
                }
                for (double r : {kRockInner, kRockMid, kRockOuter}) {
                    // "Other" lines: arcs closing the faces, from each ridge to the next.
                    for (int k = 0; k < kRidges; ++k)
                        add_line(lines, "kind", "other", moved(arc(r, angle_at(k, true, r), angle_at(k + 1, true, r), step)));
                }
                // Faces: between ridge k and couloir k (and couloir k and ridge k+1), inner and
                // outer band.
                for (int k = 0; k < kRidges; ++k)
                    for (int half = 0; half < 2; ++half)
                        for (int band = 0; band < 2; ++band) {
                            const double r0 = band ? kRockMid : kRockInner, r1 = band ? kRockOuter : kRockMid;
                            // Side a goes outwards, side b comes back: ridge k -> couloir k,
                            // or couloir k -> ridge k+1 (counter-clockwise around the summit).
                            const std::vector<Point> a = half == 0 ? ray(k, true, r0, r1, step) : ray(k, false, r0, r1, step);
                            const std::vector<Point> b = half == 0 ? ray(k, false, r0, r1, step) : ray(k + 1, true, r0, r1, step);
                            std::vector<Point> ring = a;
                            const double phi_a1 = std::atan2(a.back().y - kSummitY, a.back().x - kSummitX);
                            double phi_b1 = std::atan2(b.back().y - kSummitY, b.back().x - kSummitX);
                            while (phi_b1 < phi_a1) phi_b1 += 2 * M_PI;
                            auto outer = arc(r1, phi_a1, phi_b1, step);
                            ring.insert(ring.end(), outer.begin() + 1, outer.end() - 1);
                            ring.insert(ring.end(), b.rbegin(), b.rend());
                            const double phi_b0 = std::atan2(b.front().y - kSummitY, b.front().x - kSummitX);
                            double phi_a0 = std::atan2(a.front().y - kSummitY, a.front().x - kSummitX);
                            while (phi_a0 > phi_b0) phi_a0 -= 2 * M_PI;
                            auto inner = arc(r0, phi_b0, phi_a0, step);
                            ring.insert(ring.end(), inner.begin() + 1, inner.end() - 1);
                            ring = moved(ring);
                            // Density from illumination, orientation from the fall line.
                            tex::Region region(ring, {}, "sample face");
                            double hs = 0, ax = 0, ay = 0;
                            int n = 0;
                            const tex::BBox bb = region.bbox();
                            for (double y = bb.ymin; y < bb.ymax; y += 10)
                                for (double x = bb.xmin; x < bb.xmax; x += 10)
                                    if (region.contains({x, y})) {
                                        const double h = terrain.hillshade.sample({x, y});
                                        const double asp = terrain.aspect.sample({x, y});
                                        const double sl = terrain.slope.nearest({x, y});
                                        if (std::isnan(h) || std::isnan(asp) || std::isnan(sl)) continue;
                                        hs += h;
                                        ax += sl * std::cos(asp);
                                        ay += sl * std::sin(asp);
                                        ++n;
                                    }
                            OGRFeature f(faces->GetLayerDefn());
                            f.SetField("face_id", GIntBig(face_id));
                            f.SetField("density", std::round(100 * std::clamp(1.0 - hs / std::max(n, 1), 0.0, 1.0)) / 100);
                            OGRPolygon poly;
                            OGRLinearRing lr;
                            for (const auto& p : ring) lr.addPoint(p.x, p.y);
                            lr.closeRings();
                            poly.addRing(&lr);
                            f.SetGeometry(&poly);
                            if (faces->CreateFeature(&f) != OGRERR_NONE) throw carto::Error(carto::Code::OutputExists, "cannot write a face");
                            // Orientation line: 80 m along the mean fall line from the centre.
                            const Point c = carto::Point(bb.center());
                            const double ang = std::atan2(ay, ax);
                            Point start = c;
                            for (const auto& q : {c, Point{(a[a.size() / 2].x + b[b.size() / 2].x) / 2 + shift.x,
                                                           (a[a.size() / 2].y + b[b.size() / 2].y) / 2 + shift.y}})
                                if (region.contains(q)) {
                                    start = q;
                                    break;
                                }
                            OGRFeature of(orient->GetLayerDefn());
                            of.SetField("face_id", GIntBig(face_id));
                            OGRLineString ls = linestring({start - Point{std::cos(ang), std::sin(ang)} * 40.0,
                                                           start + Point{std::cos(ang), std::sin(ang)} * 40.0});
                            of.SetGeometry(&ls);
                            if (orient->CreateFeature(&of) != OGRERR_NONE) throw carto::Error(carto::Code::OutputExists, "cannot write an orientation line");
                            ++face_id;
                        }
            }
        part.ds.reset();
        truth.ds.reset();
        fs::rename(part_path + ".part.gpkg", part_path);
        fs::rename(truth_path + ".part.gpkg", truth_path);
        std::printf("rh_make_sample: wrote %s (%dx%d cells of %g m), %s (%lld faces), %s\n", dem_path.c_str(), dem.width,
                    dem.height, cell, part_path.c_str(), (long long)(face_id - 1), truth_path.c_str());
        return 0;
    } catch (const carto::Error& e) {
        std::fprintf(stderr, "rh_make_sample: %s\n", e.what());
        return e.exit_code();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rh_make_sample: %s\n", e.what());
        return 1;
    }
}
