// A tiled extraction of the partition (`rockhatch tiles --partition auto`): one tile of it,
// and the merge of the tiles into one partition file (carto/tiles.hpp says what is exact).
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <tuple>

#include "carto/error.hpp"
#include "carto/extract.hpp"
#include "carto/tiles.hpp"
#include "gdal_scope.hpp"

namespace carto {
namespace {

// A tile extracts again over a larger window while a face it owns comes within the halo of
// the window's edge; each round grows the window to hold those faces, so this many rounds
// are only reached by a face that keeps growing as the window does (a bug, not terrain).
constexpr int kMaxRounds = 16;

// Whether `inner` grown by `margin` stays inside `window`, a side of the window lying on the
// DEM's edge excepted (the whole run ends there too).
bool well_inside(const tex::BBox& inner, double margin, const tex::BBox& window, const tex::BBox& dem) {
    // Half a cell of slack: the window's sides and the DEM's are the same cell edges, computed
    // from different origins.
    const double eps = 1e-9 * std::max({1.0, std::abs(dem.xmin), std::abs(dem.xmax), std::abs(dem.ymin),
                                        std::abs(dem.ymax)});
    auto at_edge = [&](double w, double d) { return std::abs(w - d) <= eps; };
    return (at_edge(window.xmin, dem.xmin) || inner.xmin - margin >= window.xmin) &&
           (at_edge(window.xmax, dem.xmax) || inner.xmax + margin <= window.xmax) &&
           (at_edge(window.ymin, dem.ymin) || inner.ymin - margin >= window.ymin) &&
           (at_edge(window.ymax, dem.ymax) || inner.ymax + margin <= window.ymax);
}

std::vector<Point> ring_points(const OGRLinearRing& r) {
    std::vector<Point> pts;
    for (int i = 0; i < r.getNumPoints(); ++i) pts.push_back({r.getX(i), r.getY(i)});
    if (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
    return pts;
}

// A border line as a key that does not depend on the direction it was traced in.
std::pair<int, std::vector<Point>> line_key(const LabelledLine& l) {
    std::vector<Point> pts = l.points;
    auto less = [](const Point& a, const Point& b) { return std::tie(a.x, a.y) < std::tie(b.x, b.y); };
    if (!pts.empty() && less(pts.back(), pts.front())) std::reverse(pts.begin(), pts.end());
    return {int(l.kind), pts};
}

struct KeyLess {
    bool operator()(const std::pair<int, std::vector<Point>>& a, const std::pair<int, std::vector<Point>>& b) const {
        if (a.first != b.first) return a.first < b.first;
        return std::lexicographical_compare(a.second.begin(), a.second.end(), b.second.begin(), b.second.end(),
                                            [](const Point& p, const Point& q) {
                                                return std::tie(p.x, p.y) < std::tie(q.x, q.y);
                                            });
    }
};

}  // namespace

ExtractTileReport extract_tile(const ExtractOptions& o, const tex::BBox& tile, double halo, const std::string& out) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!(halo >= 0) || !std::isfinite(halo))
        throw Error(Code::Usage, "--extract-halo: " + std::to_string(halo) + " is not a non-negative length");
    if (o.dem.empty()) throw Error(Code::Usage, o.what + ": a tiled extraction reads the DEM from a file");
    if (!o.mask.empty()) throw Error(Code::Usage, "--mask: not available in a tiled extraction");
    // A geographic DEM is read in its working grid (UTM), window by window, as a whole
    // extraction reads it whole.
    const WorkingGrid grid = working_grid(raster_info(o.dem, o.what));
    const RasterInfo& info = grid.grid;
    const tex::BBox dem_box = info.bounds();
    const double cell = std::min(std::abs(info.gt[1]), std::abs(info.gt[5]));
    const int halo_cells = int(std::ceil(halo / cell));

    ExtractTileReport report;
    Partition kept;
    kept.crs_wkt = info.crs_wkt;
    tex::BBox box = tile.intersection(dem_box);
    while (box.xmin < box.xmax && box.ymin < box.ymax) {
        if (++report.rounds > kMaxRounds)
            throw Error(Code::Failure, o.what + " '" + o.dem + "': the faces of tile " + std::to_string(tile.xmin) +
                                           ", " + std::to_string(tile.ymin) + " did not settle in " +
                                           std::to_string(kMaxRounds) + " windows");
        ExtractOptions eo = o;
        eo.raster = read_working_window(o.dem, o.what, grid, box, halo_cells);
        if (eo.raster->width == 0) break;
        const tex::BBox window = eo.raster->bounds();
        report.dem_cells = (long long)eo.raster->width * eo.raster->height;
        ExtractResult res;
        try {
            res = extract_partition(eo);
        } catch (const Error& e) {
            // No rock in the window (or only NoData): the tile owns no face. A whole DEM
            // without rock is reported once the tiles are merged.
            if (e.code() != Code::BadLayer) throw;
            break;
        }
        // The faces this tile owns: their anchor lies in its half-open box.
        std::vector<int> owned;
        std::set<int> owned_face;
        tex::BBox reach = box;
        bool trusted = true;
        for (std::size_t i = 0; i < res.partition.faces.size(); ++i) {
            const RockFace& f = res.partition.faces[i];
            if (!owns(tile, face_anchor(f))) continue;
            owned.push_back(int(i));
            owned_face.insert(int(f.id - 1));
            reach.add(f.region.bbox());
            trusted = trusted && well_inside(f.region.bbox(), halo, window, dem_box);
        }
        if (!trusted) {
            // A face reaches the halo: what lies beyond the window may change it. Extract again
            // over a window holding every such face, with the halo around it.
            box = reach.intersection(dem_box);
            continue;
        }
        // Global face key: the whole raster's index of the face's first cell in raster order,
        // which is how a whole run numbers its faces (extract/faces.cpp).
        const Raster& fr = res.faces;
        std::map<int, long long> first;
        for (int r = 0; r < fr.height; ++r)
            for (int c = 0; c < fr.width; ++c) {
                const float v = fr.at(c, r);
                if (!(v >= 0)) continue;
                const int f = int(v);
                if (owned_face.count(f) && !first.count(f))
                    first[f] = (long long)(r + fr.row0) * info.width + (c + fr.col0);
            }
        for (int i : owned) {
            RockFace f = res.partition.faces[std::size_t(i)];
            f.id = first.at(int(f.id - 1));
            f.boundary.clear();
            kept.faces.push_back(std::move(f));
        }
        for (std::size_t k = 0; k < res.partition.lines.size(); ++k) {
            const auto& sides = res.line_faces[k];
            if (owned_face.count(sides[0]) || owned_face.count(sides[1])) kept.lines.push_back(res.partition.lines[k]);
        }
        break;
    }
    report.faces = kept.faces.size();
    report.lines = kept.lines.size();
    write_partition_gpkg(kept, out, true);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

namespace {

// Counts the pairs of faces from different tiles that overlap, and their common area.
void count_overlaps(const std::vector<std::unique_ptr<OGRGeometry>>& shapes, const std::vector<std::size_t>& tile_of,
                    PartitionMerge& m) {
    constexpr double kShare = 1e-6;  // of the smaller face: borders shared within rounding do not count
    std::vector<OGREnvelope> box(shapes.size());
    std::vector<double> area(shapes.size());
    std::vector<std::size_t> order(shapes.size());
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        shapes[i]->getEnvelope(&box[i]);
        area[i] = OGR_G_Area(OGRGeometry::ToHandle(shapes[i].get()));
        m.area += area[i];
        order[i] = i;
    }
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return box[a].MinX < box[b].MinX; });
    for (std::size_t k = 0; k < order.size(); ++k) {
        const std::size_t a = order[k];
        for (std::size_t l = k + 1; l < order.size() && box[order[l]].MinX <= box[a].MaxX; ++l) {
            const std::size_t b = order[l];
            if (tile_of[a] == tile_of[b] || !box[a].Intersects(box[b]) || !shapes[a]->Intersects(shapes[b].get())) continue;
            const std::unique_ptr<OGRGeometry> common(shapes[a]->Intersection(shapes[b].get()));
            const double c = common ? OGR_G_Area(OGRGeometry::ToHandle(common.get())) : 0.0;
            if (c > kShare * std::min(area[a], area[b])) {
                ++m.overlaps;
                m.overlap_area += c;
            }
        }
    }
}

}  // namespace

PartitionMerge merge_partition_tiles(const std::vector<std::string>& parts, const std::string& out, bool overwrite) {
    register_gdal();
    QuietGdal quiet;
    Partition all;
    std::vector<std::unique_ptr<OGRGeometry>> shapes;  // each face as read, for the overlap check
    std::vector<std::size_t> tile_of;
    std::set<std::pair<int, std::vector<Point>>, KeyLess> lines;
    for (const std::string& path : parts) {
        std::unique_ptr<GDALDataset> ds(static_cast<GDALDataset*>(
            GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
        OGRLayer* faces = ds ? ds->GetLayerByName("faces") : nullptr;
        OGRLayer* ls = ds ? ds->GetLayerByName("lines") : nullptr;
        if (!faces || !ls) throw Error(Code::BadLayer, "partition tile '" + path + "': no faces and lines layers");
        if (all.crs_wkt.empty() && faces->GetSpatialRef()) {
            char* wkt = nullptr;
            faces->GetSpatialRef()->exportToWkt(&wkt);
            all.crs_wkt = wkt ? wkt : "";
            CPLFree(wkt);
        }
        const int fall = faces->GetLayerDefn()->GetFieldIndex("fall_line");
        const int shade = faces->GetLayerDefn()->GetFieldIndex("shade");
        faces->ResetReading();
        for (std::unique_ptr<OGRFeature> f(faces->GetNextFeature()); f; f.reset(faces->GetNextFeature())) {
            const OGRGeometry* g = f->GetGeometryRef();
            if (!g || wkbFlatten(g->getGeometryType()) != wkbPolygon) continue;
            const auto* poly = g->toPolygon();
            std::vector<std::vector<Point>> holes;
            for (int h = 0; h < poly->getNumInteriorRings(); ++h) holes.push_back(ring_points(*poly->getInteriorRing(h)));
            RockFace rf;
            rf.id = f->GetFieldAsInteger64("id");
            rf.region = tex::Region(ring_points(*poly->getExteriorRing()), holes, "partition tile '" + path + "'");
            if (fall >= 0 && f->IsFieldSetAndNotNull(fall))
                rf.orientation = (90.0 - f->GetFieldAsDouble(fall)) * M_PI / 180.0;
            if (shade >= 0 && f->IsFieldSetAndNotNull(shade)) rf.density = f->GetFieldAsDouble(shade);
            all.faces.push_back(std::move(rf));
            shapes.emplace_back(g->clone());
            tile_of.push_back(std::size_t(&path - parts.data()));
        }
        ls->ResetReading();
        for (std::unique_ptr<OGRFeature> f(ls->GetNextFeature()); f; f.reset(ls->GetNextFeature())) {
            const OGRGeometry* g = f->GetGeometryRef();
            if (!g || wkbFlatten(g->getGeometryType()) != wkbLineString) continue;
            const auto* line = g->toLineString();
            LabelledLine l;
            const std::string kind = f->GetFieldAsString("kind");
            l.kind = kind == "ridge"    ? LineKind::Ridge
                     : kind == "valley" ? LineKind::Valley
                     : kind == "cliff"  ? LineKind::Cliff
                                        : LineKind::Other;
            for (int i = 0; i < line->getNumPoints(); ++i) l.points.push_back({line->getX(i), line->getY(i)});
            lines.insert(line_key(l));  // a border of faces owned by two tiles comes twice
        }
    }
    // Faces in the whole run's order (raster order of their first cells, then their place),
    // numbered from 1 as a whole run numbers them.
    std::stable_sort(all.faces.begin(), all.faces.end(), [](const RockFace& a, const RockFace& b) {
        const tex::BBox &p = a.region.bbox(), &q = b.region.bbox();
        return std::tie(a.id, p.xmin, p.ymin) < std::tie(b.id, q.xmin, q.ymin);
    });
    std::int64_t last = -1, n = 0;
    for (RockFace& f : all.faces) {
        if (f.id != last) ++n;
        last = f.id;
        f.id = n;
    }
    for (const auto& [kind, pts] : lines) all.lines.push_back({pts, LineKind(kind)});
    PartitionMerge m;
    m.faces = all.faces.size();
    count_overlaps(shapes, tile_of, m);
    write_partition_gpkg(all, out, overwrite);
    return m;
}

}  // namespace carto
