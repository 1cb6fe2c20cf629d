#include "carto/output.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <charconv>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "carto/error.hpp"
#include "gdal_scope.hpp"
#include "gpkg_rtree.hpp"
#include "temp_file.hpp"

namespace fs = std::filesystem;

namespace carto {
namespace {

void num(std::string& s, double v) {
    char buf[64];
    if (std::abs(v) < 5e-4 || !std::isfinite(v)) v = 0;
    auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 3);
    std::size_t n = std::size_t(r.ptr - buf);
    while (n > 0 && buf[n - 1] == '0') --n;
    if (n > 0 && buf[n - 1] == '.') --n;
    s.append(buf, n);
}

std::string xml_escape(const std::string& in) {
    std::string out;
    for (char c : in) {
        if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '&') out += "&amp;";
        else if (c == '"') out += "&quot;";
        else out += c;
    }
    return out;
}

}  // namespace

void check_output(const std::string& path, bool overwrite, const std::string& what) {
    const fs::path p(path);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    if (!fs::is_directory(dir)) throw Error(Code::OutputExists, what + " '" + path + "': the folder does not exist");
    if (fs::exists(p) && !overwrite)
        throw Error(Code::OutputExists, what + " '" + path + "': the file exists (use --overwrite to replace it)");
}

namespace {

// Whether two paths name the same file: the file itself when both exist (symbolic and hard
// links included), else the absolute paths with symbolic links and ./.. resolved.
bool same_file(const std::string& a, const std::string& b) {
    std::error_code ea, eb;
    const bool has_a = fs::exists(a, ea), has_b = fs::exists(b, eb);
    if (has_a && has_b) {
        std::error_code ec;
        return fs::equivalent(a, b, ec);
    }
    if (has_a || has_b) return false;
    const fs::path ca = fs::weakly_canonical(fs::absolute(a, ea), ea);
    const fs::path cb = fs::weakly_canonical(fs::absolute(b, eb), eb);
    return !ea && !eb && ca == cb;
}

}  // namespace

void check_outputs(const std::vector<FileArg>& inputs, const std::vector<FileArg>& outputs, bool overwrite) {
    auto named = [](const FileArg& f) { return f.what + " '" + f.path + "'"; };
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const FileArg& out = outputs[i];
        if (out.path.empty()) continue;
        // An output onto an input would replace the user's data with the result (--overwrite
        // says outputs may be replaced, never inputs).
        for (const FileArg& in : inputs)
            if (!in.path.empty() && fs::exists(in.path) && same_file(out.path, in.path))
                throw Error(Code::OutputExists, named(out) + " is the input " + named(in) +
                                                    ": refusing to write onto an input (choose another output)");
        for (std::size_t j = 0; j < i; ++j)
            if (!outputs[j].path.empty() && same_file(out.path, outputs[j].path))
                throw Error(Code::OutputExists,
                            named(out) + " and " + named(outputs[j]) + " are the same file (choose two outputs)");
        check_output(out.path, overwrite, out.what);
    }
}

namespace {
// The rock families are always written (an empty layer says "none drawn"); the terrain
// families only by the styles that draw them.
bool has_family(const Drawing& d, Family f) {
    if (int(f) < kRockFamilies) return true;
    for (const auto& face : d.faces)
        for (const auto& h : face.hatches)
            if (h.family == f) return true;
    return false;
}
}  // namespace

void write_gpkg(const Drawing& d, const std::string& path, bool spatial_index,
                const std::function<bool(double)>& keep_going) {
    std::size_t total = 0, written = 0;
    for (const auto& face : d.faces) total += face.hatches.size();
    auto check = [&] {
        if (keep_going && ++written % 4096 == 0 && !keep_going(double(written) / double(2 * total)))
            throw Error(Code::Cancelled, "cancelled while writing '" + path + "'");
    };
    register_gdal();
    TempFile tmp(path, ".gpkg");
    {
        // Set on this thread, which writes the file, for this call only (gdal_scope.hpp).
        const ReproducibleGpkg reproducible;
        // The file is a temporary one renamed at the end, so SQLite need not journal or sync.
        const ConfigScope sync("OGR_SQLITE_SYNCHRONOUS", "OFF"), journal("OGR_SQLITE_JOURNAL", "OFF");
        const QuietGdal quiet;
        GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
        if (!drv) throw Error(Code::Failure, "GDAL has no GeoPackage driver");
        std::unique_ptr<GDALDataset> ds(drv->Create(tmp.path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        if (!ds) throw Error(Code::OutputExists, "-o '" + path + "': cannot create (" + CPLGetLastErrorMsg() + ")");
        OGRSpatialReference srs;
        srs.importFromWkt(d.crs_wkt.c_str());
        srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        for (int fam = 0; fam < kFamilies; ++fam) {
            const Family f = Family(fam);
            if (!has_family(d, f)) continue;
            const std::string name = std::string("hatch_") + family_name(f);
            // GDAL 3.6 would fill the R-tree row by row, most of the time spent writing a large
            // drawing: the index is bulk-loaded once the file is closed (gpkg_rtree.cpp).
            const char* lco[] = {"SPATIAL_INDEX=NO", "FID=fid", "GEOMETRY_NAME=geom", nullptr};
            // Stones and hachures are filled shapes: polygons; hatches are lines.
            OGRLayer* layer = ds->CreateLayer(name.c_str(), &srs, family_filled(f) ? wkbPolygon : wkbLineString,
                                              const_cast<char**>(lco));
            if (!layer) throw Error(Code::OutputExists, "-o '" + path + "': cannot create layer " + name);
            OGRFieldDefn fid("face_id", OFTInteger64), ffam("family", OFTString), fsty("style", OFTString),
                fw("width_mm", OFTReal);
            layer->CreateField(&fid);
            layer->CreateField(&ffam);
            layer->CreateField(&fsty);
            layer->CreateField(&fw);
            ds->StartTransaction();
            OGRFeature feat(layer->GetLayerDefn());
            feat.SetField(1, family_name(f));
            feat.SetField(2, d.style.c_str());
            feat.SetField(3, family_width_mm(f));
            for (const auto& face : d.faces)
                for (const auto& h : face.hatches) {
                    if (h.family != f || h.points.size() < 2) continue;
                    check();
                    feat.SetFID(OGRNullFID);
                    feat.SetField(0, GIntBig(face.face_id));
                    auto* ls = family_filled(f) ? new OGRLinearRing() : new OGRLineString();
                    ls->setNumPoints(int(h.points.size() + (h.closed ? 1 : 0)), FALSE);
                    for (std::size_t i = 0; i < h.points.size(); ++i) ls->setPoint(int(i), h.points[i].x, h.points[i].y);
                    if (h.closed) ls->setPoint(int(h.points.size()), h.points[0].x, h.points[0].y);
                    if (family_filled(f)) {
                        auto* poly = new OGRPolygon();
                        poly->addRingDirectly(static_cast<OGRLinearRing*>(ls));
                        feat.SetGeometryDirectly(poly);
                    } else {
                        feat.SetGeometryDirectly(ls);
                    }
                    if (layer->CreateFeature(&feat) != OGRERR_NONE)
                        throw Error(Code::OutputExists, "-o '" + path + "': write failed (" + CPLGetLastErrorMsg() + ")");
                }
            ds->CommitTransaction();
        }
        // Closing the dataset flushes it; the index is added after, then the file is renamed.
    }
    if (spatial_index) {
        for (int fam = 0; fam < kFamilies; ++fam) {
            if (!has_family(d, Family(fam))) continue;
            std::vector<BoxD> boxes;
            for (const auto& face : d.faces)
                for (const auto& h : face.hatches) {
                    if (h.family != Family(fam) || h.points.size() < 2) continue;
                    check();
                    BoxD b{INFINITY, -INFINITY, INFINITY, -INFINITY};
                    for (const auto& p : h.points) {
                        b.minx = std::min(b.minx, p.x);
                        b.maxx = std::max(b.maxx, p.x);
                        b.miny = std::min(b.miny, p.y);
                        b.maxy = std::max(b.maxy, p.y);
                    }
                    boxes.push_back(b);
                }
            bulk_load_rtree(tmp.path, std::string("hatch_") + family_name(Family(fam)), "geom", "fid", boxes);
        }
    }
    tmp.commit(path);
}

void write_svg(const Drawing& d, const std::string& path) {
    const tex::BBox b = d.bounds.empty() ? tex::BBox{0, 0, 1, 1} : d.bounds;
    const double mm_per_unit = 1000.0 / d.scale;
    std::string s;
    s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    s += "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:rh=\"https://rockhatch.invalid/ns\" width=\"";
    num(s, b.width() * mm_per_unit);
    s += "mm\" height=\"";
    num(s, b.height() * mm_per_unit);
    s += "mm\" viewBox=\"0 0 ";
    num(s, b.width());
    s += " ";
    num(s, b.height());
    s += "\">\n<metadata>\n  <rh:georeference crs=\"" + xml_escape(crs_name(d.crs_wkt)) + "\" scale=\"";
    num(s, d.scale);
    s += "\" xmin=\"";
    num(s, b.xmin);
    s += "\" ymin=\"";
    num(s, b.ymin);
    s += "\" xmax=\"";
    num(s, b.xmax);
    s += "\" ymax=\"";
    num(s, b.ymax);
    s += "\" units=\"ground units of the CRS; y = ymax - svg_y, x = xmin + svg_x\" style=\"" + xml_escape(d.style) + "\"/>\n";
    s += "  <rh:crs-wkt>" + xml_escape(d.crs_wkt) + "</rh:crs-wkt>\n</metadata>\n";
    for (int fam = 0; fam < kFamilies; ++fam) {
        const Family f = Family(fam);
        if (!has_family(d, f)) continue;
        s += "<g id=\"";
        s += family_name(f);
        if (family_filled(f)) {
            s += "\" fill=\"black\" stroke=\"none\">\n";
        } else {
            s += "\" fill=\"none\" stroke=\"black\" stroke-linecap=\"round\" stroke-linejoin=\"round\" stroke-width=\"";
            num(s, family_width_mm(f) / mm_per_unit);
            s += "\">\n";
        }
        for (const auto& face : d.faces)
            for (const auto& h : face.hatches) {
                if (h.family != f || h.points.size() < 2) continue;
                s += h.closed ? "<polygon points=\"" : "<polyline points=\"";
                for (std::size_t i = 0; i < h.points.size(); ++i) {
                    if (i) s += ' ';
                    num(s, h.points[i].x - b.xmin);
                    s += ',';
                    num(s, b.ymax - h.points[i].y);
                }
                s += "\"/>\n";
            }
        s += "</g>\n";
    }
    s += "</svg>\n";
    TempFile tmp(path, ".svg");
    {
        std::ofstream out(tmp.path, std::ios::binary);
        out << s;
        out.flush();
        if (!out) throw Error(Code::OutputExists, "-o '" + path + "': write failed");
    }
    tmp.commit(path);
}

void write_png(const Drawing& d, const std::string& path, int pixels, const Raster* hillshade) {
    const tex::BBox b = d.bounds.empty() ? tex::BBox{0, 0, 1, 1} : d.bounds;
    const double upp = std::max(b.width(), b.height()) / pixels;  // ground units per pixel
    const int w = std::max(1, int(std::ceil(b.width() / upp))), h = std::max(1, int(std::ceil(b.height() / upp)));
    std::vector<float> img(std::size_t(w) * h, 1.0f);
    if (hillshade) {
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) {
                const double v = hillshade->sample({b.xmin + (c + 0.5) * upp, b.ymax - (r + 0.5) * upp});
                if (!std::isnan(v)) img[std::size_t(r) * w + c] = float(0.82 + 0.18 * v);
            }
    }
    // Strokes: darken pixels by coverage of a line of the family's width (at least one pixel).
    auto stamp = [&](double x, double y, double radius, float ink) {
        const int c0 = int(std::floor(x - radius - 1)), c1 = int(std::ceil(x + radius + 1));
        const int r0 = int(std::floor(y - radius - 1)), r1 = int(std::ceil(y + radius + 1));
        for (int r = std::max(0, r0); r <= std::min(h - 1, r1); ++r)
            for (int c = std::max(0, c0); c <= std::min(w - 1, c1); ++c) {
                const double dist = std::hypot(c + 0.5 - x, r + 0.5 - y);
                const double cover = std::clamp(radius + 0.5 - dist, 0.0, 1.0);
                float& px = img[std::size_t(r) * w + c];
                px = std::min(px, float(1.0 - ink * cover));
            }
    };
    // A filled ring (stone, hachure): the pixels whose centre it holds (even-odd scan lines),
    // its outline stamped below as a half-pixel stroke for the edge.
    auto fill = [&](const std::vector<Point>& ring, float ink) {
        std::vector<std::pair<double, double>> px;
        double ymin = INFINITY, ymax = -INFINITY;
        for (const Point& q : ring) {
            px.push_back({(q.x - b.xmin) / upp, (b.ymax - q.y) / upp});
            ymin = std::min(ymin, px.back().second), ymax = std::max(ymax, px.back().second);
        }
        std::vector<double> xs;
        for (int r = std::max(0, int(std::floor(ymin))); r <= std::min(h - 1, int(std::ceil(ymax))); ++r) {
            const double y = r + 0.5;
            xs.clear();
            for (std::size_t i = 0; i < px.size(); ++i) {
                const auto& [x0, y0] = px[i];
                const auto& [x1, y1] = px[(i + 1) % px.size()];
                if ((y0 <= y) != (y1 <= y)) xs.push_back(x0 + (y - y0) / (y1 - y0) * (x1 - x0));
            }
            std::sort(xs.begin(), xs.end());
            for (std::size_t i = 0; i + 1 < xs.size(); i += 2)
                for (int c = std::max(0, int(std::ceil(xs[i] - 0.5))); c <= std::min(w - 1, int(std::floor(xs[i + 1] - 0.5))); ++c) {
                    float& v = img[std::size_t(r) * w + c];
                    v = std::min(v, 1.0f - ink);
                }
        }
    };
    for (const auto& face : d.faces)
        for (const auto& hh : face.hatches) {
            if (family_filled(hh.family) && hh.closed) fill(hh.points, 0.9f);
            const double radius = std::max(0.5, family_width_mm(hh.family) * d.scale / 1000.0 / upp / 2);
            const std::size_t n = hh.points.size();
            const std::size_t segs = hh.closed ? n : n - 1;
            for (std::size_t i = 0; i < segs && n > 1; ++i) {
                const Point a = hh.points[i], q = hh.points[(i + 1) % n];
                const double ax = (a.x - b.xmin) / upp, ay = (b.ymax - a.y) / upp;
                const double bx = (q.x - b.xmin) / upp, by = (b.ymax - q.y) / upp;
                const int steps = std::max(1, int(std::ceil(std::hypot(bx - ax, by - ay) * 2)));
                for (int k = 0; k <= steps; ++k) {
                    const double t = double(k) / steps;
                    stamp(ax + (bx - ax) * t, ay + (by - ay) * t, radius, 0.9f);
                }
            }
        }
    std::vector<unsigned char> bytes(img.size());
    for (std::size_t i = 0; i < img.size(); ++i) bytes[i] = (unsigned char)std::lround(std::clamp(img[i], 0.0f, 1.0f) * 255);
    write_png_pixels(bytes, w, h, 1, path, "-o");
}

void write_png_pixels(const std::vector<unsigned char>& pixels, int w, int h, int bands, const std::string& path,
                      const std::string& what) {
    // GDAL writes the PNG (through an in-memory raster): it is loaded anyway, whereas
    // OpenImageIO would add some 150 shared libraries to every start of the program.
    TempFile tmp(path, ".png");
    register_gdal();
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
    if (!mem || !png) throw Error(Code::Failure, "GDAL has no PNG driver");
    std::unique_ptr<GDALDataset> src(mem->Create("", w, h, bands, GDT_Byte, nullptr));
    std::vector<unsigned char> buf(pixels);
    if (src->RasterIO(GF_Write, 0, 0, w, h, buf.data(), w, h, GDT_Byte, bands, nullptr, bands,
                      std::size_t(w) * bands, 1, nullptr) != CE_None)
        throw Error(Code::OutputExists, what + " '" + path + "': cannot build the preview");
    std::unique_ptr<GDALDataset> out;
    {
        const QuietGdal quiet;
        out.reset(png->CreateCopy(tmp.path.c_str(), src.get(), FALSE, nullptr, nullptr, nullptr));
    }
    if (!out) throw Error(Code::OutputExists, what + " '" + path + "': cannot write the PNG (" + CPLGetLastErrorMsg() + ")");
    out.reset();
    std::error_code ec;
    std::filesystem::remove(tmp.path + ".aux.xml", ec);
    tmp.commit(path);
}

}  // namespace carto
