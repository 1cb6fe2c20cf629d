#include "carto/output.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <sqlite3.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cctype>
#include <cstdlib>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

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

// The fields of a hatch layer, by index.
struct HatchFields {
    int face_id, family, style, width_mm;
};

// Sets a hatch feature: its fields and its geometry (a LineString; a Polygon of one ring for
// the filled families, whose points close the ring).
void set_hatch(OGRFeature& feat, const HatchFields& k, Family f, std::int64_t face_id, const char* style,
               const std::vector<Point>& pts) {
    feat.SetField(k.face_id, GIntBig(face_id));
    feat.SetField(k.family, family_name(f));
    feat.SetField(k.style, style);
    feat.SetField(k.width_mm, family_width_mm(f));
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
}

// The attribute table of the faces' fingerprints (face_id, fingerprint), and the metadata
// item of a run key of Fingerprints::run ("version" -> RH_RUN_VERSION).
constexpr const char* kFacesTable = "rockhatch_faces";
std::string run_key(const std::string& key) {
    std::string k = "RH_RUN_";
    for (char c : key) k += char(std::toupper((unsigned char)c));
    return k;
}
std::string face_index_sql(const std::string& table) {
    return "CREATE INDEX \"" + table + "_face_id\" ON \"" + table + "\" (face_id)";
}

// The hatch GeoPackage. Layers: one per family (fid, geom, face_id, family, style, width_mm;
// LineStrings, Polygons for the filled families): the rock families always, in family order,
// then the other families a hatch of the drawing has, in family order, then "crest" (fid, geom,
// ridge_id, style) with the crest ornaments, then the fingerprints table; the frame and the run
// keys as metadata; the face_id indexes and the R-trees once the rows are in. In each layer the
// features are in face order, then in the order of the face's hatches.
std::string hatch_table(Family f) { return std::string("hatch_") + family_name(f); }

int add_hatch_layer(GpkgWriter& out, Family f) {
    // Stones and hachures are filled shapes: polygons; hatches are lines.
    return out.add_layer(hatch_table(f), family_filled(f) ? wkbPolygon : wkbLineString,
                         {{"face_id", OFTInteger64}, {"family", OFTString}, {"style", OFTString}, {"width_mm", OFTReal}});
}

// A hatch's row: the points written (a closed hatch with its first point repeated at the end;
// fewer than two: no row), a LineString, or a Polygon of one ring for the filled families.
bool hatch_row(GpkgRows& rows, int layer, Family f, std::int64_t face_id, std::string_view style, const Point* pts,
               std::size_t n, bool closed) {
    const bool close = closed && n > 0;
    if (n + (close ? 1 : 0) < 2) return false;
    rows.line(layer, pts, n, close, family_filled(f));
    rows.integer(face_id);
    rows.text(family_name(f));
    rows.text(style);
    rows.real(family_width_mm(f));
    return true;
}

// After the hatch layers: the frame, the crest layer, the fingerprints, the indexes.
void write_rest(GpkgWriter& out, const tex::BBox& frame, const CrestSource& crests, const Fingerprints* fingerprints,
                const std::vector<int>& hatch_layers, const std::vector<char>& indexed,
                const std::function<bool(double)>& keep_going, const std::string& path) {
    auto check = [&](double f) {
        if (keep_going && !keep_going(f)) throw Error(Code::Cancelled, "cancelled while writing '" + path + "'");
    };
    check(0.25);
    if (!frame.empty()) out.set_metadata(kFrameKey, frame_text(frame));
    if (crests) {
        const int layer = out.add_layer("crest", wkbPolygon, {{"ridge_id", OFTInteger64}, {"style", OFTString}});
        GpkgRows rows(out.srs_id());
        crests([&](std::int64_t ridge_id, const char* style, const std::vector<std::vector<Point>>& rings) {
            if (rings.empty()) return;
            rows.polygon(layer, rings);
            rows.integer(ridge_id);
            rows.text(style);
        });
        out.insert(rows);
    }
    check(0.5);
    if (fingerprints) {
        for (const auto& [key, value] : fingerprints->run) out.set_metadata(run_key(key).c_str(), value);
        const int layer = out.add_layer(kFacesTable, wkbNone,
                                        {{"face_id", OFTInteger64}, {"fingerprint", OFTString}, {"xmin", OFTReal},
                                         {"ymin", OFTReal}, {"xmax", OFTReal}, {"ymax", OFTReal}});
        GpkgRows rows(out.srs_id());
        for (std::size_t i = 0; i < fingerprints->faces.size(); ++i) {
            rows.attributes(layer);
            rows.integer(fingerprints->faces[i].first);
            rows.text(fingerprints->faces[i].second);
            // The face's box as drawn (NULL when unknown or empty).
            const tex::BBox b = i < fingerprints->boxes.size() ? fingerprints->boxes[i] : tex::BBox{};
            for (double v : {b.xmin, b.ymin, b.xmax, b.ymax}) rows.real(b.empty() ? std::nan("") : v);
        }
        out.insert(rows);
        // The edit loop finds a face's features by face_id (the layers made before the faces
        // were drawn have their index already).
        for (int fam = 0; fam < kFamilies; ++fam)
            if (hatch_layers[std::size_t(fam)] >= 0 && !indexed[std::size_t(fam)]) out.sql(face_index_sql(hatch_table(Family(fam))));
        out.sql(std::string("CREATE UNIQUE INDEX \"") + kFacesTable + "_face_id\" ON \"" + kFacesTable + "\" (face_id)");
    }
    check(0.75);
}

// The crest polygons of a drawing (each ornament's outer rings with their holes).
CrestSource drawing_crests(const Drawing& d) {
    if (!d.crests) return {};
    return [&d](const CrestSink& sink) {
        std::vector<std::vector<Point>> rings;
        for (const auto& c : *d.crests)
            for (const auto& poly : crest_polygons(c)) {
                rings.clear();
                for (std::size_t r : poly) rings.push_back(c.rings[r]);
                sink(c.id, d.style.c_str(), rings);
            }
    };
}

// The rows of one face, encoded on a drawing thread: those of the layers made already, and
// those of the other families (tagged with their family), kept until their layers are made.
struct FaceRows {
    GpkgRows now, later;
    unsigned families = 0;  // bit f: the face has a hatch of family f
    bool ready = false;
};

// Inserts the faces' rows in face order on a thread of its own while the callers encode later
// faces. A face waits to be queued while the queue holds more than kQueueBytes (the face the
// inserter waits for never waits), so memory stays bounded whatever the order faces end in.
class OrderedInserter {
public:
    static constexpr std::size_t kQueueBytes = std::size_t(16) << 20;
    OrderedInserter(GpkgWriter& out, std::size_t faces, std::size_t total, const std::function<bool(double)>& keep_going,
                    const std::string& path)
        : out_(out), slots_(faces), total_(total), keep_going_(keep_going), path_(path), later_(kFamilies) {
        thread_ = std::thread([this] { run(); });
    }
    ~OrderedInserter() { stop(); }
    // Hands face k's rows over (after the face failed: empty, and `failed`).
    void put(std::size_t k, FaceRows&& rows, bool failed) {
        std::unique_lock lock(m_);
        const std::size_t bytes = rows.now.bytes() + rows.later.bytes();
        cv_.wait(lock, [&] { return k == next_ || queued_ + bytes <= kQueueBytes || stop_; });
        if (failed) stop_ = true;
        queued_ += bytes;
        slots_[k] = std::move(rows);
        slots_[k].ready = true;
        cv_.notify_all();
    }
    bool stopped() {
        std::lock_guard lock(m_);
        return stop_;
    }
    // Waits for every face; rethrows the inserter's error. Then later(f) holds the rows of
    // family f kept for later (tagged f), and families() the families drawn.
    void finish() {
        if (thread_.joinable()) thread_.join();
        if (error_) std::rethrow_exception(error_);
    }
    GpkgRows& later(int f) { return later_[std::size_t(f)]; }
    unsigned families() const { return families_; }

private:
    void stop() {
        {
            std::lock_guard lock(m_);
            stop_ = true;
        }
        cv_.notify_all();
        if (thread_.joinable()) thread_.join();
    }
    void run() {
        try {
            std::size_t written = 0;
            for (;;) {
                FaceRows rows;
                {
                    std::unique_lock lock(m_);
                    cv_.wait(lock, [&] { return stop_ || next_ == slots_.size() || slots_[next_].ready; });
                    if (stop_ || next_ == slots_.size()) return;
                    rows = std::move(slots_[next_]);
                    slots_[next_] = FaceRows{GpkgRows(), GpkgRows()};
                }
                out_.insert(rows.now);
                if (!rows.later.empty())
                    for (int f = 0; f < kFamilies; ++f) later_[std::size_t(f)].append(rows.later, f, f);
                families_ |= rows.families;
                const std::size_t before = written;
                written += rows.now.size();
                if (keep_going_ && written / 4096 != before / 4096 &&
                    !keep_going_(std::min(1.0, double(written) / double(std::max<std::size_t>(1, total_)))))
                    throw Error(Code::Cancelled, "cancelled while writing '" + path_ + "'");
                {
                    std::lock_guard lock(m_);
                    queued_ -= rows.now.bytes() + rows.later.bytes();
                    ++next_;
                }
                cv_.notify_all();
            }
        } catch (...) {
            error_ = std::current_exception();
            {
                std::lock_guard lock(m_);
                stop_ = true;
            }
            cv_.notify_all();
        }
    }
    GpkgWriter& out_;
    std::vector<FaceRows> slots_;
    std::size_t total_;
    const std::function<bool(double)>& keep_going_;
    const std::string& path_;
    std::vector<GpkgRows> later_;
    unsigned families_ = 0;
    std::mutex m_;
    std::condition_variable cv_;
    std::size_t next_ = 0, queued_ = 0;
    bool stop_ = false;
    std::exception_ptr error_;
    std::thread thread_;
};

// The hatch GeoPackage of the faces of `s` (see above); `total` (hatches) for the fractions
// `during` is asked with while the faces' rows go in, `after` while the rest is written.
void write_faces_gpkg(const std::string& path, const FaceStream& s, const std::function<const Drawing&()>& rest,
                      bool spatial_index, std::size_t total, const std::function<bool(double)>& during,
                      const std::function<bool(double)>& after) {
    GpkgWriter out(path, s.crs_wkt, spatial_index);
    std::vector<int> layer(kFamilies, -1);
    for (int fam = 0; fam < kRockFamilies; ++fam) layer[std::size_t(fam)] = add_hatch_layer(out, Family(fam));
    const std::int32_t srs = out.srs_id();  // SQLite has the file from here on
    std::vector<char> indexed(kFamilies, 0);
    if (s.fingerprints)
        for (int fam = 0; fam < kRockFamilies; ++fam) {
            out.sql(face_index_sql(hatch_table(Family(fam))));
            indexed[std::size_t(fam)] = 1;
        }
    {
        OrderedInserter inserter(out, s.faces, total, during, path);
        auto encode = [&](std::size_t k) {
            FaceRows rows{GpkgRows(srs), GpkgRows(srs)};
            if (inserter.stopped()) return inserter.put(k, std::move(rows), false);
            try {
                s.face(k, [&](const FaceHatches& face) {
                    for (const Hatch& h : face.hatches) {
                        const int fam = int(h.family);
                        rows.families |= 1u << fam;
                        const int l = layer[std::size_t(fam)];
                        hatch_row(l >= 0 ? rows.now : rows.later, l >= 0 ? l : fam, h.family, face.face_id, s.style,
                                  h.points.data(), h.points.size(), h.closed);
                    }
                });
            } catch (...) {
                inserter.put(k, FaceRows{GpkgRows(srs), GpkgRows(srs)}, true);
                throw;
            }
            inserter.put(k, std::move(rows), false);
        };
        if (s.serial)
            for (std::size_t k = 0; k < s.faces; ++k) encode(k);
        else
            tex::parallel_for(s.faces, encode);
        inserter.finish();
        // The other families the faces have, after the rock ones (write_gpkg's order).
        for (int fam = kRockFamilies; fam < kFamilies; ++fam) {
            if (!(inserter.families() & (1u << fam))) continue;
            layer[std::size_t(fam)] = add_hatch_layer(out, Family(fam));
            GpkgRows rows(srs);
            rows.append(inserter.later(fam), fam, layer[std::size_t(fam)]);
            inserter.later(fam).clear();
            out.insert(rows);
        }
    }
    const Drawing& d = rest();
    if (s.fingerprints != d.fingerprints.has_value())
        throw Error(Code::Failure, "-o '" + path + "': the fingerprints came unannounced or not at all");
    write_rest(out, d.bounds, drawing_crests(d), d.fingerprints ? &*d.fingerprints : nullptr, layer, indexed, after, path);
    out.commit();
}

}  // namespace

void write_gpkg(const FaceStream& faces, const std::function<const Drawing&()>& rest, const std::string& path,
                bool spatial_index, const std::function<bool(double)>& keep_going) {
    write_faces_gpkg(path, faces, rest, spatial_index, 0, {}, keep_going);
}

namespace {

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
    FaceStream s{d.crs_wkt, d.style, d.faces.size(), false,
                 [&](std::size_t k, const std::function<void(const FaceHatches&)>& use) { use(d.faces[k]); },
                 d.fingerprints.has_value()};
    std::function<bool(double)> during, after;
    if (keep_going) {
        during = [&](double f) { return keep_going(0.9 * f); };
        after = [&](double f) { return keep_going(0.9 + 0.1 * f); };
    }
    write_faces_gpkg(path, s, [&]() -> const Drawing& { return d; }, spatial_index, total, during, after);
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
            if (OGRLayer* l = ds->GetLayerByName(hatch_table(Family(fam)).c_str())) {
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
    auto check = [&] {
        if (keep_going && n % 4096 == 0 && !keep_going(std::min(0.9, 0.9 * double(n) / double(std::max<std::size_t>(1, total)))))
            throw Error(Code::Cancelled, "cancelled while writing '" + path + "'");
    };
    GpkgWriter out(path, crs_wkt, spatial_index);
    std::vector<int> layer(kFamilies, -1);
    // Family by family, the parts' features one after the other; one part open at a time:
    // memory does not grow with the number of tiles.
    for (int fam = 0; fam < kFamilies; ++fam) {
        const Family f = Family(fam);
        if (!present[std::size_t(fam)]) continue;
        const int l = layer[std::size_t(fam)] = add_hatch_layer(out, f);
        GpkgRows rows(out.srs_id());
        for (const auto& part : parts) {
            auto ds = open_hatches(part, "tile");
            read_family(*ds, f, "tile '" + part + "'", [&](std::int64_t id, const char* style, const std::vector<Point>& p) {
                ++n;
                check();
                hatch_row(rows, l, f, id, style, p.data(), p.size(), false);
                if (rows.size() >= 4096) {
                    out.insert(rows);
                    rows.clear();
                }
            });
        }
        out.insert(rows);
    }
    std::function<bool(double)> after;
    if (keep_going) after = [&](double f) { return keep_going(0.9 + 0.1 * f); };
    write_rest(out, frame, crests ? CrestSource([&](const CrestSink& sink) {
        for (const auto& part : parts) read_crests(*open_hatches(part, "tile"), "tile '" + part + "'", sink);
    }) : CrestSource(), nullptr, layer, std::vector<char>(kFamilies, 0), after, path);
    out.commit();
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

std::optional<Fingerprints> read_fingerprints(const std::string& path, const std::string& what) {
    auto ds = open_hatches(path, what);
    OGRLayer* t = ds->GetLayerByName(kFacesTable);
    if (!t) return std::nullopt;
    Fingerprints fp;
    const std::string prefix = run_key("");
    for (char** m = ds->GetMetadata(); m && *m; ++m) {
        const std::string item = *m;
        const auto eq = item.find('=');
        if (eq == std::string::npos || item.compare(0, prefix.size(), prefix) != 0) continue;
        std::string key = item.substr(prefix.size(), eq - prefix.size());
        for (auto& c : key) c = char(std::tolower((unsigned char)c));
        fp.run[key] = item.substr(eq + 1);
    }
    const int id_idx = t->GetLayerDefn()->GetFieldIndex("face_id");
    const int fp_idx = t->GetLayerDefn()->GetFieldIndex("fingerprint");
    if (id_idx < 0 || fp_idx < 0)
        throw Error(Code::BadLayer, what + " '" + path + "': table " + kFacesTable + " has no face_id or fingerprint field");
    const int box_idx[4] = {t->GetLayerDefn()->GetFieldIndex("xmin"), t->GetLayerDefn()->GetFieldIndex("ymin"),
                            t->GetLayerDefn()->GetFieldIndex("xmax"), t->GetLayerDefn()->GetFieldIndex("ymax")};
    t->ResetReading();
    for (auto& feat : *t) {
        fp.faces.emplace_back(feat->GetFieldAsInteger64(id_idx), feat->GetFieldAsString(fp_idx));
        tex::BBox b;
        if (std::all_of(std::begin(box_idx), std::end(box_idx), [&](int k) { return k >= 0 && feat->IsFieldSetAndNotNull(k); }))
            b = {feat->GetFieldAsDouble(box_idx[0]), feat->GetFieldAsDouble(box_idx[1]), feat->GetFieldAsDouble(box_idx[2]),
                 feat->GetFieldAsDouble(box_idx[3])};
        fp.boxes.push_back(b);
    }
    return fp;
}

namespace {

// The condition "column IN (values)" in batches of SQL text (SQLite's statements stay small).
template <class Int>
std::vector<std::string> in_conditions(const std::string& column, const std::vector<Int>& values) {
    std::vector<std::string> out;
    for (std::size_t k = 0; k < values.size(); k += 1000) {
        std::string sql = column + " IN (";
        for (std::size_t i = k; i < std::min(values.size(), k + 1000); ++i) {
            if (i > k) sql += ',';
            sql += std::to_string(values[i]);
        }
        out.push_back(sql + ")");
    }
    return out;
}

// The condition of the features of these faces (sorted ids), in batches.
std::vector<std::string> face_conditions(const std::vector<std::int64_t>& ids) { return in_conditions("face_id", ids); }

// The table of an undo file listing the faces an update replaced.
constexpr const char* kReplacedTable = "rockhatch_replaced";
// The table of an undo file listing the features an update wrote (layer, fid): restore_faces
// removes them.
constexpr const char* kWrittenTable = "rockhatch_written";

// What a hatch feature holds, as a key: its face, family, style and width (each a tag, then a
// number's bytes or a text and a NUL; NULL one tag of its own) and its geometry's WKB. Two
// features with the same key are the same bytes in the file (the blob's header follows from
// the WKB). Made for a hatch drawn again (drawn_key) and for a row of the file (StoredKeys)
// alike.
void key_integer(std::string& k, std::int64_t v) {
    k += 'i';
    k.append(reinterpret_cast<const char*>(&v), sizeof v);
}

void key_real(std::string& k, double v) {
    k += 'r';
    k.append(reinterpret_cast<const char*>(&v), sizeof v);
}

void key_text(std::string& k, std::string_view v) {
    k += 's';
    k += v;
    k += '\0';
}

// The key's bytes reduced to 128 bits (two multiply-xorshift lanes over 8-byte words), so the
// features of large faces are looked up without a string each: two different features share
// a digest with a chance of 2^-128, and the digest depends on the bytes only.
struct KeyDigest {
    std::uint64_t a, b;
    bool operator<(const KeyDigest& o) const { return a != o.a ? a < o.a : b < o.b; }
    bool operator==(const KeyDigest& o) const { return a == o.a && b == o.b; }
};

KeyDigest key_digest(std::string_view k) {
    auto mix = [](std::uint64_t x) {
        x ^= x >> 30;
        x *= 0xBF58476D1CE4E5B9ULL;
        x ^= x >> 27;
        x *= 0x94D049BB133111EBULL;
        return x ^ (x >> 31);
    };
    std::uint64_t a = 0x9E3779B97F4A7C15ULL ^ k.size(), b = 0xD6E8FEB86659FD93ULL + k.size();
    std::size_t i = 0;
    for (; i + 8 <= k.size(); i += 8) {
        std::uint64_t w;
        std::memcpy(&w, k.data() + i, 8);
        a = mix(a ^ w);
        b = (b ^ w) * 0xFF51AFD7ED558CCDULL;
        b ^= b >> 33;
    }
    std::uint64_t w = 0;
    std::memcpy(&w, k.data() + i, k.size() - i);
    return {mix(a ^ w), mix(b ^ (w * 0xC4CEB9FE1A85EC53ULL) ^ a)};
}

void drawn_key(std::string& k, std::int64_t face_id, Family f, const std::string& style, const Hatch& h) {
    k.clear();
    key_integer(k, face_id);
    key_text(k, family_name(f));
    key_text(k, style);
    key_real(k, family_width_mm(f));
    append_line_wkb(k, h.points.data(), h.points.size(), h.closed && !h.points.empty(), family_filled(f));
}

// The features of some faces in the hatch layers, by their keys' digests, read with SQLite from
// the file as it is before the edit writes (a connection of its own, closed before GDAL
// writes): GDAL's features would parse each geometry only for the key to write it out again.
class StoredKeys {
public:
    // A layer's features by digest (sorted); take() hands each out once.
    struct Fids {
        std::vector<std::pair<KeyDigest, GIntBig>> rows;
        std::vector<char> taken;
        bool empty() const { return rows.empty(); }
        // Takes a feature of this key not yet taken (the last in file order); false if none.
        bool take(const KeyDigest& k) {
            auto it = std::upper_bound(rows.begin(), rows.end(), std::make_pair(k, std::numeric_limits<GIntBig>::max()));
            while (it != rows.begin() && (it - 1)->first == k) {
                --it;
                char& t = taken[std::size_t(it - rows.begin())];
                if (!t) {
                    t = 1;
                    return true;
                }
            }
            return false;
        }
        // The fids not taken, ascending.
        std::vector<GIntBig> rest() const {
            std::vector<GIntBig> out;
            for (std::size_t i = 0; i < rows.size(); ++i)
                if (!taken[i]) out.push_back(rows[i].second);
            std::sort(out.begin(), out.end());
            return out;
        }
    };
    StoredKeys(const std::string& path, const std::string& what) : what_(what) {
        if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) fail("cannot read");
        sqlite3_busy_timeout(db_, 5000);
    }
    ~StoredKeys() { sqlite3_close(db_); }
    StoredKeys(const StoredKeys&) = delete;
    StoredKeys& operator=(const StoredKeys&) = delete;
    // The features of these faces (the conditions of face_conditions) in a layer.
    Fids read(OGRLayer& layer, const std::vector<std::string>& where) {
        Fids out;
        const std::string sql_start = "SELECT " + sql_name(layer.GetFIDColumn()) + ", face_id, family, style, width_mm, " +
                                      sql_name(layer.GetGeometryColumn()) + " FROM " + sql_name(layer.GetName()) +
                                      " WHERE ";
        std::string k;
        for (const std::string& w : where) {
            sqlite3_stmt* st = nullptr;
            if (sqlite3_prepare_v2(db_, (sql_start + w).c_str(), -1, &st, nullptr) != SQLITE_OK)
                fail(std::string("cannot read the features of ") + layer.GetName());
            int rc;
            while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
                k.clear();
                for (int col = 1; col <= 4; ++col) value(k, st, col);
                const auto* blob = static_cast<const char*>(sqlite3_column_blob(st, 5));
                k += gpkg_blob_wkb(std::string_view(blob ? blob : "", std::size_t(sqlite3_column_bytes(st, 5))));
                out.rows.emplace_back(key_digest(k), sqlite3_column_int64(st, 0));
            }
            sqlite3_finalize(st);
            if (rc != SQLITE_DONE) fail(std::string("cannot read the features of ") + layer.GetName());
        }
        std::sort(out.rows.begin(), out.rows.end());
        out.taken.assign(out.rows.size(), 0);
        return out;
    }

private:
    static void value(std::string& k, sqlite3_stmt* st, int col) {
        switch (sqlite3_column_type(st, col)) {
            case SQLITE_INTEGER: key_integer(k, sqlite3_column_int64(st, col)); break;
            case SQLITE_FLOAT: key_real(k, sqlite3_column_double(st, col)); break;
            case SQLITE_NULL: k += '\x01'; break;
            default:
                key_text(k, std::string_view(reinterpret_cast<const char*>(sqlite3_column_text(st, col)),
                                             std::size_t(sqlite3_column_bytes(st, col))));
        }
    }
    [[noreturn]] void fail(const std::string& m) const {
        throw Error(Code::OutputExists, what_ + ": " + m + " (" + (db_ ? sqlite3_errmsg(db_) : "no memory") +
                                            "); the file is as it was");
    }
    std::string what_;
    sqlite3* db_ = nullptr;
};

// A hatch GeoPackage open for an edit in one transaction: rolled back unless committed, so
// an error (or an exception, or the process's end) leaves the file as it was.
class FaceEdit {
public:
    FaceEdit(const std::string& path, const std::string& what) : what_(what) {
        register_gdal();
        ds_.reset(GDALDataset::FromHandle(
            GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, nullptr, nullptr, nullptr)));
        if (!ds_) throw Error(Code::OutputExists, what_ + ": cannot open for writing (" + CPLGetLastErrorMsg() + ")");
        if (ds_->StartTransaction(FALSE) != OGRERR_NONE) throw fail("cannot start a transaction");
    }
    ~FaceEdit() {
        if (ds_ && !done_) ds_->RollbackTransaction();
    }
    GDALDataset& ds() { return *ds_; }
    Error fail(const std::string& m) const {
        return Error(Code::OutputExists, what_ + ": " + m + " (" + CPLGetLastErrorMsg() + "); the file is as it was");
    }
    // Removes the features of these faces (sorted ids; every feature when `all`) from a layer,
    // by one SQL statement per batch (the file's triggers keep its R-tree and feature count);
    // returns how many. They go to `keep` first when given (an undo file's layer).
    std::size_t remove(OGRLayer* layer, const std::vector<std::int64_t>& ids, bool all, OGRLayer* keep) {
        const std::string table = std::string("\"") + layer->GetName() + "\"";
        std::size_t n = 0;
        for (const std::string& where : all ? std::vector<std::string>{"1"} : face_conditions(ids)) {
            if (keep) {
                OGRLayer* res = ds_->ExecuteSQL(("SELECT * FROM " + table + " WHERE " + where).c_str(), nullptr, nullptr);
                if (!res) throw fail(std::string("cannot read the features of ") + layer->GetName());
                for (auto& f : *res) copy(*f, keep);
                ds_->ReleaseResultSet(res);
            }
            OGRLayer* res = ds_->ExecuteSQL(("SELECT count(*) FROM " + table + " WHERE " + where).c_str(), nullptr, nullptr);
            if (!res) throw fail(std::string("cannot count the features of ") + layer->GetName());
            for (auto& f : *res) n += std::size_t(f->GetFieldAsInteger64(0));
            ds_->ReleaseResultSet(res);
            CPLErrorReset();
            ds_->ExecuteSQL(("DELETE FROM " + table + " WHERE " + where).c_str(), nullptr, nullptr);
            if (CPLGetLastErrorType() >= CE_Failure)
                throw fail(std::string("cannot delete the features of ") + layer->GetName());
        }
        return n;
    }
    // Removes these features; a copy of each goes to `keep` first when given (an undo file's
    // layer). Returns how many there were.
    std::size_t remove_fids(OGRLayer* layer, const std::vector<GIntBig>& fids, OGRLayer* keep) {
        const std::string table = sql_name(layer->GetName());
        const std::string fid = sql_name(layer->GetFIDColumn());
        std::size_t n = 0;
        for (const std::string& batch : in_conditions(fid, fids)) {
            const std::string where = " WHERE " + batch;
            // The features themselves only for a copy; else their count.
            OGRLayer* res =
                ds_->ExecuteSQL(((keep ? "SELECT * FROM " : "SELECT count(*) FROM ") + table + where).c_str(), nullptr, nullptr);
            if (!res) throw fail(std::string("cannot read the features of ") + layer->GetName());
            for (auto& f : *res) {
                if (keep) {
                    copy(*f, keep);
                    ++n;
                } else {
                    n += std::size_t(f->GetFieldAsInteger64(0));
                }
            }
            ds_->ReleaseResultSet(res);
            CPLErrorReset();
            ds_->ExecuteSQL(("DELETE FROM " + table + where).c_str(), nullptr, nullptr);
            if (CPLGetLastErrorType() >= CE_Failure)
                throw fail(std::string("cannot delete the features of ") + layer->GetName());
        }
        return n;
    }
    // Writes a copy of a feature (geometry and the fields of the same names) as a new one.
    void copy(const OGRFeature& f, OGRLayer* to) {
        OGRFeature out(to->GetLayerDefn());
        if (out.SetFrom(&f, TRUE) != OGRERR_NONE) throw fail(std::string("cannot copy a feature to ") + to->GetName());
        out.SetFID(OGRNullFID);
        if (to->CreateFeature(&out) != OGRERR_NONE) throw fail(std::string("cannot write a feature of ") + to->GetName());
    }
    void metadata(const std::string& key, const std::string& value) {
        if (ds_->SetMetadataItem(key.c_str(), value.c_str()) != CE_None) throw fail("cannot write " + key);
    }
    void commit() {
        // The metadata goes to the file now, inside the transaction.
        CPLErrorReset();
        ds_->FlushCache(false);
        if (CPLGetLastErrorType() >= CE_Failure) throw fail("cannot write the metadata");
        if (ds_->CommitTransaction() != OGRERR_NONE) throw fail("cannot commit");
        done_ = true;
        ds_.reset();
    }

private:
    std::string what_;
    DatasetPtr ds_;
    bool done_ = false;
};

// The layers of the undo file of an update (replace_faces): an empty copy of each hatch layer
// and of the fingerprints table, the list of the faces replaced, and the file's metadata.
class UndoFile {
public:
    UndoFile(const std::string& path, GDALDataset& from, const std::vector<std::int64_t>& replaced) : path_(path) {
        GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
        std::error_code ec;
        std::filesystem::remove(path, ec);
        ds_.reset(drv ? drv->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr) : nullptr);
        if (!ds_) throw Error(Code::OutputExists, "undo '" + path + "': cannot create (" + CPLGetLastErrorMsg() + ")");
        ds_->StartTransaction(FALSE);
        for (OGRLayer* l : from.GetLayers()) {
            const std::string name = l->GetName();
            if (name.rfind("hatch_", 0) != 0 && name != kFacesTable) continue;
            const char* lco[] = {"SPATIAL_INDEX=NO", "FID=fid", "GEOMETRY_NAME=geom", nullptr};
            OGRLayer* c = ds_->CreateLayer(name.c_str(), l->GetSpatialRef(), l->GetGeomType(), const_cast<char**>(lco));
            if (!c) throw Error(Code::OutputExists, "undo '" + path + "': cannot create layer " + name);
            for (int i = 0; i < l->GetLayerDefn()->GetFieldCount(); ++i) c->CreateField(l->GetLayerDefn()->GetFieldDefn(i));
            layers_[name] = c;
        }
        written_ = ds_->CreateLayer(kWrittenTable, nullptr, wkbNone, nullptr);
        OGRFieldDefn layer_field("layer", OFTString), fid_field("fid", OFTInteger64);
        if (!written_ || written_->CreateField(&layer_field) != OGRERR_NONE ||
            written_->CreateField(&fid_field) != OGRERR_NONE)
            throw Error(Code::OutputExists, "undo '" + path + "': cannot create layer " + kWrittenTable);
        OGRLayer* r = ds_->CreateLayer(kReplacedTable, nullptr, wkbNone, nullptr);
        OGRFieldDefn id("face_id", OFTInteger64);
        r->CreateField(&id);
        for (std::int64_t f : replaced) {
            OGRFeature feat(r->GetLayerDefn());
            feat.SetField(0, GIntBig(f));
            if (r->CreateFeature(&feat) != OGRERR_NONE)
                throw Error(Code::OutputExists, "undo '" + path + "': write failed (" + CPLGetLastErrorMsg() + ")");
        }
        for (char** m = from.GetMetadata(); m && *m; ++m) {
            const std::string item = *m;
            const auto eq = item.find('=');
            if (eq != std::string::npos && item.rfind("RH_", 0) == 0)
                ds_->SetMetadataItem(item.substr(0, eq).c_str(), item.substr(eq + 1).c_str());
        }
    }
    ~UndoFile() {
        if (ds_ && !done_) {
            ds_.reset();
            std::error_code ec;
            std::filesystem::remove(path_, ec);
        }
    }
    OGRLayer* layer(const std::string& name) {
        const auto it = layers_.find(name);
        return it == layers_.end() ? nullptr : it->second;
    }
    // A feature the update wrote into `layer`.
    void written(const std::string& layer, GIntBig fid) {
        OGRFeature f(written_->GetLayerDefn());
        f.SetField(0, layer.c_str());
        f.SetField(1, fid);
        if (written_->CreateFeature(&f) != OGRERR_NONE)
            throw Error(Code::OutputExists, "undo '" + path_ + "': write failed (" + CPLGetLastErrorMsg() + ")");
    }
    void commit() {
        if (ds_->CommitTransaction() != OGRERR_NONE)
            throw Error(Code::OutputExists, "undo '" + path_ + "': write failed (" + CPLGetLastErrorMsg() + ")");
        ds_.reset();
        done_ = true;
    }

private:
    std::string path_;
    DatasetPtr ds_;
    std::map<std::string, OGRLayer*> layers_;
    OGRLayer* written_ = nullptr;
    bool done_ = false;
};

}  // namespace

struct FeatureKeys {
    std::vector<std::int64_t> faces;  // sorted, distinct
    std::array<StoredKeys::Fids, kFamilies> old;
};

namespace {

// The sorted, distinct face ids.
std::vector<std::int64_t> distinct(std::vector<std::int64_t> ids) {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
}

// The keys of the features of `ids` (sorted) in the hatch layers of `ds`, in family order.
void read_keys(GDALDataset& ds, const std::string& path, const std::string& what, const std::vector<std::int64_t>& ids,
               std::array<StoredKeys::Fids, kFamilies>& old) {
    StoredKeys stored(path, what);
    const std::vector<std::string> where = face_conditions(ids);
    for (int fam = 0; fam < kFamilies; ++fam)
        if (OGRLayer* layer = ds.GetLayerByName(hatch_table(Family(fam)).c_str())) old[std::size_t(fam)] = stored.read(*layer, where);
}

}  // namespace

std::shared_ptr<FeatureKeys> read_feature_keys(const std::string& path, const std::vector<std::int64_t>& faces) {
    const QuietGdal quiet;
    register_gdal();
    const std::string what = "-o '" + path + "'";
    std::unique_ptr<GDALDataset> ds(
        GDALDataset::FromHandle(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    if (!ds) throw Error(Code::OutputExists, what + ": cannot read (" + CPLGetLastErrorMsg() + ")");
    auto keys = std::make_shared<FeatureKeys>();
    keys->faces = distinct(faces);
    read_keys(*ds, path, what, keys->faces, keys->old);
    return keys;
}

FaceReplacement replace_faces(const std::string& path, const std::vector<std::int64_t>& faces, bool all,
                              const Drawing& d, const std::string& undo, std::shared_ptr<FeatureKeys> keys) {
    const ReproducibleGpkg reproducible;
    const QuietGdal quiet;
    const std::string what = "-o '" + path + "'";
    FaceEdit edit(path, what);
    GDALDataset& ds = edit.ds();
    const std::vector<std::int64_t> ids = distinct(faces);
    if (keys && keys->faces != ids) throw Error(Code::Failure, what + ": the features read before are of other faces");
    std::optional<UndoFile> keep;
    if (!undo.empty()) keep.emplace(undo, ds, ids);
    FaceReplacement r;
    // The hatch layers, and (unless all go) the keys of the faces' features in them, read before
    // anything is written.
    std::array<OGRLayer*, kFamilies> layers{};
    std::array<StoredKeys::Fids, kFamilies> old;
    for (int fam = 0; fam < kFamilies; ++fam) {
        const Family f = Family(fam);
        const std::string table = hatch_table(f);
        OGRLayer* layer = ds.GetLayerByName(table.c_str());
        if (!layer) {
            if (has_family(d, f)) throw Error(Code::BadLayer, what + ": no layer " + table + " for the redrawn faces");
            continue;
        }
        const OGRFeatureDefn* defn = layer->GetLayerDefn();
        for (const char* field : {"face_id", "family", "style", "width_mm"})
            if (defn->GetFieldIndex(field) < 0)
                throw Error(Code::BadLayer, what + ": layer " + table + " lacks face_id, family, style or width_mm");
        layers[std::size_t(fam)] = layer;
    }
    if (!all) {
        if (keys) old = std::move(keys->old);
        else read_keys(ds, path, what, ids, old);
    }
    std::vector<Point> pts;
    std::string key;
    for (int fam = 0; fam < kFamilies; ++fam) {
        const Family f = Family(fam);
        OGRLayer* layer = layers[std::size_t(fam)];
        if (!layer) continue;
        const std::string table = layer->GetName();
        OGRLayer* undo_layer = keep ? keep->layer(table) : nullptr;
        // Every feature of the faces goes (all), or those the new drawing does not hold: a feature
        // the redrawn face draws again, byte for byte, stays (its R-tree entry with it).
        StoredKeys::Fids& was = old[std::size_t(fam)];
        if (all) r.deleted += edit.remove(layer, ids, true, undo_layer);
        OGRFeatureDefn* defn = layer->GetLayerDefn();
        const HatchFields k{defn->GetFieldIndex("face_id"), defn->GetFieldIndex("family"), defn->GetFieldIndex("style"),
                            defn->GetFieldIndex("width_mm")};
        OGRFeature feat(defn);
        for (const auto& face : d.faces)
            for (const auto& h : face.hatches) {
                if (h.family != f) continue;
                if (h.points.size() + (h.closed && !h.points.empty()) < 2) continue;
                if (!was.empty()) {
                    drawn_key(key, face.face_id, f, d.style, h);
                    if (was.take(key_digest(key))) {
                        ++r.kept;
                        continue;
                    }
                }
                pts.assign(h.points.begin(), h.points.end());
                if (h.closed) pts.push_back(pts.front());
                set_hatch(feat, k, f, face.face_id, d.style.c_str(), pts);
                feat.SetFID(OGRNullFID);
                if (layer->CreateFeature(&feat) != OGRERR_NONE) throw edit.fail("cannot write a feature of " + table);
                if (keep) keep->written(table, feat.GetFID());
                ++r.written;
            }
        r.deleted += edit.remove_fids(layer, was.rest(), undo_layer);
    }
    if (d.fingerprints) {
        OGRLayer* t = ds.GetLayerByName(kFacesTable);
        if (!t) throw Error(Code::BadLayer, what + ": no table " + kFacesTable + " (not written with fingerprints)");
        edit.remove(t, ids, all, keep ? keep->layer(kFacesTable) : nullptr);
        OGRFeature feat(t->GetLayerDefn());
        const int id_idx = t->GetLayerDefn()->GetFieldIndex("face_id");
        const int fp_idx = t->GetLayerDefn()->GetFieldIndex("fingerprint");
        const char* const box_names[4] = {"xmin", "ymin", "xmax", "ymax"};
        for (std::size_t i = 0; i < d.fingerprints->faces.size(); ++i) {
            const auto& [id, fp] = d.fingerprints->faces[i];
            feat.SetField(id_idx, GIntBig(id));
            feat.SetField(fp_idx, fp.c_str());
            const tex::BBox b = i < d.fingerprints->boxes.size() ? d.fingerprints->boxes[i] : tex::BBox{};
            const double v[4] = {b.xmin, b.ymin, b.xmax, b.ymax};
            for (int k = 0; k < 4; ++k) {
                const int idx = t->GetLayerDefn()->GetFieldIndex(box_names[k]);
                if (idx < 0) continue;  // a file of an earlier version (only with --reset)
                if (b.empty()) feat.SetFieldNull(idx);
                else feat.SetField(idx, v[k]);
            }
            feat.SetFID(OGRNullFID);
            if (t->CreateFeature(&feat) != OGRERR_NONE) throw edit.fail("cannot write a fingerprint");
        }
        for (const auto& [key, value] : d.fingerprints->run) edit.metadata(run_key(key), value);
    }
    if (!d.bounds.empty()) edit.metadata(kFrameKey, frame_text(d.bounds));
    if (keep) keep->commit();
    edit.commit();
    return r;
}

FaceReplacement restore_faces(const std::string& path, const std::string& undo) {
    const ReproducibleGpkg reproducible;
    const QuietGdal quiet;
    register_gdal();
    DatasetPtr from(GDALDataset::FromHandle(
        GDALOpenEx(undo.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    OGRLayer* replaced = from ? from->GetLayerByName(kReplacedTable) : nullptr;
    OGRLayer* written = from ? from->GetLayerByName(kWrittenTable) : nullptr;
    if (!replaced || !written)
        throw Error(Code::InputMissing, "undo '" + undo + "': not an undo file of this version of rockhatch update");
    std::vector<std::int64_t> ids;
    for (auto& f : *replaced) ids.push_back(f->GetFieldAsInteger64(0));
    std::sort(ids.begin(), ids.end());
    // The features the update wrote, by layer: they go; those it removed come back.
    std::map<std::string, std::vector<GIntBig>> wrote;
    for (auto& f : *written) wrote[f->GetFieldAsString(0)].push_back(f->GetFieldAsInteger64(1));
    FaceEdit edit(path, "-o '" + path + "'");
    FaceReplacement r;
    for (OGRLayer* l : from->GetLayers()) {
        const std::string name = l->GetName();
        if (name == kReplacedTable || name == kWrittenTable) continue;
        OGRLayer* to = edit.ds().GetLayerByName(name.c_str());
        if (!to) throw Error(Code::BadLayer, "-o '" + path + "': no layer " + name + " to restore");
        if (name == kFacesTable) {
            edit.remove(to, ids, false, nullptr);
        } else {
            std::vector<GIntBig>& fids = wrote[name];
            std::sort(fids.begin(), fids.end());
            r.deleted += edit.remove_fids(to, fids, nullptr);
        }
        l->ResetReading();
        for (auto& f : *l) {
            edit.copy(*f, to);
            if (name != kFacesTable) ++r.written;
        }
    }
    for (char** m = from->GetMetadata(); m && *m; ++m) {
        const std::string item = *m;
        const auto eq = item.find('=');
        if (eq != std::string::npos && item.rfind("RH_", 0) == 0) edit.metadata(item.substr(0, eq), item.substr(eq + 1));
    }
    edit.commit();
    return r;
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
