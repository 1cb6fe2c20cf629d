#include "carto/output.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>

#include "carto/error.hpp"
#include "libtex/parallel.hpp"
#include "libtex/region.hpp"
#include "libtex/svg.hpp"
#include "gdal_scope.hpp"
#include "gpkg_file.hpp"
#include "gpkg_rtree.hpp"
#include "preview.hpp"
#include "temp_file.hpp"
#include "xml_text.hpp"

namespace fs = std::filesystem;

namespace carto {
namespace {

void num(std::string& s, double v) { tex::append_svg_number(s, v); }


// The R-tree box of a feature's points.
BoxD box_of(const std::vector<Point>& pts) {
    BoxD b{INFINITY, -INFINITY, INFINITY, -INFINITY};
    for (const auto& p : pts) {
        b.minx = std::min(b.minx, p.x);
        b.maxx = std::max(b.maxx, p.x);
        b.miny = std::min(b.miny, p.y);
        b.maxy = std::max(b.maxy, p.y);
    }
    return b;
}

// The polygons of one crest ornament: each outer ring (counter-clockwise) with the holes
// (clockwise rings) whose first point it holds, a hole going to the smallest such ring.
std::vector<std::vector<std::size_t>> crest_polygons(const CrestOrnament& c) {
    std::vector<std::vector<std::size_t>> polys;
    std::vector<double> area;
    std::vector<std::size_t> outer_of_poly;
    for (std::size_t i = 0; i < c.rings.size(); ++i)
        if (c.rings[i].size() >= 3 && tex::signed_area(c.rings[i]) > 0) {
            polys.push_back({i});
            area.push_back(tex::signed_area(c.rings[i]));
        }
    for (std::size_t i = 0; i < c.rings.size(); ++i) {
        if (c.rings[i].size() < 3 || tex::signed_area(c.rings[i]) > 0) continue;
        std::size_t best = polys.size();
        for (std::size_t k = 0; k < polys.size(); ++k)
            if (tex::point_in_ring(c.rings[i][0], c.rings[polys[k][0]]) && (best == polys.size() || area[k] < area[best]))
                best = k;
        if (best < polys.size()) polys[best].push_back(i);
    }
    return polys;
}

}  // namespace

void check_output(const std::string& path, bool overwrite, const std::string& what) {
    // A folder output (DIR/ of vector tiles) is checked as the folder's own name.
    std::string name = path;
    while (name.size() > 1 && name.back() == '/') name.pop_back();
    const fs::path p(name);
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

bool has_family(const Drawing& d, Family f) {
    if (int(f) < kRockFamilies) return true;
    for (const auto& face : d.faces)
        for (const auto& h : face.hatches)
            if (h.family == f) return true;
    return false;
}

namespace {

// Receives the hatches of one family, each as the points written (a closed hatch with its
// first point repeated at the end), with its face and style.
using HatchSink = std::function<void(std::int64_t face_id, const char* style, const std::vector<Point>& points)>;

// Receives the polygons of the crest ornaments, each as its ridge id, style and rings (the
// outer ring first, then its holes; without the first point repeated).
using CrestSink = std::function<void(std::int64_t ridge_id, const char* style, const std::vector<std::vector<Point>>& rings)>;
using CrestSource = std::function<void(const CrestSink&)>;

// The drawing's frame (Drawing::bounds: the faces drawn, their crests and the terrain's
// extent; a hatch GeoPackage's hatches alone may cover less) is kept in the file as this
// metadata item, so that an SVG or PNG drawn back from it (a tiled run's merged tiles) has
// the frame of the run that wrote it: "xmin ymin xmax ymax", each the shortest text that
// reads back to the same double (std::to_chars: no locale, which QGIS's process may set).
constexpr const char* kFrameKey = "RH_FRAME";

std::string frame_text(const tex::BBox& b) {
    std::string s;
    char buf[32];
    for (double v : {b.xmin, b.ymin, b.xmax, b.ymax}) {
        if (!s.empty()) s += ' ';
        s.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
    }
    return s;
}

// The frame a hatch GeoPackage holds (empty if none, as in files of older versions).
tex::BBox read_frame(GDALDataset& ds) {
    tex::BBox b;
    const char* t = ds.GetMetadataItem(kFrameKey);
    if (!t) return b;
    const char* end = t + std::strlen(t);
    double v[4];
    for (double& x : v) {
        while (t < end && *t == ' ') ++t;
        const auto r = std::from_chars(t, end, x);
        if (r.ec != std::errc() || !std::isfinite(x)) return b;
        t = r.ptr;
    }
    if (v[0] <= v[2] && v[1] <= v[3]) {
        b.add(Point{v[0], v[1]});
        b.add(Point{v[2], v[3]});
    }
    return b;
}

// The hatch GeoPackage: one layer per family that is `present` (fid, geom, face_id, family,
// style, width_mm; LineStrings, Polygons for the filled families), written family by family
// from `source`, which hands every hatch of the
// family it is asked for to the sink, in order. `total` (hatches, for the progress) may be an
// estimate. The R-trees are bulk-loaded once the file is closed; the file is renamed in
// place at the end. A non-empty `frame` is kept in the file (kFrameKey).
void write_hatch_gpkg(const std::string& path, const std::string& crs_wkt, bool spatial_index, std::size_t total,
                      const std::function<bool(double)>& keep_going,
                      const std::function<void(Family, const HatchSink&)>& source,
                      const std::function<bool(Family)>& present,
                      const CrestSource& crests, const tex::BBox& frame) {
    std::size_t written = 0;
    auto check = [&] {
        if (keep_going && ++written % 4096 == 0 &&
            !keep_going(std::min(1.0, double(written) / double(std::max<std::size_t>(1, total)))))
            throw Error(Code::Cancelled, "cancelled while writing '" + path + "'");
    };
    GpkgWriter out(path, crs_wkt, spatial_index);
    if (!frame.empty()) out.set_metadata(kFrameKey, frame_text(frame));
    for (int fam = 0; fam < kFamilies; ++fam) {
        const Family f = Family(fam);
        if (!present(f)) continue;
        // Stones and hachures are filled shapes: polygons; hatches are lines.
        const int layer = out.add_layer(std::string("hatch_") + family_name(f), family_filled(f) ? wkbPolygon : wkbLineString,
                                        {{"face_id", OFTInteger64}, {"family", OFTString}, {"style", OFTString},
                                         {"width_mm", OFTReal}});
        out.begin();
        OGRFeature feat(out.definition(layer));
        feat.SetField(1, family_name(f));
        feat.SetField(3, family_width_mm(f));
        source(f, [&](std::int64_t face_id, const char* style, const std::vector<Point>& pts) {
            if (pts.size() < 2) return;
            check();
            feat.SetField(0, GIntBig(face_id));
            feat.SetField(2, style);
            // Stones and hachures are filled shapes (closed: the first point repeated).
            auto* ls = family_filled(f) ? new OGRLinearRing() : new OGRLineString();
            ls->setNumPoints(int(pts.size()), FALSE);
            for (std::size_t i = 0; i < pts.size(); ++i) ls->setPoint(int(i), pts[i].x, pts[i].y);
            if (family_filled(f)) {
                auto* poly = new OGRPolygon();
                poly->addRingDirectly(static_cast<OGRLinearRing*>(ls));
                feat.SetGeometryDirectly(poly);
            } else {
                feat.SetGeometryDirectly(ls);
            }
            out.put(layer, feat, box_of(pts));
        });
        out.end();
    }
    if (crests) {
        const int layer = out.add_layer("crest", wkbPolygon, {{"ridge_id", OFTInteger64}, {"style", OFTString}});
        out.begin();
        OGRFeature feat(out.definition(layer));
        crests([&](std::int64_t ridge_id, const char* style, const std::vector<std::vector<Point>>& rings) {
            if (rings.empty()) return;
            feat.SetField(0, GIntBig(ridge_id));
            feat.SetField(1, style);
            auto* pg = new OGRPolygon();
            for (const auto& pts : rings) {
                OGRLinearRing ring;
                ring.setNumPoints(int(pts.size() + 1), FALSE);
                for (std::size_t i = 0; i <= pts.size(); ++i) ring.setPoint(int(i), pts[i % pts.size()].x, pts[i % pts.size()].y);
                pg->addRing(&ring);
            }
            feat.SetGeometryDirectly(pg);
            out.put(layer, feat, box_of(rings[0]));
        });
        out.end();
    }
    out.commit();
}

// A hatch GeoPackage written by write_gpkg, open for reading; `what` names it in errors.
DatasetPtr open_hatches(const std::string& path, const std::string& what) {
    register_gdal();
    if (!fs::exists(path)) throw Error(Code::InputMissing, what + " '" + path + "': no such file");
    DatasetPtr ds(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    if (!ds) throw Error(Code::InputMissing, what + " '" + path + "': not a GeoPackage OGR can read");
    for (int fam = 0; fam < kRockFamilies; ++fam)
        if (!ds->GetLayerByName((std::string("hatch_") + family_name(Family(fam))).c_str()))
            throw Error(Code::BadLayer, what + " '" + path + "': no layer hatch_" + family_name(Family(fam)) +
                                            " (not a rockhatch output)");
    return ds;
}

// Every feature of layer hatch_<family> in fid order, as (face id, style, points).
void read_family(GDALDataset& ds, Family f, const std::string& what, const HatchSink& sink) {
    OGRLayer* layer = ds.GetLayerByName((std::string("hatch_") + family_name(f)).c_str());
    if (!layer) return;  // a terrain family the drawing did not have (open_hatches checked the rock ones)
    const int face_idx = layer->GetLayerDefn()->GetFieldIndex("face_id");
    const int style_idx = layer->GetLayerDefn()->GetFieldIndex("style");
    if (face_idx < 0 || style_idx < 0)
        throw Error(Code::BadLayer, what + ": layer " + layer->GetName() + " has no face_id or style field");
    std::vector<Point> pts;
    layer->ResetReading();
    for (auto& feat : *layer) {
        const OGRGeometry* g = feat->GetGeometryRef();
        if (!g) continue;
        // A hatch is a line; a stone or a hachure a polygon of one ring (its points as written).
        const OGRSimpleCurve* ls = nullptr;
        if (wkbFlatten(g->getGeometryType()) == wkbLineString) ls = g->toLineString();
        else if (wkbFlatten(g->getGeometryType()) == wkbPolygon && family_filled(f)) ls = g->toPolygon()->getExteriorRing();
        if (!ls) continue;
        pts.resize(std::size_t(ls->getNumPoints()));
        for (int i = 0; i < ls->getNumPoints(); ++i) pts[std::size_t(i)] = {ls->getX(i), ls->getY(i)};
        sink(feat->GetFieldAsInteger64(face_idx), feat->GetFieldAsString(style_idx), pts);
    }
}

// Every polygon of layer "crest", in fid order, as (ridge id, style, rings); false when the
// file has no such layer (a run without crest ornaments).
bool read_crests(GDALDataset& ds, const std::string& what, const CrestSink& sink) {
    OGRLayer* layer = ds.GetLayerByName("crest");
    if (!layer) return false;
    const int id_idx = layer->GetLayerDefn()->GetFieldIndex("ridge_id");
    const int style_idx = layer->GetLayerDefn()->GetFieldIndex("style");
    if (id_idx < 0 || style_idx < 0) throw Error(Code::BadLayer, what + ": layer crest has no ridge_id or style field");
    std::vector<std::vector<Point>> rings;
    layer->ResetReading();
    for (auto& feat : *layer) {
        const OGRGeometry* g = feat->GetGeometryRef();
        if (!g || wkbFlatten(g->getGeometryType()) != wkbPolygon) continue;
        rings.clear();
        for (const OGRLinearRing* ring : *g->toPolygon()) {
            std::vector<Point>& pts = rings.emplace_back();
            for (int i = 0; i + 1 < ring->getNumPoints(); ++i) pts.push_back({ring->getX(i), ring->getY(i)});
        }
        sink(feat->GetFieldAsInteger64(id_idx), feat->GetFieldAsString(style_idx), rings);
    }
    return true;
}

}  // namespace

void write_gpkg(const Drawing& d, const std::string& path, bool spatial_index,
                const std::function<bool(double)>& keep_going) {
    std::size_t total = 0;
    for (const auto& face : d.faces) total += face.hatches.size();
    std::vector<Point> pts;
    write_hatch_gpkg(path, d.crs_wkt, spatial_index, total, keep_going, [&](Family f, const HatchSink& sink) {
        for (const auto& face : d.faces)
            for (const auto& h : face.hatches) {
                if (h.family != f) continue;
                pts.assign(h.points.begin(), h.points.end());
                if (h.closed && !pts.empty()) pts.push_back(pts.front());
                sink(face.face_id, d.style.c_str(), pts);
            }
    }, [&](Family f) { return has_family(d, f); }, d.crests ? CrestSource([&](const CrestSink& sink) {
        std::vector<std::vector<Point>> rings;
        for (const auto& c : *d.crests)
            for (const auto& poly : crest_polygons(c)) {
                rings.clear();
                for (std::size_t r : poly) rings.push_back(c.rings[r]);
                sink(c.id, d.style.c_str(), rings);
            }
    }) : CrestSource(), d.bounds);
}

std::size_t merge_gpkg(const std::vector<std::string>& parts, const std::string& path, bool spatial_index,
                       const std::function<bool(double)>& keep_going) {
    if (parts.empty()) throw Error(Code::Usage, "merge: no GeoPackage to merge into '" + path + "'");
    std::string crs_wkt;
    std::size_t total = 0;
    bool crests = false;  // a crest layer in any part: one in the result
    std::vector<char> present(kFamilies, 0);  // the rock families, and the terrain ones of any part
    tex::BBox frame;
    for (const auto& part : parts) {
        auto ds = open_hatches(part, "tile");
        for (int fam = 0; fam < kFamilies; ++fam)
            if (OGRLayer* l = ds->GetLayerByName((std::string("hatch_") + family_name(Family(fam))).c_str())) {
                total += std::size_t(std::max<GIntBig>(0, l->GetFeatureCount()));
                present[std::size_t(fam)] = 1;
            }
        if (crs_wkt.empty()) crs_wkt = wkt2_of(ds->GetLayer(0)->GetSpatialRef());
        crests = crests || ds->GetLayerByName("crest");
        // The parts' frames together: the whole run's (each face, ridge and terrain element is
        // drawn by one tile, and a tile drawing terrain frames the whole DEM as the run does).
        frame.add(read_frame(*ds));
    }
    std::size_t n = 0;
    write_hatch_gpkg(path, crs_wkt, spatial_index, total, keep_going, [&](Family f, const HatchSink& sink) {
        // One part open at a time: memory does not grow with the number of tiles.
        for (const auto& part : parts) {
            auto ds = open_hatches(part, "tile");
            read_family(*ds, f, "tile '" + part + "'", [&](std::int64_t id, const char* style, const std::vector<Point>& p) {
                ++n;
                sink(id, style, p);
            });
        }
    }, [&](Family f) { return present[std::size_t(f)] != 0; }, crests ? CrestSource([&](const CrestSink& sink) {
        for (const auto& part : parts) read_crests(*open_hatches(part, "tile"), "tile '" + part + "'", sink);
    }) : CrestSource(), frame);
    return n;
}

Drawing read_gpkg(const std::string& path, double scale) {
    auto ds = open_hatches(path, "hatches");
    Drawing d;
    d.scale = scale;
    d.crs_wkt = wkt2_of(ds->GetLayer(0)->GetSpatialRef());
    std::map<std::int64_t, std::size_t> face_index;
    for (int fam = 0; fam < kFamilies; ++fam)
        read_family(*ds, Family(fam), "hatches '" + path + "'", [&](std::int64_t id, const char* style,
                                                                   const std::vector<Point>& p) {
            if (d.style.empty()) d.style = style;
            auto [it, fresh] = face_index.emplace(id, d.faces.size());
            if (fresh) d.faces.push_back({id, {}});
            Hatch h;
            h.points = p;
            h.family = Family(fam);
            if (h.points.size() > 2 && h.points.front() == h.points.back()) {
                h.points.pop_back();
                h.closed = true;
            }
            for (const auto& q : h.points) d.bounds.add(q);
            d.faces[it->second].hatches.push_back(std::move(h));
        });
    std::vector<CrestOrnament> crests;
    if (read_crests(*ds, "hatches '" + path + "'", [&](std::int64_t id, const char*, const std::vector<std::vector<Point>>& rings) {
            CrestOrnament& c = crests.emplace_back();
            c.id = id;
            c.rings = rings;
            for (const auto& ring : rings)
                for (const Point& q : ring) d.bounds.add(q);
        }))
        d.crests = std::move(crests);
    if (const tex::BBox frame = read_frame(*ds); !frame.empty()) d.bounds = frame;
    return d;
}

void write_svg(const Drawing& d, const std::string& path) {
    const tex::BBox b = d.bounds.empty() ? tex::BBox{0, 0, 1, 1} : d.bounds;
    const double mm_per_unit = 1000.0 / d.scale;
    // The text is made in pieces: the header, then per family the strokes of each face,
    // formatted face by face in parallel (the numbers are most of the work), then written
    // in order; the bytes do not depend on the thread count.
    std::vector<std::string> parts;
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
        parts.push_back(std::move(s));
        s.clear();
        std::vector<std::string> faces(d.faces.size());
        tex::parallel_for(d.faces.size(), [&](std::size_t k) {
            std::string& t = faces[k];
            // About 15 bytes a point and 30 a stroke: one allocation, not a doubling string.
            std::size_t bytes = 0;
            for (const auto& h : d.faces[k].hatches)
                if (h.family == f) bytes += 30 + 15 * h.points.size();
            t.reserve(bytes);
            for (const auto& h : d.faces[k].hatches) {
                if (h.family != f || h.points.size() < 2) continue;
                t += h.closed ? "<polygon points=\"" : "<polyline points=\"";
                for (std::size_t i = 0; i < h.points.size(); ++i) {
                    if (i) t += ' ';
                    num(t, h.points[i].x - b.xmin);
                    t += ',';
                    num(t, b.ymax - h.points[i].y);
                }
                t += "\"/>\n";
            }
        });
        for (auto& t : faces)
            if (!t.empty()) parts.push_back(std::move(t));
        s += "</g>\n";
    }
    if (d.crests) {
        // Filled, holes by even-odd: one path per ridge.
        s += "<g id=\"crest\" fill=\"black\" fill-rule=\"evenodd\" stroke=\"none\">\n";
        for (const auto& c : *d.crests) {
            s += "<path d=\"";
            for (const auto& ring : c.rings) {
                for (std::size_t i = 0; i < ring.size(); ++i) {
                    s += i ? " L" : "M";
                    num(s, ring[i].x - b.xmin);
                    s += ',';
                    num(s, b.ymax - ring[i].y);
                }
                s += " Z";
            }
            s += "\"/>\n";
        }
        s += "</g>\n";
    }
    s += "</svg>\n";
    parts.push_back(std::move(s));
    TempFile tmp(path, ".svg");
    {
        std::ofstream out(tmp.path, std::ios::binary);
        for (const auto& t : parts) out.write(t.data(), std::streamsize(t.size()));
        out.flush();
        if (!out) throw Error(Code::OutputExists, "-o '" + path + "': write failed");
    }
    tmp.commit(path);
}

void write_png(const Drawing& d, const std::string& path, int pixels, const Raster* hillshade) {
    Preview pv(d.bounds, pixels, 1, "-o '" + path + "'");
    const tex::PixelGrid& g = pv.grid();
    if (hillshade)
        for (int r = 0; r < g.height; ++r)
            for (int c = 0; c < g.width; ++c) {
                const double v = hillshade->sample(g.Centre(c, r));
                if (!std::isnan(v)) *pv.at(c, r) = float(0.82 + 0.18 * v);
            }
    // Every stroke and filled shape in one ink (90 %): lines of the family's width on paper,
    // at least a pixel wide; stones, hachures and crest ornaments filled.
    std::vector<float> cover = pv.blank();
    std::vector<std::optional<tex::StrokeCoverage>> strokes(kFamilies);
    for (const auto& face : d.faces)
        for (const auto& hh : face.hatches) {
            auto& s = strokes[std::size_t(hh.family)];
            if (!s) s.emplace(g, std::max(g.pixel, family_width_mm(hh.family) * d.scale / 1000.0));
            s->Add(hh.points, hh.closed);
            if (family_filled(hh.family) && hh.closed) tex::CoverFill(g, {hh.points}, cover);
        }
    for (const auto& s : strokes)
        if (s) s->Render(cover);
    if (d.crests)
        for (const auto& c : *d.crests) tex::CoverFill(g, c.rings, cover);
    pv.darken(cover, {0.1f, 0.1f, 0.1f});
    pv.write_png(path, "-o");
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
