#include "carto/partition.hpp"

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <unordered_map>

#include "carto/error.hpp"

namespace carto {
namespace {

struct DsCloser {
    void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using DsPtr = std::unique_ptr<GDALDataset, DsCloser>;

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool parse_kind(const std::string& raw, LineKind& out) {
    const std::string v = lower(raw);
    if (v == "ridge" || v == "crete" || v == "crête" || v == "arete" || v == "arête") out = LineKind::Ridge;
    else if (v == "valley" || v == "thalweg" || v == "talweg" || v == "couloir") out = LineKind::Valley;
    else if (v == "other" || v == "" || v == "boundary" || v == "limit") out = LineKind::Other;
    else return false;
    return true;
}

OGRwkbGeometryType flat(OGRLayer* l) { return wkbFlatten(l->GetGeomType()); }
bool is_polygon_layer(OGRLayer* l) { return flat(l) == wkbPolygon || flat(l) == wkbMultiPolygon; }
bool is_line_layer(OGRLayer* l) { return flat(l) == wkbLineString || flat(l) == wkbMultiLineString; }

struct Reprojector {
    std::unique_ptr<OGRCoordinateTransformation> ct;
    void apply(OGRGeometry* g) const {
        if (ct) g->transform(ct.get());
    }
};

Reprojector reprojector(OGRLayer* layer, const std::string& working_wkt, const std::string& what) {
    const OGRSpatialReference* srs = layer->GetSpatialRef();
    // GeoPackage layers without a CRS report an "Undefined" placeholder.
    const char* name = srs ? srs->GetName() : nullptr;
    if (!srs || srs->IsEmpty() || (name && std::string(name).find("Undefined") != std::string::npos))
        throw Error(Code::NoCrs, what + ": layer '" + layer->GetName() + "' has no CRS");
    OGRSpatialReference dst;
    dst.importFromWkt(working_wkt.c_str());
    dst.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReference src(*srs);
    src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    Reprojector r;
    if (!src.IsSame(&dst)) {
        r.ct.reset(OGRCreateCoordinateTransformation(&src, &dst));
        if (!r.ct) throw Error(Code::NoCrs, what + ": cannot reproject layer '" + std::string(layer->GetName()) + "'");
    }
    return r;
}

std::vector<Point> ring_points(const OGRLinearRing* ring) {
    std::vector<Point> pts;
    pts.reserve(ring->getNumPoints());
    for (int i = 0; i < ring->getNumPoints(); ++i) pts.push_back({ring->getX(i), ring->getY(i)});
    return pts;
}

void add_lines(const OGRGeometry* g, LineKind kind, std::vector<LabelledLine>& out) {
    const auto t = wkbFlatten(g->getGeometryType());
    if (t == wkbLineString) {
        const auto* ls = g->toLineString();
        LabelledLine l;
        l.kind = kind;
        for (int i = 0; i < ls->getNumPoints(); ++i) l.points.push_back({ls->getX(i), ls->getY(i)});
        if (l.points.size() >= 2) out.push_back(std::move(l));
    } else if (t == wkbMultiLineString || t == wkbGeometryCollection) {
        for (const auto* part : *g->toGeometryCollection()) add_lines(part, kind, out);
    }
}

// Segment index on a uniform grid of cell size `cell`.
struct SegmentGrid {
    double cell;
    std::unordered_map<std::uint64_t, std::vector<int>> cells;
    static std::uint64_t key(long long i, long long j) {
        return (std::uint64_t(i) * 0x9E3779B97F4A7C15ULL) ^ std::uint64_t(j);
    }
    void insert(const Point& a, const Point& b, int id) {
        const long long i0 = (long long)std::floor(std::min(a.x, b.x) / cell), i1 = (long long)std::floor(std::max(a.x, b.x) / cell);
        const long long j0 = (long long)std::floor(std::min(a.y, b.y) / cell), j1 = (long long)std::floor(std::max(a.y, b.y) / cell);
        if ((i1 - i0 + 1) * (j1 - j0 + 1) > 4096) return;  // absurdly long segment: skip index
        for (long long i = i0; i <= i1; ++i)
            for (long long j = j0; j <= j1; ++j) cells[key(i, j)].push_back(id);
    }
    template <class F>
    void query(const Point& p, F&& f) const {
        const long long i = (long long)std::floor(p.x / cell), j = (long long)std::floor(p.y / cell);
        for (long long di = -1; di <= 1; ++di)
            for (long long dj = -1; dj <= 1; ++dj) {
                auto it = cells.find(key(i + di, j + dj));
                if (it != cells.end())
                    for (int id : it->second) f(id);
            }
    }
};

double seg_distance(const Point& p, const Point& a, const Point& b) {
    const Point d = b - a;
    const double l2 = tex::dot(d, d);
    double t = l2 > 0 ? tex::dot(p - a, d) / l2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    return tex::distance(p, a + d * t);
}

}  // namespace

const char* kind_name(LineKind k) {
    switch (k) {
        case LineKind::Ridge: return "ridge";
        case LineKind::Valley: return "valley";
        default: return "other";
    }
}

tex::BBox Partition::bounds() const {
    tex::BBox b;
    for (const auto& f : faces) b.add(f.region.bbox());
    return b;
}

void label_boundaries(Partition& p, double snap) {
    // Index the labelled line segments.
    struct Seg {
        Point a, b;
        LineKind kind;
    };
    std::vector<Seg> segs;
    for (const auto& l : p.lines)
        for (std::size_t i = 0; i + 1 < l.points.size(); ++i) segs.push_back({l.points[i], l.points[i + 1], l.kind});
    const double cell = std::max(snap * 8, 1e-6);
    SegmentGrid lines_grid{cell, {}};
    for (std::size_t i = 0; i < segs.size(); ++i) lines_grid.insert(segs[i].a, segs[i].b, int(i));

    // Boundary segments of all faces, and an index of their midpoints for adjacency.
    SegmentGrid mids{cell, {}};
    struct Ref {
        int face, seg;
    };
    std::vector<Ref> refs;
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
        RockFace& rf = p.faces[f];
        rf.boundary.clear();
        auto add_ring = [&](const std::vector<Point>& ring) {
            for (std::size_t i = 0; i < ring.size(); ++i) {
                BoundarySegment s;
                s.a = ring[i];
                s.b = ring[(i + 1) % ring.size()];
                const Point m = (s.a + s.b) / 2;
                const Point d = s.b - s.a;
                const double len = tex::norm(d);
                if (len == 0) continue;
                // A boundary segment lies on a labelled line when its midpoint is within the
                // tolerance and the directions agree (within about 10 degrees).
                double best = snap;
                lines_grid.query(m, [&](int id) {
                    const Seg& sg = segs[id];
                    const Point e = sg.b - sg.a;
                    const double le = tex::norm(e);
                    if (le == 0) return;
                    if (std::abs(tex::cross(d, e)) > 0.18 * len * le) return;
                    const double dist = seg_distance(m, sg.a, sg.b);
                    if (dist <= best) {
                        best = dist;
                        s.kind = sg.kind;
                    }
                });
                mids.insert(m, m, int(refs.size()));
                refs.push_back({int(f), int(rf.boundary.size())});
                rf.boundary.push_back(s);
            }
        };
        add_ring(rf.region.outer());
        for (const auto& h : rf.region.holes()) add_ring(h);
    }
    // Neighbours: another face's boundary segment with (nearly) the same midpoint.
    for (const Ref& r : refs) {
        BoundarySegment& s = p.faces[r.face].boundary[r.seg];
        const Point m = (s.a + s.b) / 2;
        double best = snap;
        mids.query(m, [&](int id) {
            const Ref& o = refs[id];
            if (o.face == r.face) return;
            const BoundarySegment& t = p.faces[o.face].boundary[o.seg];
            const double dist = tex::distance(m, (t.a + t.b) / 2);
            if (dist <= best) {
                best = dist;
                s.neighbor = o.face;
            }
        });
    }
}

Partition load_partition(const PartitionOptions& opt, const std::string& working_wkt) {
    GDALAllRegister();
    const std::string what = "--partition '" + opt.path + "'";
    if (!std::filesystem::exists(opt.path)) throw Error(Code::InputMissing, what + ": no such file");
    CPLPushErrorHandler(CPLQuietErrorHandler);
    DsPtr ds(GDALDataset::FromHandle(GDALOpenEx(opt.path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr,
                                                nullptr, nullptr)));
    CPLPopErrorHandler();
    if (!ds) throw Error(Code::InputMissing, what + ": not a vector dataset OGR can read");

    auto find_layer = [&](const std::string& name, bool (*pred)(OGRLayer*), const char* role) -> OGRLayer* {
        if (!name.empty()) {
            OGRLayer* l = ds->GetLayerByName(name.c_str());
            if (!l) throw Error(Code::BadLayer, what + ": no layer named '" + name + "'");
            if (pred && !pred(l)) throw Error(Code::BadLayer, what + ": layer '" + name + "' is not a " + role + " layer");
            return l;
        }
        return nullptr;
    };

    Partition p;
    p.crs_wkt = working_wkt;

    // ---- Faces
    OGRLayer* faces = find_layer(opt.faces_layer, is_polygon_layer, "polygon");
    if (!faces)
        for (int i = 0; i < ds->GetLayerCount() && !faces; ++i)
            if (is_polygon_layer(ds->GetLayer(i))) faces = ds->GetLayer(i);
    if (!faces) throw Error(Code::BadLayer, what + ": no polygon layer (the rock faces)");
    const Reprojector face_proj = reprojector(faces, working_wkt, what);
    OGRFeatureDefn* fdef = faces->GetLayerDefn();
    const int id_idx = opt.id_field.empty() ? -1 : fdef->GetFieldIndex(opt.id_field.c_str());
    if (!opt.id_field.empty() && id_idx < 0)
        throw Error(Code::BadLayer, what + ": layer '" + faces->GetName() + "' has no field '" + opt.id_field + "'");
    const int orient_idx = fdef->GetFieldIndex(opt.orientation_field.c_str());
    const int dens_idx = fdef->GetFieldIndex(opt.density_field.c_str());
    int repaired = 0;
    faces->ResetReading();
    for (auto& feat : *faces) {
        OGRGeometry* g0 = feat->GetGeometryRef();
        if (!g0 || g0->IsEmpty()) continue;
        std::unique_ptr<OGRGeometry> g(g0->clone());
        face_proj.apply(g.get());
        if (!g->IsValid()) {
            if (!opt.repair)
                throw Error(Code::BadGeometry, what + ": face " + std::to_string(feat->GetFID()) +
                                                   " is not a valid polygon (self-intersecting?); repair it or drop --no-repair");
            std::unique_ptr<OGRGeometry> fixed(g->MakeValid());
            if (!fixed || fixed->IsEmpty())
                throw Error(Code::BadGeometry, what + ": face " + std::to_string(feat->GetFID()) + " is invalid and cannot be repaired");
            g = std::move(fixed);
            ++repaired;
        }
        std::vector<const OGRPolygon*> polys;
        std::function<void(const OGRGeometry*)> collect = [&](const OGRGeometry* x) {
            const auto t = wkbFlatten(x->getGeometryType());
            if (t == wkbPolygon) polys.push_back(x->toPolygon());
            else if (t == wkbMultiPolygon || t == wkbGeometryCollection)
                for (const auto* part : *x->toGeometryCollection()) collect(part);
        };
        collect(g.get());
        for (const OGRPolygon* poly : polys) {
            if (!poly->getExteriorRing() || poly->getExteriorRing()->getNumPoints() < 4) continue;
            RockFace rf;
            rf.id = id_idx >= 0 ? feat->GetFieldAsInteger64(id_idx) : feat->GetFID();
            std::vector<std::vector<Point>> holes;
            for (int k = 0; k < poly->getNumInteriorRings(); ++k) holes.push_back(ring_points(poly->getInteriorRing(k)));
            try {
                rf.region = tex::Region(ring_points(poly->getExteriorRing()), holes, "face");
            } catch (const std::exception&) {
                continue;  // a zero-area sliver left by a repair
            }
            if (orient_idx >= 0 && feat->IsFieldSetAndNotNull(orient_idx)) {
                const double az = feat->GetFieldAsDouble(orient_idx);
                if (!std::isfinite(az))
                    throw Error(Code::BadLayer, what + ": face " + std::to_string(rf.id) + ": bad " + opt.orientation_field);
                rf.orientation = (90.0 - az) * M_PI / 180.0;
            }
            if (dens_idx >= 0 && feat->IsFieldSetAndNotNull(dens_idx)) {
                const double d = feat->GetFieldAsDouble(dens_idx);
                if (!(d >= 0 && d <= 1))
                    throw Error(Code::BadLayer, what + ": face " + std::to_string(rf.id) + ": " + opt.density_field + " " +
                                                    std::to_string(d) + " is not in [0, 1]");
                rf.density = d;
            }
            p.faces.push_back(std::move(rf));
        }
    }
    if (p.faces.empty()) throw Error(Code::BadLayer, what + ": layer '" + std::string(faces->GetName()) + "' holds no polygon");
    if (repaired) p.notes.push_back("repaired " + std::to_string(repaired) + " invalid face polygon(s)");

    // ---- Lines: one layer with a label attribute, or one layer per kind.
    OGRLayer* lines = find_layer(opt.lines_layer, is_line_layer, "line");
    std::vector<std::pair<OGRLayer*, LineKind>> per_kind;
    if (!lines) {
        for (int i = 0; i < ds->GetLayerCount(); ++i) {
            OGRLayer* l = ds->GetLayer(i);
            if (!is_line_layer(l)) continue;
            const std::string n = lower(l->GetName());
            if (n.rfind("ridge", 0) == 0 || n.rfind("crete", 0) == 0) per_kind.push_back({l, LineKind::Ridge});
            else if (n.rfind("valley", 0) == 0 || n.rfind("thalweg", 0) == 0 || n.rfind("talweg", 0) == 0)
                per_kind.push_back({l, LineKind::Valley});
            else if (!lines && l->GetLayerDefn()->GetFieldIndex(opt.label_field.c_str()) >= 0)
                lines = l;
        }
    }
    if (lines) {
        const Reprojector proj = reprojector(lines, working_wkt, what);
        const int idx = lines->GetLayerDefn()->GetFieldIndex(opt.label_field.c_str());
        if (idx < 0)
            throw Error(Code::BadLayer, what + ": line layer '" + std::string(lines->GetName()) + "' has no label field '" +
                                            opt.label_field + "' (ridge / valley / other)");
        lines->ResetReading();
        for (auto& feat : *lines) {
            OGRGeometry* g = feat->GetGeometryRef();
            if (!g) continue;
            LineKind kind;
            const std::string v = feat->IsFieldSetAndNotNull(idx) ? feat->GetFieldAsString(idx) : "";
            if (!parse_kind(v, kind))
                throw Error(Code::BadLayer, what + ": line " + std::to_string(feat->GetFID()) + ": label '" + v +
                                                "' is not ridge, valley or other");
            if (kind == LineKind::Other) continue;
            std::unique_ptr<OGRGeometry> c(g->clone());
            proj.apply(c.get());
            add_lines(c.get(), kind, p.lines);
        }
    } else if (!per_kind.empty()) {
        for (auto [l, kind] : per_kind) {
            const Reprojector proj = reprojector(l, working_wkt, what);
            l->ResetReading();
            for (auto& feat : *l) {
                if (!feat->GetGeometryRef()) continue;
                std::unique_ptr<OGRGeometry> c(feat->GetGeometryRef()->clone());
                proj.apply(c.get());
                add_lines(c.get(), kind, p.lines);
            }
        }
    } else {
        throw Error(Code::BadLayer, what + ": no line layer with a '" + opt.label_field +
                                        "' field and no 'ridges' / 'valleys' layers: the faces' borders cannot be labelled");
    }

    // ---- Orientation and density layers.
    OGRLayer* olayer = find_layer(opt.orientation_layer, is_line_layer, "line");
    if (!olayer && opt.orientation_layer.empty()) {
        for (int i = 0; i < ds->GetLayerCount() && !olayer; ++i) {
            const std::string n = lower(ds->GetLayer(i)->GetName());
            if (is_line_layer(ds->GetLayer(i)) && n.rfind("orient", 0) == 0) olayer = ds->GetLayer(i);
        }
    }
    if (olayer) {
        const Reprojector proj = reprojector(olayer, working_wkt, what);
        int matched = 0;
        olayer->ResetReading();
        for (auto& feat : *olayer) {
            if (!feat->GetGeometryRef()) continue;
            std::unique_ptr<OGRGeometry> c(feat->GetGeometryRef()->clone());
            proj.apply(c.get());
            std::vector<LabelledLine> ls;
            add_lines(c.get(), LineKind::Other, ls);
            for (const auto& l : ls) {
                const Point a = l.points.front(), b = l.points.back();
                const Point mid = (a + b) / 2;
                for (auto& f : p.faces)
                    if (!f.orientation && f.region.contains(mid)) {
                        f.orientation = std::atan2(b.y - a.y, b.x - a.x);
                        ++matched;
                        break;
                    }
            }
        }
        p.notes.push_back("orientation of " + std::to_string(matched) + " face(s) from layer '" + olayer->GetName() + "'");
    }
    OGRLayer* dlayer = find_layer(opt.density_layer, nullptr, "");
    if (dlayer) {
        const Reprojector proj = reprojector(dlayer, working_wkt, what);
        const int idx = dlayer->GetLayerDefn()->GetFieldIndex(opt.density_field.c_str());
        if (idx < 0)
            throw Error(Code::BadLayer, what + ": layer '" + opt.density_layer + "' has no field '" + opt.density_field + "'");
        dlayer->ResetReading();
        for (auto& feat : *dlayer) {
            if (!feat->GetGeometryRef() || !feat->IsFieldSetAndNotNull(idx)) continue;
            const double d = feat->GetFieldAsDouble(idx);
            if (!(d >= 0 && d <= 1))
                throw Error(Code::BadLayer, what + ": layer '" + opt.density_layer + "': density " + std::to_string(d) + " is not in [0, 1]");
            std::unique_ptr<OGRGeometry> c(feat->GetGeometryRef()->clone());
            proj.apply(c.get());
            OGRPoint centre;
            c->Centroid(&centre);
            for (auto& f : p.faces)
                if (f.region.contains({centre.getX(), centre.getY()})) f.density = d;
        }
    }
    label_boundaries(p, opt.snap);
    return p;
}

}  // namespace carto
