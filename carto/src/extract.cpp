#include "carto/extract.hpp"

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <queue>

#include "carto/error.hpp"
#include "carto/fields.hpp"
#include "carto/output.hpp"
#include "corner_cut.hpp"
#include "gdal_scope.hpp"
#include "temp_file.hpp"

namespace carto {
namespace {

// The eight neighbours (rows go south): E, SE, S, SW, W, NW, N, NE.
constexpr int kDc[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDr[8] = {0, 1, 1, 1, 0, -1, -1, -1};

struct Grid {
    int w = 0, h = 0;
    std::size_t size() const { return std::size_t(w) * h; }
    bool inside(int c, int r) const { return c >= 0 && r >= 0 && c < w && r < h; }
    std::size_t at(int c, int r) const { return std::size_t(r) * w + c; }
};

void step(const Progress& p, double f, const std::string& stage) {
    if (p && !p(f, stage)) throw Error(Code::Cancelled, "cancelled during " + stage);
}

// NoData-aware window mean (carto/fields.hpp) on the extraction's grid.
std::vector<float> box_mean(const Grid& g, const std::vector<float>& v, int radius) {
    return carto::box_mean(v, g.w, g.h, radius);
}

// Connected components of the cells where on[i] is true (4- or 8-connected), numbered from 0
// in raster order; -1 elsewhere.
std::vector<int> components(const Grid& g, const std::vector<char>& on, bool eight, int& count) {
    std::vector<int> lab(g.size(), -1);
    std::vector<std::size_t> stack;
    count = 0;
    for (std::size_t s = 0; s < g.size(); ++s) {
        if (!on[s] || lab[s] >= 0) continue;
        lab[s] = count;
        stack.push_back(s);
        while (!stack.empty()) {
            const std::size_t i = stack.back();
            stack.pop_back();
            const int c = int(i % g.w), r = int(i / g.w);
            for (int k = 0; k < 8; k += eight ? 1 : 2) {
                const int cc = c + kDc[k], rr = r + kDr[k];
                if (!g.inside(cc, rr)) continue;
                const std::size_t j = g.at(cc, rr);
                if (on[j] && lab[j] < 0) {
                    lab[j] = count;
                    stack.push_back(j);
                }
            }
        }
        ++count;
    }
    return lab;
}

// The 8- (or 4-) connected non-rock pieces: label per cell (-1 on rock), and per piece its
// size and whether it is open (reaches the grid's edge, NoData or the outside of the user's mask)
// rather than a hole in the rock.
struct NonRock {
    std::vector<int> lab;
    std::vector<std::size_t> size;
    std::vector<char> open;
};

NonRock non_rock_pieces(const Grid& g, const std::vector<char>& rock, const std::vector<float>& dem,
                        const std::vector<char>& inside_mask, bool eight) {
    std::vector<char> non_rock(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) non_rock[i] = !rock[i];
    NonRock out;
    int n = 0;
    out.lab = components(g, non_rock, eight, n);
    out.size.assign(std::size_t(n), 0);
    out.open.assign(std::size_t(n), 0);
    for (int r = 0; r < g.h; ++r)
        for (int c = 0; c < g.w; ++c) {
            const std::size_t i = g.at(c, r);
            const int l = out.lab[i];
            if (l < 0) continue;
            ++out.size[l];
            if (c == 0 || r == 0 || c == g.w - 1 || r == g.h - 1 || std::isnan(dem[i]) ||
                (!inside_mask.empty() && !inside_mask[i]))
                out.open[l] = 1;
        }
    return out;
}

// The user's mask layer burnt onto the grid (1 inside a polygon).
std::vector<char> rasterize_mask(const std::string& path, const Raster& grid) {
    const std::string what = "--mask '" + path + "'";
    if (!std::filesystem::exists(path)) throw Error(Code::InputMissing, what + ": no such file");
    register_gdal();
    const QuietGdal quiet;
    std::unique_ptr<GDALDataset> ds(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    if (!ds) throw Error(Code::InputMissing, what + ": not a vector dataset OGR can read");
    OGRLayer* layer = nullptr;
    for (int i = 0; i < ds->GetLayerCount() && !layer; ++i) {
        const auto t = wkbFlatten(ds->GetLayer(i)->GetGeomType());
        if (t == wkbPolygon || t == wkbMultiPolygon) layer = ds->GetLayer(i);
    }
    if (!layer) throw Error(Code::BadLayer, what + ": no polygon layer");
    const OGRSpatialReference* srs = layer->GetSpatialRef();
    const char* srs_name = srs ? srs->GetName() : nullptr;
    if (!srs || srs->IsEmpty() || (srs_name && std::string(srs_name).find("Undefined") != std::string::npos))
        throw Error(Code::NoCrs, what + ": layer '" + std::string(layer->GetName()) + "' has no CRS");
    OGRSpatialReference src(*srs), dst;
    src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    dst.importFromWkt(grid.crs_wkt.c_str());
    dst.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> ct;
    if (!src.IsSame(&dst)) {
        ct.reset(OGRCreateCoordinateTransformation(&src, &dst));
        if (!ct) throw Error(Code::NoCrs, what + ": cannot reproject the layer to the DEM's CRS");
    }
    std::vector<std::unique_ptr<OGRGeometry>> geoms;
    layer->ResetReading();
    for (auto& f : *layer) {
        if (!f->GetGeometryRef()) continue;
        std::unique_ptr<OGRGeometry> g(f->GetGeometryRef()->clone());
        if (ct) g->transform(ct.get());
        geoms.push_back(std::move(g));
    }
    if (geoms.empty())
        throw Error(Code::BadLayer, what + ": layer '" + std::string(layer->GetName()) + "' holds no polygon");
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    std::unique_ptr<GDALDataset> ras(mem->Create("", grid.width, grid.height, 1, GDT_Byte, nullptr));
    ras->SetGeoTransform(const_cast<double*>(grid.gt.data()));
    std::vector<OGRGeometryH> handles;
    std::vector<double> burn;
    for (auto& g : geoms) {
        handles.push_back(OGRGeometry::ToHandle(g.get()));
        burn.push_back(1.0);
    }
    int band = 1;
    if (GDALRasterizeGeometries(GDALDataset::ToHandle(ras.get()), 1, &band, int(handles.size()), handles.data(),
                                nullptr, nullptr, burn.data(), nullptr, nullptr, nullptr) != CE_None)
        throw Error(Code::BadLayer, what + ": cannot rasterize the polygons");
    std::vector<char> out(std::size_t(grid.width) * grid.height);
    if (ras->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, grid.width, grid.height, out.data(), grid.width, grid.height,
                                        GDT_Byte, 0, 0) != CE_None)
        throw Error(Code::Failure, what + ": cannot read the rasterized mask");
    return out;
}

// Flow on a surface: every cell's D8 direction (index of the steepest lower neighbour, -1
// for sinks), used to trace lines, and its contributing area by multiple flow directions
// (Freeman: shared among the lower neighbours in proportion to slope^1.1), which follows the
// true gradient on planar flanks instead of D8's straight parallel paths.
//
// Depressions are found by priority flood from the edges and the NoData border. Those at most
// `max_fill` deep are filled and drain through their spill point along the flood's order;
// deeper ones (on the inverted DEM: summits) are kept and are sinks.
struct Flow {
    std::vector<int> down;
    std::vector<double> area;
};

Flow flow(const Grid& g, const std::vector<float>& z, double dx, double dy, double max_fill) {
    const std::size_t n = g.size();
    std::vector<float> filled(z);
    std::vector<int> flooder(n, -1);
    std::vector<std::size_t> order(n, 0);  // pop order of the flood
    std::vector<char> seen(n, 0);
    using Item = std::pair<float, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
    for (int r = 0; r < g.h; ++r)
        for (int c = 0; c < g.w; ++c) {
            const std::size_t i = g.at(c, r);
            if (std::isnan(z[i])) continue;
            bool border = false;
            for (int k = 0; k < 8 && !border; ++k) {
                const int cc = c + kDc[k], rr = r + kDr[k];
                border = !g.inside(cc, rr) || std::isnan(z[g.at(cc, rr)]);
            }
            if (border) {
                seen[i] = 1;
                pq.push({z[i], i});
            }
        }
    std::size_t popped = 0;
    while (!pq.empty()) {
        const auto [level, i] = pq.top();
        pq.pop();
        order[i] = popped++;
        const int c = int(i % g.w), r = int(i / g.w);
        for (int k = 0; k < 8; ++k) {
            const int cc = c + kDc[k], rr = r + kDr[k];
            if (!g.inside(cc, rr)) continue;
            const std::size_t j = g.at(cc, rr);
            if (seen[j] || std::isnan(z[j])) continue;
            seen[j] = 1;
            filled[j] = std::max(z[j], level);
            flooder[j] = int(i);
            pq.push({filled[j], j});
        }
    }
    // Depressions (8-connected raised cells): shallow ones stay filled, deep ones are restored.
    std::vector<char> raised(n);
    for (std::size_t i = 0; i < n; ++i) raised[i] = !std::isnan(z[i]) && filled[i] > z[i];
    int ndep = 0;
    const std::vector<int> dep = components(g, raised, true, ndep);
    std::vector<float> depth(std::size_t(ndep), 0.0f);
    for (std::size_t i = 0; i < n; ++i)
        if (dep[i] >= 0) depth[dep[i]] = std::max(depth[dep[i]], filled[i] - z[i]);
    std::vector<float> s(filled);
    for (std::size_t i = 0; i < n; ++i)
        if (dep[i] >= 0 && depth[dep[i]] > max_fill) s[i] = z[i];

    // Highest first; on equal heights the later-flooded first (it drains to its flooder).
    std::vector<std::size_t> idx;
    idx.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isnan(z[i])) idx.push_back(i);
    std::sort(idx.begin(), idx.end(),
              [&](std::size_t a, std::size_t b) { return s[a] != s[b] ? s[a] > s[b] : order[a] > order[b]; });
    Flow f;
    f.down.assign(n, -1);
    f.area.assign(n, 0.0);
    const double cell_area = dx * dy, diag = std::hypot(dx, dy);
    for (std::size_t i : idx) {
        f.area[i] += cell_area;
        const int c = int(i % g.w), r = int(i / g.w);
        double best = 0, wsum = 0, w[8];
        for (int k = 0; k < 8; ++k) {
            w[k] = 0;
            const int cc = c + kDc[k], rr = r + kDr[k];
            if (!g.inside(cc, rr)) continue;
            const std::size_t j = g.at(cc, rr);
            if (std::isnan(z[j]) || !(s[j] < s[i])) continue;
            const double dist = (kDc[k] && kDr[k]) ? diag : (kDc[k] ? dx : dy);
            const double slope = (double(s[i]) - s[j]) / dist;
            w[k] = std::pow(slope, 1.1);
            wsum += w[k];
            if (slope > best) {
                best = slope;
                f.down[i] = int(j);
            }
        }
        if (wsum > 0) {
            for (int k = 0; k < 8; ++k)
                if (w[k] > 0) f.area[g.at(c + kDc[k], r + kDr[k])] += f.area[i] * w[k] / wsum;
        } else if (flooder[i] >= 0 && !(dep[i] >= 0 && depth[dep[i]] > max_fill) && s[flooder[i]] <= s[i]) {
            f.down[i] = flooder[i];  // a flat (or a filled depression) draining out
            f.area[std::size_t(flooder[i])] += f.area[i];
        }
    }
    return f;
}

// Contributing area of a cell over the mean of its two neighbours across its D8 direction:
// 1 on a planar flank (where MFD area only grows with the flow length), larger in a hollow.
double convergence(const Grid& g, const Flow& f, std::size_t i) {
    if (f.down[i] < 0) return 0;
    const int c = int(i % g.w), r = int(i / g.w);
    const int dc = f.down[i] % g.w - c, dr = f.down[i] / g.w - r;
    double sides = 0;
    for (int side : {-1, 1}) {
        const int cc = c - side * dr, rr = r + side * dc;
        sides += g.inside(cc, rr) ? f.area[g.at(cc, rr)] : 0.0;
    }
    return sides > 0 ? 2 * f.area[i] / sides : 1e9;
}

// The channel network: cells whose contributing area reaches the threshold and where flow
// converges (the area is at least `converge` x the mean of the two neighbours across the D8
// direction: on a planar flank, where MFD area only grows with the flow length, it is equal),
// each followed down its D8 path while the area stays above the threshold: 1-cell wide lines.
std::vector<char> channels(const Grid& g, const Flow& f, double threshold, double converge,
                           const std::vector<char>& edge, int near) {
    std::vector<char> ch(g.size(), 0);
    for (int r = 0; r < g.h; ++r)
        for (int c = 0; c < g.w; ++c) {
            const std::size_t i = g.at(c, r);
            if (!(f.area[i] >= threshold) || f.down[i] < 0 || ch[i] || edge[i]) continue;
            bool crest = convergence(g, f, i) >= converge;
            // Not a side line along a bigger one: no cell within `near` carries twice the area.
            for (int rr = std::max(0, r - near); crest && rr <= std::min(g.h - 1, r + near); ++rr)
                for (int cc = std::max(0, c - near); crest && cc <= std::min(g.w - 1, c + near); ++cc)
                    if (f.area[g.at(cc, rr)] > 2 * f.area[i]) crest = false;
            if (!crest) continue;
            // Into the border band for a few cells only: the line reaches the edge of the DEM
            // without running along it.
            int band = 0;
            for (std::size_t j = i; f.area[j] >= threshold && !ch[j] && (band += edge[j]) <= 3;) {
                ch[j] = 1;
                if (f.down[j] < 0) break;
                j = std::size_t(f.down[j]);
            }
        }
    return ch;
}

// Removes first-order branches (from a head down to the first junction with another line)
// that are shorter than `min_cells`, or that run for most of their length within `near`
// cells of a line draining more: the short or parallel paths drawn on a wall beside a thalweg.
void prune_spurs(const Grid& g, const Flow& f, std::vector<char>& ch, int min_cells, int near) {
    std::vector<int> ups(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && f.down[i] >= 0 && ch[f.down[i]]) ++ups[f.down[i]];
    std::vector<std::size_t> heads;
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && ups[i] == 0) heads.push_back(i);
    std::vector<int> owner(g.size(), -1);
    std::vector<std::vector<std::size_t>> paths;
    for (std::size_t h : heads) {
        std::vector<std::size_t> path;
        for (std::size_t j = h;;) {
            path.push_back(j);
            const int d = f.down[j];
            if (d < 0 || !ch[d] || ups[d] > 1) break;
            j = std::size_t(d);
        }
        for (std::size_t j : path) owner[j] = int(paths.size());
        paths.push_back(std::move(path));
    }
    std::vector<std::size_t> drop;
    for (std::size_t k = 0; k < paths.size(); ++k) {
        const auto& path = paths[k];
        bool remove = int(path.size()) < min_cells;
        if (!remove) {
            std::size_t beside = 0;
            for (std::size_t i : path) {
                const int c = int(i % g.w), r = int(i / g.w);
                bool found = false;
                for (int rr = std::max(0, r - near); !found && rr <= std::min(g.h - 1, r + near); ++rr)
                    for (int cc = std::max(0, c - near); !found && cc <= std::min(g.w - 1, c + near); ++cc) {
                        const std::size_t j = g.at(cc, rr);
                        found = ch[j] && owner[j] != int(k) && f.area[j] > f.area[i];
                    }
                beside += found;
            }
            remove = 10 * beside > 7 * path.size();
        }
        if (remove) drop.insert(drop.end(), path.begin(), path.end());
    }
    for (std::size_t i : drop) ch[i] = 0;
}

// Cross-profile concavity of a surface at each cell: its height minus the mean of the two
// points `dist` away along the contour line (across the fall line). Negative on a valley
// floor, positive on a crest, about 0 on a planar flank.
std::vector<float> concavity(const Grid& g, const std::vector<float>& z, double dx, double dy, double dist) {
    std::vector<float> out(g.size(), NAN);
    auto at = [&](double c, double r) -> double {  // bilinear at cell coordinates (centres at .5)
        const double fx = c - 0.5, fy = r - 0.5;
        const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
        const double tx = fx - x0, ty = fy - y0;
        double s = 0;
        for (int k = 0; k < 4; ++k) {
            const int x = x0 + (k & 1), y = y0 + (k >> 1);
            if (!g.inside(x, y) || std::isnan(z[g.at(x, y)])) return NAN;
            s += z[g.at(x, y)] * ((k & 1) ? tx : 1 - tx) * ((k >> 1) ? ty : 1 - ty);
        }
        return s;
    };
    for (int r = 1; r + 1 < g.h; ++r)
        for (int c = 1; c + 1 < g.w; ++c) {
            const double gx = (double(z[g.at(c + 1, r)]) - z[g.at(c - 1, r)]) / (2 * dx);
            const double gy = (double(z[g.at(c, r + 1)]) - z[g.at(c, r - 1)]) / (2 * dy);
            const double n = std::hypot(gx, gy);
            if (!(n > 0)) continue;
            // Contour direction in cell units (perpendicular to the gradient).
            const double ux = -gy / n * dist / dx, uy = gx / n * dist / dy;
            const double a = at(c + 0.5 + ux, r + 0.5 + uy), b = at(c + 0.5 - ux, r + 0.5 - uy);
            out[g.at(c, r)] = float(z[g.at(c, r)] - (a + b) / 2);
        }
    return out;
}

// Prolongs each head of a network upstream along its valley floor: to the higher neighbour
// (8 around) that is most concave, while concave by at least `depth` (two cells' tolerance),
// for at most `max_cells`; where the floor fades (near a col or a summit) the walk finishes
// by steepest ascent over at most `finish` cells. Kept only when it reaches a cell of `stop`
// (the other lines), or leaves the rock for the `open` non-rock, or comes next to the grid's
// edge (the edge cell joins the line), so the line cuts the rock area instead of dangling in
// it. Holes of the rock (non-rock that is not `open`) are crossed, as a line ending in one
// seldom cuts its face; if the walk then gets nowhere, it is kept up to the hole. A head in a
// hole first walks into the rock.
// Kept steps are linked downstream in `down`, so the network can be traced along them; those
// of the steepest finish are set in `straight` (they cut the rock but follow no crest or floor).
void extend_heads(const Grid& g, std::vector<int>& down, std::vector<char>& ch, std::vector<char>& straight,
                  const std::vector<float>& z, const std::vector<float>& conc, double depth,
                  const std::vector<char>& stop, const std::vector<char>& rock, const std::vector<char>& open,
                  int max_cells, int finish) {
    std::vector<char> has_up(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && down[i] >= 0) has_up[down[i]] = 1;
    std::vector<std::size_t> heads;
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && !has_up[i]) heads.push_back(i);
    std::vector<std::size_t> path;
    std::vector<char> steep;  // per step of the path: taken by the steepest finish
    auto keep = [&](std::size_t marked) {
        for (std::size_t k = 1; k < marked; ++k) {
            ch[path[k]] = 1;
            down[path[k]] = int(path[k - 1]);
            straight[path[k]] = k < steep.size() && steep[k];
        }
    };
    for (std::size_t h : heads) {
        path.assign(1, h);
        steep.assign(1, 0);
        int weak = 0, finishing = -1;
        bool in_rock = rock[h] || open[h];
        std::size_t fallback = 0;  // the steps kept if the walk, having entered a hole, gets nowhere
        while (int(path.size()) <= max_cells) {
            const std::size_t i = path.back();
            const int c = int(i % g.w), r = int(i / g.w);
            int best = -1, edge = -1;
            double key = 0;
            for (int k = 0; k < 8; ++k) {
                const int cc = c + kDc[k], rr = r + kDr[k];
                if (!g.inside(cc, rr)) continue;
                const std::size_t j = g.at(cc, rr);
                if (rock[j] && (cc == 0 || rr == 0 || cc == g.w - 1 || rr == g.h - 1) && edge < 0) edge = int(j);
                if (!(z[j] > z[i]) || std::isnan(conc[j])) continue;
                // Along the floor: the most concave; finishing: the steepest.
                const double v = finishing < 0 ? conc[j] : -(z[j] - z[i]) / ((kDc[k] && kDr[k]) ? 1.4142 : 1.0);
                if (best < 0 || v < key) best = int(j), key = v;
            }
            if (in_rock && edge >= 0 && path.size() > 1) {  // at the grid's edge: the edge cell ends the line
                path.push_back(std::size_t(edge));
                steep.push_back(finishing >= 0);
                keep(path.size());
                fallback = 0;
                break;
            }
            if (best < 0) break;
            if (stop[best] || (in_rock && open[best])) {
                path.push_back(std::size_t(best));
                keep(path.size() - 1);
                fallback = 0;
                break;
            }
            // Into a hole of the rock: crossed (ending there seldom cuts the face), but the
            // steps so far are kept if nothing better is reached.
            if (in_rock && !rock[best] && !fallback && rock[i]) fallback = path.size();
            in_rock = in_rock || rock[best];
            if (finishing < 0) {
                weak = conc[best] <= -depth ? 0 : weak + 1;
                if (weak > 2) finishing = 0;
            } else if (++finishing > finish) {
                break;
            }
            path.push_back(std::size_t(best));
            steep.push_back(finishing >= 0);
        }
        if (fallback) keep(fallback);
    }
}

// ---- Polygons from the face grid

// Douglas-Peucker tolerance of the lighter fallback generalisation, in cells.
constexpr double kHalfCell = 0.5;

// Directions between cell corners: E, S, W, N (rows go south).
constexpr int kCx[4] = {1, 0, -1, 0};
constexpr int kCy[4] = {0, 1, 0, -1};

struct Chain {
    std::vector<Point> raw;     // corner coordinates (col, row)
    // The shapes a face may use, from the most generalised to the cell edges themselves
    // (`level` picks one): 0 the generalised chain, 1 the cut steps simplified within half a
    // cell and rounded once, 2 the cut steps themselves (a one-cell staircase becomes its
    // diagonal), 3 the steps cut at the middles of the cell edges (a face of line cells alone
    // would lose its width if both of its borders moved onto the line), 4 the cell edges.
    // Levels 0 to 3 run along a grid axis only where the trace runs straight; level 4 is the
    // last resort. All five end at the same node places (NodePlaces).
    std::array<std::vector<Point>, 5> shapes;
    int right = -1, left = -1;  // faces on either side (-1: outside)
    int first_dir = 0, last_dir = 0;
    long long start = -1, end = -1;  // corner ids (closed chains: start == end)
    bool closed = false;
    int level = 0;
    static constexpr int kLevels = 5;
    const std::vector<Point>& shape() const { return shapes[std::size_t(level)]; }
    LineKind kind = LineKind::Other;
    std::vector<unsigned char> edges;  // per cell edge: bit 0 along a ridge cell, bit 1 along a thalweg cell
};

double seg_dist(const Point& p, const Point& a, const Point& b) {
    const Point d = b - a;
    const double l2 = tex::dot(d, d);
    const double t = l2 > 0 ? std::clamp(tex::dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
    return tex::distance(p, a + d * t);
}

void douglas_peucker(const std::vector<Point>& pts, std::size_t a, std::size_t b, double tol, std::vector<char>& keep) {
    if (b <= a + 1) return;
    double best = -1;
    std::size_t idx = a;
    for (std::size_t i = a + 1; i < b; ++i) {
        const double d = seg_dist(pts[i], pts[a], pts[b]);
        if (d > best) {
            best = d;
            idx = i;
        }
    }
    if (best <= tol) return;
    keep[idx] = 1;
    douglas_peucker(pts, a, idx, tol, keep);
    douglas_peucker(pts, idx, b, tol, keep);
}

std::vector<Point> simplify(const std::vector<Point>& pts, bool closed, double tol) {
    std::vector<char> keep(pts.size(), 0);
    keep.front() = keep.back() = 1;
    if (closed) {
        // Fix the start and the corner farthest from it, simplify both halves.
        std::size_t far = 0;
        for (std::size_t i = 0; i < pts.size(); ++i)
            if (tex::distance(pts[i], pts[0]) > tex::distance(pts[far], pts[0])) far = i;
        keep[far] = 1;
        douglas_peucker(pts, 0, far, tol, keep);
        douglas_peucker(pts, far, pts.size() - 1, tol, keep);
    } else {
        douglas_peucker(pts, 0, pts.size() - 1, tol, keep);
    }
    std::vector<Point> out;
    for (std::size_t i = 0; i < pts.size(); ++i)
        if (keep[i]) out.push_back(pts[i]);
    // A closed ring needs at least three distinct corners.
    if (closed && out.size() < 4) return pts;
    return out;
}

// The stair steps of a border chain cut at one point per cell edge (`cuts`: BorderPlaces, the
// edge's middle or a sub-cell position near it), so a one-cell staircase becomes its
// diagonal, between the chain's end nodes `from` and `to` (NodePlaces). Every chain through a
// node ends at the same point, so the chains of neighbouring faces still meet and the faces
// still tile the rock exactly: both faces of a border use the same chain. A closed chain
// without a node is the loop of its cut points.
std::vector<Point> cut_steps(const std::vector<Point>& cuts, bool closed, const Point& from, const Point& to) {
    std::vector<Point> out;
    out.reserve(cuts.size() + 2);
    if (!closed) out.push_back(from);
    out.insert(out.end(), cuts.begin(), cuts.end());
    if (closed) out.push_back(cuts.front());
    else out.push_back(to);
    return out;
}

// Where a border crosses each cell edge, below the cell size (issue 16: borders traced at
// sub-cell precision, not along the grid's axes):
//  - a ridge or thalweg border lies on its line, through the line cell beside the edge: a
//    ridge through the cell's centre; a thalweg on its floor, moved across from the centre to
//    the low point of a parabola through the smoothed heights of the cell and its two
//    neighbours across the edge (sub-pixel peak fitting). Not ridges: a border that wraps
//    around a crest cell would then turn more tightly than the crest ornaments' band can
//    follow (51 of Chamonix.tif's 599 ridges lost their ornament), and ridge precision on
//    the sample did not gain;
//  - the rock outline lies where the averaged slope crosses the rock threshold between the
//    centres of the rock cell and the cell outside, where it does cross it (elsewhere the
//    outline was drawn by the closing or the gap filling, and the edge's middle is kept);
//  - any other border crosses at the edge's middle.
struct BorderPlaces {
    const Grid& g;
    const std::vector<int>& face;
    const std::vector<int>& line_cells;  // 0 none, 1 ridge, 2 thalweg
    const std::vector<float>& slope;     // averaged slope, percent
    const std::vector<float>& z;         // the smoothed DEM
    double min_slope;

    // How far a thalweg's floor may move off its cell's centre, and how close the outline may
    // come to a cell's centre, in cells: the points stay near the edge they cut, so borders
    // of narrow faces seldom cross.
    static constexpr double kMaxFloorShiftCells = 0.45;
    static constexpr double kOutlineMarginCells = 0.15;

    Point cut(const Point& a, const Point& b, LineKind kind) const {
        const Point m = (a + b) / 2;
        // The two cells across the unit edge a-b: 0 above (left), 1 below (right).
        const bool horizontal = a.y == b.y;
        const int c0 = int(std::floor(horizontal ? m.x : m.x - 0.5));
        const int r0 = int(std::floor(horizontal ? m.y - 0.5 : m.y));
        const int c1 = horizontal ? c0 : c0 + 1, r1 = horizontal ? r0 + 1 : r0;
        if (kind != LineKind::Other) {
            // Only onto line cells of a face: the rock outline does not move out of the rock.
            auto on = [&](int c, int r) {
                return g.inside(c, r) && line_cells[g.at(c, r)] == int(kind) && face[g.at(c, r)] >= 0;
            };
            const bool on0 = on(c0, r0), on1 = on(c1, r1);
            if (on0 == on1) return m;
            const int c = on0 ? c0 : c1, r = on0 ? r0 : r1;
            const Point centre{c + 0.5, r + 0.5};
            if (kind == LineKind::Ridge) return centre;
            // Across the edge: rows for a horizontal edge, columns for a vertical one.
            const int sc = horizontal ? 0 : 1, sr = horizontal ? 1 : 0;
            if (!g.inside(c - sc, r - sr) || !g.inside(c + sc, r + sr)) return centre;
            const double zm = z[g.at(c - sc, r - sr)], z0 = z[g.at(c, r)], zp = z[g.at(c + sc, r + sr)];
            const double curve = zm - 2 * z0 + zp;  // > 0 across a floor
            if (!std::isfinite(curve) || curve <= 0) return centre;
            const double t = std::clamp(0.5 * (zm - zp) / curve, -kMaxFloorShiftCells, kMaxFloorShiftCells);
            return centre + Point{sc * t, sr * t};
        }
        const bool in0 = g.inside(c0, r0) && face[g.at(c0, r0)] >= 0, in1 = g.inside(c1, r1) && face[g.at(c1, r1)] >= 0;
        if (in0 == in1 || !g.inside(c0, r0) || !g.inside(c1, r1)) return m;
        const double s_in = slope[g.at(in0 ? c0 : c1, in0 ? r0 : r1)], s_out = slope[g.at(in0 ? c1 : c0, in0 ? r1 : r0)];
        if (!(s_in >= min_slope && s_out < min_slope)) return m;
        // Fraction of the way from the rock cell's centre to the outside cell's centre.
        const double t = std::clamp((s_in - min_slope) / (s_in - s_out), kOutlineMarginCells, 1 - kOutlineMarginCells);
        const Point from = in0 ? Point{c0 + 0.5, r0 + 0.5} : Point{c1 + 0.5, r1 + 0.5};
        const Point to = in0 ? Point{c1 + 0.5, r1 + 0.5} : Point{c0 + 0.5, r0 + 0.5};
        return from + (to - from) * t;
    }
};

// Where the chains meeting at a node end: the cell corner moved to the mean of the middles of
// the cell edges that meet there (by at most kMaxNodeShiftCells along each axis), so a short
// border between two nodes does not run along a cell edge. The middles, not the chains' cut
// points, so that the place does not depend on the borders' labels (labelling the outline or
// not leaves the inner borders as they are). Every chain through the node ends at this one
// point, whatever its level of generalisation.
class NodePlaces {
public:
    static constexpr double kMaxNodeShiftCells = 0.35;

    void add(long long id, const Point& corner, const Point& edge_middle) {
        Sum& s = sums_[id];
        s.corner = corner;
        s.middles = s.middles + edge_middle;
        ++s.n;
    }
    // The node stays at its corner from now on (a face whose cell edges alone are valid).
    void pin(long long id) { sums_[id].pinned = true; }
    Point place(long long id) const {
        const auto it = sums_.find(id);
        if (it == sums_.end()) return {};
        const Sum& s = it->second;
        const Point d = s.pinned ? Point{0, 0} : s.middles / double(s.n) - s.corner;
        return s.corner + Point{std::clamp(d.x, -kMaxNodeShiftCells, kMaxNodeShiftCells),
                                std::clamp(d.y, -kMaxNodeShiftCells, kMaxNodeShiftCells)};
    }

private:
    struct Sum {
        Point corner, middles{0, 0};
        int n = 0;
        bool pinned = false;
    };
    std::map<long long, Sum> sums_;
};

// The cut chain generalised: simplified within `tol` cells, then rounded by `rounds` passes
// of corner cutting at 1/4 and 3/4 of each segment (each pass stays inside the previous
// polyline's hull; the ends stay).
std::vector<Point> generalise(const std::vector<Point>& cut, bool closed, double tol, int rounds) {
    if (cut.size() < 3) return cut;
    return cut_corners(simplify(cut, closed, tol), rounds);
}

// Traces the borders between faces (and between faces and the outside) as chains of cell
// edges between nodes (corners where three or four edges meet).
std::vector<Chain> trace_chains(const Grid& g, const std::vector<int>& face, const std::vector<int>& kind) {
    auto label = [&](int c, int r) { return g.inside(c, r) ? face[g.at(c, r)] : -1; };
    const int W = g.w + 1, H = g.h + 1;
    // Edge from corner (i, j) in direction d exists when the two cells across it differ.
    auto cells = [&](int i, int j, int d, int& right, int& left, int& rc, int& rr, int& lc, int& lr) {
        switch (d) {
            case 0:
                rc = i, rr = j - 1, lc = i, lr = j;
                break;  // E
            case 1:
                rc = i, rr = j, lc = i - 1, lr = j;
                break;  // S
            case 2:
                rc = i - 1, rr = j, lc = i - 1, lr = j - 1;
                break;  // W
            default:
                rc = i - 1, rr = j - 1, lc = i, lr = j - 1;
                break;  // N
        }
        right = label(rc, rr);
        left = label(lc, lr);
    };
    auto edge_exists = [&](int i, int j, int d) {
        const int ni = i + kCx[d], nj = j + kCy[d];
        if (ni < 0 || nj < 0 || ni >= W || nj >= H) return false;
        int right, left, rc, rr, lc, lr;
        cells(i, j, d, right, left, rc, rr, lc, lr);
        return right != left;
    };
    // Visited edges: horizontal ones keyed by their west corner, vertical ones by their north.
    std::vector<char> hseen(std::size_t(W) * H, 0), vseen(std::size_t(W) * H, 0);
    auto seen = [&](int i, int j, int d) -> char& {
        switch (d) {
            case 0:
                return hseen[std::size_t(j) * W + i];
            case 2:
                return hseen[std::size_t(j) * W + i - 1];
            case 1:
                return vseen[std::size_t(j) * W + i];
            default:
                return vseen[std::size_t(j - 1) * W + i];
        }
    };
    auto degree = [&](int i, int j) {
        int n = 0;
        for (int d = 0; d < 4; ++d) n += edge_exists(i, j, d);
        return n;
    };
    std::vector<Chain> chains;
    auto trace = [&](int i0, int j0, int d0) {
        Chain ch;
        int right, left, rc, rr, lc, lr;
        cells(i0, j0, d0, right, left, rc, rr, lc, lr);
        ch.right = right;
        ch.left = left;
        ch.first_dir = d0;
        ch.start = (long long)j0 * W + i0;
        ch.raw.push_back({double(i0), double(j0)});
        int i = i0, j = j0, d = d0;
        while (true) {
            seen(i, j, d) = 1;
            cells(i, j, d, right, left, rc, rr, lc, lr);
            const int kr = g.inside(rc, rr) ? kind[g.at(rc, rr)] : 0, kl = g.inside(lc, lr) ? kind[g.at(lc, lr)] : 0;
            ch.edges.push_back((unsigned char)((kr == 1 || kl == 1) | ((kr == 2 || kl == 2) << 1)));
            ch.last_dir = d;
            i += kCx[d];
            j += kCy[d];
            ch.raw.push_back({double(i), double(j)});
            if (i == i0 && j == j0) {
                ch.closed = degree(i, j) == 2;
                break;
            }
            if (degree(i, j) != 2) break;
            int next = -1;
            for (int e = 0; e < 4; ++e)
                if (e != (d + 2) % 4 && edge_exists(i, j, e)) next = e;
            d = next;
        }
        ch.end = (long long)j * W + i;
        chains.push_back(std::move(ch));
    };
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
            if (degree(i, j) > 2)
                for (int d = 0; d < 4; ++d)
                    if (edge_exists(i, j, d) && !seen(i, j, d)) trace(i, j, d);
    // Closed loops without a node: start at their first corner in raster order.
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
            for (int d = 0; d < 4; ++d)
                if (edge_exists(i, j, d) && !seen(i, j, d)) trace(i, j, d);
    return chains;
}

// Labels the chains by the line cells they run along, piece by piece: each chain is cut where
// it passes from running along ridge cells to thalweg cells or to neither, pieces shorter than
// `min_run` cell edges taking the label of their longer neighbour (so a border is not chopped
// at every kink of a line). Borders of the rock outline are labelled too when `outline` is set:
// an arête is often the very edge of the steep area.
std::vector<Chain> label_chains(std::vector<Chain> chains, int corner_w, int min_run, bool outline) {
    auto dir_of = [](const Point& a, const Point& b) {
        return b.x > a.x ? 0 : b.y > a.y ? 1 : b.x < a.x ? 2 : 3;
    };
    auto corner = [&](const Point& q) { return (long long)std::lround(q.y) * corner_w + std::lround(q.x); };
    auto kind_of = [](int l) { return l == 1 ? LineKind::Ridge : l == 2 ? LineKind::Valley : LineKind::Other; };
    std::vector<Chain> out;
    for (Chain& ch : chains) {
        const std::size_t n = ch.edges.size();
        std::vector<int> lab(n, 0);
        if (outline || (ch.right >= 0 && ch.left >= 0))
            for (std::size_t e = 0; e < n; ++e) lab[e] = (ch.edges[e] & 1) ? 1 : (ch.edges[e] & 2) ? 2 : 0;
        // A loop without a node starts where its label changes, so its first and last pieces differ.
        if (ch.closed && lab[n - 1] == lab[0]) {
            std::size_t s = n;  // start of the last run
            while (s > 0 && lab[s - 1] == lab[n - 1]) --s;
            if (s > 0) {
                std::rotate(lab.begin(), lab.begin() + long(s), lab.end());
                std::rotate(ch.edges.begin(), ch.edges.begin() + long(s), ch.edges.end());
                ch.raw.pop_back();
                std::rotate(ch.raw.begin(), ch.raw.begin() + long(s), ch.raw.end());
                ch.raw.push_back(ch.raw.front());
                ch.start = ch.end = corner(ch.raw.front());
                ch.first_dir = dir_of(ch.raw[0], ch.raw[1]);
                ch.last_dir = dir_of(ch.raw[n - 1], ch.raw[n]);
            }
        }
        struct Run {
            int label;
            std::size_t begin, len;
        };
        std::vector<Run> runs;
        for (std::size_t e = 0; e < n; ++e)
            if (runs.empty() || runs.back().label != lab[e])
                runs.push_back({lab[e], e, 1});
            else
                ++runs.back().len;
        auto merge_equal = [&] {
            std::vector<Run> m;
            for (const Run& r : runs)
                if (!m.empty() && m.back().label == r.label)
                    m.back().len += r.len;
                else
                    m.push_back(r);
            runs = std::move(m);
        };
        while (runs.size() > 1) {
            std::size_t k = 0;
            for (std::size_t q = 1; q < runs.size(); ++q)
                if (runs[q].len < runs[k].len) k = q;
            if (int(runs[k].len) >= min_run) break;
            const Run* a = k > 0 ? &runs[k - 1] : nullptr;
            const Run* b = k + 1 < runs.size() ? &runs[k + 1] : nullptr;
            runs[k].label = (!b || (a && a->len >= b->len)) ? a->label : b->label;
            merge_equal();
        }
        if (runs.size() == 1) {
            ch.kind = kind_of(runs[0].label);
            out.push_back(std::move(ch));
            continue;
        }
        for (const Run& r : runs) {
            Chain piece;
            piece.raw.assign(ch.raw.begin() + long(r.begin), ch.raw.begin() + long(r.begin + r.len + 1));
            piece.edges.assign(ch.edges.begin() + long(r.begin), ch.edges.begin() + long(r.begin + r.len));
            piece.right = ch.right;
            piece.left = ch.left;
            piece.first_dir = dir_of(piece.raw[0], piece.raw[1]);
            piece.last_dir = dir_of(piece.raw[piece.raw.size() - 2], piece.raw.back());
            piece.start = corner(piece.raw.front());
            piece.end = corner(piece.raw.back());
            piece.kind = kind_of(r.label);
            out.push_back(std::move(piece));
        }
    }
    return out;
}

// The network cells inside the rock traced into polylines: from each head down the D8
// directions to a junction (included) or out of the rock; simplified.
std::vector<LabelledLine> trace_network(const Grid& g, const std::vector<int>& down, const std::vector<char>& ch,
                                        const std::vector<char>& rock, LineKind kind, const Raster& grid, double tol) {
    std::vector<char> has_up(g.size(), 0), done(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && rock[i] && down[i] >= 0) has_up[down[i]] = 1;
    std::vector<LabelledLine> out;
    auto run = [&](std::size_t start) {
        std::vector<Point> pts;
        for (std::size_t j = start;;) {
            pts.push_back({j % g.w + 0.5, j / g.w + 0.5});
            if (done[j]) break;
            done[j] = 1;
            const int d = down[j];
            if (d < 0 || !ch[d] || !rock[d]) break;
            j = std::size_t(d);
        }
        if (pts.size() < 2) return;
        LabelledLine l;
        l.kind = kind;
        for (const Point& q : simplify(pts, false, tol)) l.points.push_back(grid.to_world(q.x, q.y));
        out.push_back(std::move(l));
    };
    for (std::size_t i = 0; i < g.size(); ++i)
        if (ch[i] && rock[i] && !has_up[i]) run(i);
    for (std::size_t i = 0; i < g.size(); ++i)  // loops without a head (none expected)
        if (ch[i] && rock[i] && !done[i]) run(i);
    return out;
}

struct OrientedChain {
    int chain;
    bool reversed;
};

// The rings of one face, face on the right of each chain in grid coordinates (so outer rings
// come out counter-clockwise in the world, holes clockwise). At a corner where the face
// touches itself diagonally, the ring turns to keep the face's two cells joined, which makes
// shell and hole touch at that point (valid) rather than a ring cross itself.
std::vector<std::vector<Point>> face_rings(const std::vector<Chain>& chains, const std::vector<int>& mine, int f) {
    std::vector<OrientedChain> oc;
    for (int k : mine) {
        if (chains[k].right == f) oc.push_back({k, false});
        if (chains[k].left == f) oc.push_back({k, true});
    }
    auto pts = [&](const OrientedChain& o) {
        const Chain& c = chains[o.chain];
        std::vector<Point> p = c.shape();
        if (o.reversed) std::reverse(p.begin(), p.end());
        return p;
    };
    auto start = [&](const OrientedChain& o) { return o.reversed ? chains[o.chain].end : chains[o.chain].start; };
    auto end = [&](const OrientedChain& o) { return o.reversed ? chains[o.chain].start : chains[o.chain].end; };
    auto first_dir = [&](const OrientedChain& o) {
        return o.reversed ? (chains[o.chain].last_dir + 2) % 4 : chains[o.chain].first_dir;
    };
    auto last_dir = [&](const OrientedChain& o) {
        return o.reversed ? (chains[o.chain].first_dir + 2) % 4 : chains[o.chain].last_dir;
    };
    std::multimap<long long, int> from;
    for (std::size_t k = 0; k < oc.size(); ++k)
        if (!chains[oc[k].chain].closed) from.insert({start(oc[k]), int(k)});
    std::vector<char> used(oc.size(), 0);
    std::vector<std::vector<Point>> rings;
    for (std::size_t k = 0; k < oc.size(); ++k) {
        if (used[k]) continue;
        used[k] = 1;
        std::vector<Point> ring = pts(oc[k]);
        if (chains[oc[k].chain].closed) {
            rings.push_back(std::move(ring));
            continue;
        }
        const long long ring_start = start(oc[k]);
        std::size_t cur = k;
        while (end(oc[cur]) != ring_start) {
            int pick = -1;
            const int din = last_dir(oc[cur]);
            auto range = from.equal_range(end(oc[cur]));
            for (auto it = range.first; it != range.second; ++it) {
                if (used[it->second]) continue;
                const int dout = first_dir(oc[it->second]);
                // Join turn: the left turn in grid coordinates (cross product > 0).
                const int cross = kCx[din] * kCy[dout] - kCy[din] * kCx[dout];
                if (pick < 0 || cross > 0) pick = it->second;
            }
            if (pick < 0) throw Error(Code::Failure, "face " + std::to_string(f + 1) + ": its border does not close");
            used[pick] = 1;
            const std::vector<Point> more = pts(oc[pick]);
            ring.insert(ring.end(), more.begin() + 1, more.end());
            cur = std::size_t(pick);
        }
        rings.push_back(std::move(ring));
    }
    return rings;
}

struct FacePolygon {
    std::vector<Point> outer;
    std::vector<std::vector<Point>> holes;
};

std::unique_ptr<OGRPolygon> to_ogr(const FacePolygon& fp) {
    auto poly = std::make_unique<OGRPolygon>();
    auto add = [&](const std::vector<Point>& ring) {
        OGRLinearRing lr;
        for (const Point& p : ring) lr.addPoint(p.x, p.y);
        lr.closeRings();
        poly->addRing(&lr);
    };
    add(fp.outer);
    for (const auto& h : fp.holes) add(h);
    return poly;
}

// The polygons of face f in world coordinates: one shell per ring of positive area, each
// hole given to the shell containing it.
std::vector<FacePolygon> face_polygons(const std::vector<Chain>& chains, const std::vector<int>& mine, int f,
                                       const Raster& grid) {
    std::vector<std::vector<Point>> rings = face_rings(chains, mine, f);
    for (auto& ring : rings)
        for (Point& p : ring) p = grid.to_world(p.x, p.y);
    std::vector<FacePolygon> out;
    std::vector<std::vector<Point>> holes;
    for (auto& ring : rings) {
        if (tex::signed_area(ring) > 0)
            out.push_back({std::move(ring), {}});
        else
            holes.push_back(std::move(ring));
    }
    for (auto& h : holes) {
        // A hole touches its shell at most at corners: test the middle of its first edge.
        const Point probe = (h[0] + h[1]) / 2;
        std::size_t best = 0;
        for (std::size_t k = 0; k < out.size(); ++k)
            if (tex::point_in_ring(probe, out[k].outer)) best = k;
        if (!out.empty()) out[best].holes.push_back(std::move(h));
    }
    return out;
}

}  // namespace

double azimuth_degrees(double math_angle) {
    double az = 90.0 - math_angle * 180.0 / M_PI;
    az = std::fmod(az, 360.0);
    if (az < 0) az += 360.0;
    return az;
}

ExtractResult extract_partition(const ExtractOptions& o, const Progress& progress) {
    const std::string what = o.what + (o.dem.empty() ? std::string() : " '" + o.dem + "'");
    auto positive = [](double v, const char* name, bool zero_ok) {
        if (!std::isfinite(v) || v < 0 || (!zero_ok && v == 0))
            throw Error(Code::Usage, std::string(name) + ": " + std::to_string(v) + " is not a " +
                                         (zero_ok ? "non-negative" : "positive") + " number");
    };
    positive(o.min_slope, "--min-slope", true);
    positive(o.min_roughness, "--min-roughness", true);
    positive(o.min_area_mm2, "--min-area", true);
    positive(o.scale, "--scale", false);
    positive(o.thalweg_area, "--thalweg-area", false);
    positive(o.ridge_area, "--ridge-area", false);
    positive(o.max_fill, "--max-fill", true);
    positive(o.smooth, "--smooth", true);
    positive(o.converge, "--converge", true);
    positive(o.simplify, "--simplify", true);
    if (o.min_roughness > 1) throw Error(Code::Usage, "--min-roughness: must lie in 0..1");
    if (o.simplify > 2) throw Error(Code::Usage, "--simplify: at most 2 cells (faces would cross)");

    ExtractResult res;
    step(progress, 0.0, "reading the DEM");
    Raster dem = o.raster ? *o.raster : read_raster(o.dem, o.what);
    if (dem.crs_wkt.empty()) throw Error(Code::NoCrs, what + ": the raster has no CRS");
    if (!dem.north_up()) throw Error(Code::BadLayer, what + ": rotated rasters are not supported");
    if (std::isnan(dem.min_max().first)) throw Error(Code::BadLayer, what + ": every cell is NoData");
    std::string note;
    dem = to_working_crs(std::move(dem), &note);
    if (!note.empty()) res.notes.push_back(note);

    step(progress, 0.1, "terrain fields");
    res.terrain = compute_terrain(dem);
    const Grid g{dem.width, dem.height};
    const double dx = dem.cell_x(), dy = dem.cell_y(), cell_area = dx * dy;
    const double min_area = o.min_area_mm2 * (o.scale / 1000.0) * (o.scale / 1000.0);  // m2 on the ground
    // Rock specks are dropped and gaps filled unless their cells cover 1.5 times the minimum
    // area: generalising their outlines (step 4) takes area from small pieces, and one that
    // fell under `min_area` would be a speck on paper. (Faces under the minimum area merge
    // into a neighbour as before: a margin there would remove ridge and thalweg borders; a
    // face that generalising makes too small keeps borders closer to its cell edges.)
    const double keep_area = 1.5 * min_area;

    // ---- 1. Rock mask
    step(progress, 0.2, "rock mask");
    // Slope and roughness averaged over about 25 m (at least 3x3 cells): single cells are noisy.
    const int radius = std::max(1, int(std::lround(12.5 / dx)));
    const std::vector<float> slope = box_mean(g, res.terrain.slope.data, radius);
    const std::vector<float> rough = box_mean(g, res.terrain.roughness.data, radius);
    std::vector<char> inside_mask;
    if (!o.mask.empty()) inside_mask = rasterize_mask(o.mask, dem);
    std::vector<char> rock(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i)
        rock[i] = !std::isnan(dem.data[i]) && slope[i] >= o.min_slope && rough[i] >= o.min_roughness &&
                  (inside_mask.empty() || inside_mask[i]);
    {
        // Closing over about 15 m (dilation then erosion by a disc, at least the 4 neighbours):
        // crests and couloir floors are less steep than the flanks around them but belong to
        // the rock. A round window keeps the outline and the gaps free of square corners.
        const int rc = std::max(1, int(std::lround(15.0 / dx)));
        std::vector<std::pair<int, int>> disc;
        for (int dr = -rc; dr <= rc; ++dr)
            for (int dc = -rc; dc <= rc; ++dc)
                if (dr * dr + dc * dc <= rc * (rc + 1)) disc.push_back({dc, dr});
        auto grow = [&](const std::vector<char>& on, bool dilate) {
            // NoData counts as not rock when dilating and as rock when eroding; cells off the
            // grid do not count.
            std::vector<char> out(g.size());
            for (int r = 0; r < g.h; ++r)
                for (int c = 0; c < g.w; ++c) {
                    bool any = false, all = true;
                    for (auto [dc, dr] : disc) {
                        if (!g.inside(c + dc, r + dr)) continue;
                        const std::size_t j = g.at(c + dc, r + dr);
                        const bool v = std::isnan(dem.data[j]) ? !dilate : on[j] != 0;
                        any = any || v;
                        all = all && v;
                        if (dilate ? any : !all) break;
                    }
                    out[g.at(c, r)] = dilate ? any : all;
                }
            return out;
        };
        std::vector<char> closed = grow(grow(rock, true), false);
        for (std::size_t i = 0; i < g.size(); ++i)
            rock[i] = closed[i] && !std::isnan(dem.data[i]) && (inside_mask.empty() || inside_mask[i]);
        // Specks: 4-connected rock pieces smaller than the minimum area.
        int n = 0;
        const std::vector<int> lab = components(g, rock, false, n);
        std::vector<std::size_t> size(std::size_t(n), 0);
        for (int l : lab)
            if (l >= 0) ++size[l];
        for (std::size_t i = 0; i < g.size(); ++i)
            if (lab[i] >= 0 && double(size[lab[i]]) * cell_area < keep_area) rock[i] = 0;
        // Gaps: non-rock pieces enclosed by rock, without NoData, below the area. 4-connected,
        // as the face outlines see them: a gap touching a bigger one (or the outside) only at a
        // cell's corner is a hole of its own in the face's polygon.
        const NonRock gaps = non_rock_pieces(g, rock, dem.data, inside_mask, false);
        for (std::size_t i = 0; i < g.size(); ++i) {
            const int l = gaps.lab[i];
            if (l >= 0 && !gaps.open[l] && double(gaps.size[l]) * cell_area < keep_area) rock[i] = 1;
        }
    }
    std::size_t rock_cells = 0;
    for (char v : rock) rock_cells += v;
    if (rock_cells == 0) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      ": no rock: no area of at least %g mm2 at 1:%g has a slope >= %g %% and a roughness >= %g "
                      "(lower --min-slope / --min-roughness / --min-area)",
                      o.min_area_mm2, o.scale, o.min_slope, o.min_roughness);
        throw Error(Code::BadLayer, what + buf);
    }
    res.rock = dem;
    for (std::size_t i = 0; i < g.size(); ++i) res.rock.data[i] = std::isnan(dem.data[i]) ? NAN : float(rock[i]);

    // ---- 2. Thalwegs and ridges
    step(progress, 0.3, "thalwegs");
    // Flow runs on the DEM smoothed by three box filters (about a Gaussian of `smooth` metres,
    // at least one cell), so that small bumps and hollows do not start or divert lines.
    const int sr = std::max(1, int(std::lround(o.smooth / dx / std::sqrt(2.0))));
    std::vector<float> z = dem.data;
    for (int pass = 0; pass < 3 && o.smooth > 0; ++pass) z = box_mean(g, z, sr);
    // Thresholds: the options, but at least 50 (thalwegs) and 100 (ridges) cells, so that a
    // coarse DEM does not start a line in every hollow it can barely resolve.
    const double thalweg_area = std::max(o.thalweg_area, 50 * cell_area);
    const double ridge_area = std::max(o.ridge_area, 100 * cell_area);
    // Flow along the DEM's edges and NoData border is an artefact of the cut: no lines within
    // two cells of them.
    std::vector<char> edge(g.size(), 0);
    for (int r = 0; r < g.h; ++r)
        for (int c = 0; c < g.w; ++c)
            for (int dr = -2; dr <= 2; ++dr)
                for (int dc = -2; dc <= 2; ++dc)
                    if (!g.inside(c + dc, r + dr) || std::isnan(dem.data[g.at(c + dc, r + dr)])) edge[g.at(c, r)] = 1;
    const int near = std::max(1, int(std::lround(15.0 / dx)));
    const Flow valley_flow = flow(g, z, dx, dy, o.max_fill);
    std::vector<char> valley = channels(g, valley_flow, thalweg_area, o.converge, edge, near);
    step(progress, 0.45, "ridges");
    for (float& v : z) v = -v;
    const Flow ridge_flow = flow(g, z, dx, dy, o.max_fill);
    std::vector<char> ridge = channels(g, ridge_flow, ridge_area, o.converge, edge, near);
    // Spurs shorter than 100 m (at least 3 cells) go.
    const int spur = std::max(3, int(std::lround(100.0 / dx)));
    prune_spurs(g, valley_flow, valley, spur, near);
    prune_spurs(g, ridge_flow, ridge, spur, near);
    // Line heads prolonged along their floor (thalwegs up their couloir, ridges down their
    // crest, which is the same walk on the inverted DEM) to a line of the other kind or out of
    // the rock, over at most 1000 m, along cells at least 5 % of 20 m (two cells at least)
    // below (above) both sides, finishing by steepest ascent (descent) over at most 150 m.
    const int reach = std::max(3, int(std::lround(1000.0 / dx)));
    const int finish = std::max(4, int(std::lround(150.0 / dx)));
    const double across = std::max(2 * dx, 20.0);
    // The open non-rock (not the holes in the rock).
    std::vector<char> open(g.size(), 0);
    {
        const NonRock pieces = non_rock_pieces(g, rock, dem.data, inside_mask, true);
        for (std::size_t i = 0; i < g.size(); ++i) open[i] = pieces.lab[i] >= 0 && pieces.open[pieces.lab[i]];
    }
    // Steps of the steepest finishes: ridge ones label no border (a ridge finished straight
    // down a flank is not an arête); thalweg ones do (a couloir's head is steep and straight).
    std::vector<char> stop(g.size()), straight(g.size(), 0), steep_valley(g.size(), 0);
    std::vector<int> ridge_down = ridge_flow.down, valley_down = valley_flow.down;
    std::vector<float> conc = concavity(g, z, dx, dy, across);  // of the inverted DEM
    if (o.extend_ridges) {
        for (std::size_t i = 0; i < g.size(); ++i) stop[i] = valley[i];
        extend_heads(g, ridge_down, ridge, straight, z, conc, 0.05 * across, stop, rock, open, reach, finish);
    }
    for (float& v : z) v = -v;  // back to the (smoothed) DEM
    for (float& v : conc) v = -v;
    for (std::size_t i = 0; i < g.size(); ++i) stop[i] = ridge[i];
    extend_heads(g, valley_down, valley, steep_valley, z, conc, 0.05 * across, stop, rock, open, reach, finish);
    res.network = trace_network(g, ridge_down, ridge, rock, LineKind::Ridge, dem, 1.0);
    for (auto& l : trace_network(g, valley_down, valley, rock, LineKind::Valley, dem, 1.0))
        res.network.push_back(std::move(l));
    res.line_cells.assign(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i) res.line_cells[i] = ridge[i] ? 1 : (valley[i] ? 2 : 0);

    // ---- 3. Faces
    step(progress, 0.6, "faces");
    std::vector<char> free_cell(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) free_cell[i] = rock[i] && res.line_cells[i] == 0;
    int nfaces = 0;
    std::vector<int> face = components(g, free_cell, false, nfaces);
    // Line cells join a 4-neighbouring face, wave by wave (the smallest face index wins).
    while (true) {
        std::vector<std::pair<std::size_t, int>> wave;
        for (int r = 0; r < g.h; ++r)
            for (int c = 0; c < g.w; ++c) {
                const std::size_t i = g.at(c, r);
                if (!rock[i] || face[i] >= 0) continue;
                int best = -1;
                for (int k = 0; k < 8; k += 2) {
                    const int cc = c + kDc[k], rr = r + kDr[k];
                    if (!g.inside(cc, rr)) continue;
                    const int f = face[g.at(cc, rr)];
                    if (f >= 0 && (best < 0 || f < best)) best = f;
                }
                if (best >= 0) wave.push_back({i, best});
            }
        if (wave.empty()) break;
        for (auto [i, f] : wave) face[i] = f;
    }
    // Rock made only of line cells (narrow ribs): faces of their own.
    for (std::size_t i = 0; i < g.size(); ++i)
        if (rock[i] && face[i] < 0) {
            std::vector<char> rest(g.size());
            for (std::size_t j = 0; j < g.size(); ++j) rest[j] = rock[j] && face[j] < 0;
            int n = 0;
            const std::vector<int> lab = components(g, rest, false, n);
            for (std::size_t j = 0; j < g.size(); ++j)
                if (lab[j] >= 0) face[j] = nfaces + lab[j];
            nfaces += n;
            break;
        }
    // Small faces merge into the neighbour they share most border with, smallest first.
    for (int pass = 0; pass < 50; ++pass) {
        std::vector<std::size_t> area(std::size_t(nfaces), 0);
        std::map<std::pair<int, int>, int> shared;
        for (int r = 0; r < g.h; ++r)
            for (int c = 0; c < g.w; ++c) {
                const int f = face[g.at(c, r)];
                if (f < 0) continue;
                ++area[f];
                for (int k : {0, 2}) {  // east and south neighbours
                    const int cc = c + kDc[k], rr = r + kDr[k];
                    if (!g.inside(cc, rr)) continue;
                    const int e = face[g.at(cc, rr)];
                    if (e >= 0 && e != f) {
                        ++shared[{f, e}];
                        ++shared[{e, f}];
                    }
                }
            }
        std::vector<int> order;
        for (int f = 0; f < nfaces; ++f)
            if (area[f] > 0 && double(area[f]) * cell_area < min_area) order.push_back(f);
        std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] < area[b]; });
        std::vector<int> target(std::size_t(nfaces), -1);
        std::vector<char> touched(std::size_t(nfaces), 0);
        bool merged = false;
        for (int f : order) {
            if (touched[f]) continue;
            int best = -1, most = 0;
            for (auto it = shared.lower_bound({f, -1}); it != shared.end() && it->first.first == f; ++it)
                if (it->second > most && !touched[it->first.second]) {
                    most = it->second;
                    best = it->first.second;
                }
            if (best < 0) continue;
            target[f] = best;
            touched[f] = touched[best] = 1;
            merged = true;
        }
        if (!merged) break;
        for (int& f : face)
            if (f >= 0 && target[f] >= 0) f = target[f];
    }
    // Compact numbering in raster order of the faces' first cells.
    {
        std::vector<int> renum(std::size_t(nfaces), -1);
        int n = 0;
        for (int& f : face)
            if (f >= 0) {
                if (renum[f] < 0) renum[f] = n++;
                f = renum[f];
            }
        nfaces = n;
    }
    res.faces = dem;
    for (std::size_t i = 0; i < g.size(); ++i) res.faces.data[i] = float(face[i]);

    // ---- 4. Polygons: shared, simplified borders
    step(progress, 0.75, "polygons");
    // Border pieces are labelled when they run along line cells for at least 40 m (3 cells).
    const int min_run = std::max(3, int(std::lround(40.0 / dx)));
    // The steepest finishes of prolonged ridges split faces but follow no crest: the borders
    // along them are "other".
    std::vector<int> label_cells(res.line_cells);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (straight[i]) label_cells[i] = 0;
    std::vector<Chain> chains = label_chains(trace_chains(g, face, label_cells), g.w + 1, min_run, o.label_outline);
    const BorderPlaces places{g, face, label_cells, slope, z, o.min_slope};
    // Cut points per chain: sub-cell (levels 0 to 2) and at the edges' middles (level 3).
    std::vector<std::vector<Point>> fine(chains.size()), middles(chains.size());
    NodePlaces nodes;
    for (std::size_t k = 0; k < chains.size(); ++k) {
        const std::vector<Point>& raw = chains[k].raw;
        for (std::size_t i = 0; i + 1 < raw.size(); ++i) {
            fine[k].push_back(places.cut(raw[i], raw[i + 1], chains[k].kind));
            middles[k].push_back((raw[i] + raw[i + 1]) / 2);
        }
        if (!chains[k].closed) {
            nodes.add(chains[k].start, raw.front(), middles[k].front());
            nodes.add(chains[k].end, raw.back(), middles[k].back());
        }
    }
    auto shape_chain = [&](std::size_t k) {
        Chain& c = chains[k];
        const Point from = nodes.place(c.start), to = nodes.place(c.end);
        const std::vector<Point> cut = cut_steps(fine[k], c.closed, from, to);
        std::vector<Point> edges = c.raw;
        if (!c.closed) {
            edges.front() = from;
            edges.back() = to;
        }
        c.shapes = {generalise(cut, c.closed, o.simplify, o.smooth_rounds), generalise(cut, c.closed, kHalfCell, 1), cut,
                    cut_steps(middles[k], c.closed, from, to), std::move(edges)};
    };
    std::vector<std::vector<int>> of_face(static_cast<std::size_t>(nfaces));
    std::multimap<long long, int> at_node;  // the open chains ending at each node
    for (std::size_t k = 0; k < chains.size(); ++k) {
        shape_chain(k);
        const Chain& c = chains[k];
        if (c.right >= 0) of_face[c.right].push_back(int(k));
        if (c.left >= 0) of_face[c.left].push_back(int(k));
        if (!c.closed) {
            at_node.insert({c.start, int(k)});
            if (c.end != c.start) at_node.insert({c.end, int(k)});
        }
    }
    std::vector<std::vector<FacePolygon>> polys(static_cast<std::size_t>(nfaces));
    std::vector<char> redo(static_cast<std::size_t>(nfaces), 1);
    std::vector<char> degraded(static_cast<std::size_t>(nfaces), 0);
    const QuietGdal quiet;  // IsValid reports each crossing it finds as a warning
    // Each round a bad face's chains step back one level; at the last level its nodes go back
    // to their corners too, which gives the face its cell edges exactly (valid, and as large
    // as its cells). A few more rounds settle the faces across.
    constexpr int kRounds = Chain::kLevels + 4;
    for (int round = 0; round <= kRounds; ++round) {
        std::vector<char> bad(std::size_t(nfaces), 0);
        bool any = false;
        for (int f = 0; f < nfaces; ++f) {
            if (!redo[f]) continue;
            polys[f] = face_polygons(chains, of_face[f], f, dem);
            bool ok = polys[f].size() == 1;
            for (const auto& fp : polys[f]) {
                ok = ok && to_ogr(fp)->IsValid();
                // Rounding takes area from small faces and holes: one that falls under the
                // minimum area (which its cells reach) keeps its cell edges instead of
                // becoming a speck.
                ok = ok && std::abs(tex::signed_area(fp.outer)) >= min_area;
                for (const auto& h : fp.holes) ok = ok && std::abs(tex::signed_area(h)) >= min_area;
            }
            if (!ok && round < kRounds) {
                bad[f] = 1;
                any = true;
            }
        }
        if (!any) break;
        // Invalid once generalised (two borders of a narrow face crossing), or under the
        // minimum area: the face's chains step back one level (Chain: a lighter
        // generalisation, then the cut steps, then the cell edges themselves), and the faces
        // across them (which share those chains) are rebuilt.
        std::fill(redo.begin(), redo.end(), 0);
        auto redo_faces_of = [&](int k) {
            if (chains[k].right >= 0) redo[chains[k].right] = 1;
            if (chains[k].left >= 0) redo[chains[k].left] = 1;
        };
        for (int f = 0; f < nfaces; ++f) {
            if (!bad[f]) continue;
            degraded[f] = 1;
            const bool last = std::all_of(of_face[f].begin(), of_face[f].end(),
                                          [&](int k) { return chains[k].level == Chain::kLevels - 1; });
            for (int k : of_face[f]) {
                if (!last) {
                    chains[k].level = std::min(chains[k].level + 1, Chain::kLevels - 1);
                    redo_faces_of(k);
                    continue;
                }
                if (chains[k].closed) continue;
                for (const long long node : {chains[k].start, chains[k].end}) {
                    nodes.pin(node);
                    for (auto [it, stop] = at_node.equal_range(node); it != stop; ++it) {
                        shape_chain(std::size_t(it->second));
                        redo_faces_of(it->second);
                    }
                }
            }
        }
    }
    if (const auto n = std::count(degraded.begin(), degraded.end(), 1)) {
        std::array<int, Chain::kLevels> at_level{};
        for (const Chain& c : chains) ++at_level[std::size_t(c.level)];
        res.notes.push_back("kept the borders of " + std::to_string(n) +
                            " narrow or small faces closer to the cell edges (generalised, they would cross or "
                            "fall under the minimum area): " + std::to_string(at_level[1]) + " borders lightly generalised, " +
                            std::to_string(at_level[2] + at_level[3]) + " on the cut steps, " +
                            std::to_string(at_level[4]) + " on the cell edges");
    }

    // ---- 5. The partition, with orientation and density per face
    step(progress, 0.85, "orientation and density");
    Partition& p = res.partition;
    p.crs_wkt = dem.crs_wkt;
    for (int f = 0; f < nfaces; ++f)
        for (const auto& fp : polys[f]) {
            RockFace rf;
            rf.id = f + 1;
            rf.region = tex::Region(fp.outer, fp.holes, "extracted face");
            p.faces.push_back(std::move(rf));
        }
    for (const Chain& c : chains) {
        LabelledLine l;
        l.kind = c.kind;
        for (const Point& q : c.shape()) l.points.push_back(dem.to_world(q.x, q.y));
        p.lines.push_back(std::move(l));
    }
    derive_face_controls(p, res.terrain);
    label_boundaries(p, 0.1 * dx);  // lines are the borders themselves
    std::size_t nridge = 0, nvalley = 0;
    for (const Chain& c : chains) {
        nridge += c.kind == LineKind::Ridge;
        nvalley += c.kind == LineKind::Valley;
    }
    res.notes.push_back("rock: " + std::to_string(rock_cells) + " cells (" +
                        std::to_string(int(std::round(double(rock_cells) * cell_area / 1e4))) + " ha), " +
                        std::to_string(p.faces.size()) + " faces, " + std::to_string(nridge) + " ridge and " +
                        std::to_string(nvalley) + " valley borders");
    p.notes = res.notes;
    step(progress, 1.0, "done");
    return res;
}

void check_extract_files(const ExtractOptions& o, const std::string& out, const std::string& png, bool overwrite) {
    check_outputs({{o.what, o.dem}, {"--mask", o.mask}}, {{"-o", out}, {"--png", png}}, overwrite);
}

void write_partition_gpkg(const Partition& p, const std::string& path, bool overwrite,
                          const std::vector<LabelledLine>* network, bool fixed_controls) {
    check_output(path, overwrite);
    register_gdal();
    TempFile tmp(path, ".gpkg");
    {
        const ReproducibleGpkg reproducible;  // on this thread, for this call (gdal_scope.hpp)
        const QuietGdal quiet;
        GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
        if (!drv) throw Error(Code::Failure, "GDAL has no GeoPackage driver");
        std::unique_ptr<GDALDataset> ds(drv->Create(tmp.path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        if (!ds) throw Error(Code::OutputExists, "-o '" + path + "': cannot create (" + CPLGetLastErrorMsg() + ")");
        OGRSpatialReference srs;
        srs.importFromWkt(p.crs_wkt.c_str());
        srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        auto layer = [&](const char* name, OGRwkbGeometryType t,
                         std::vector<std::pair<const char*, OGRFieldType>> fields) {
            const char* lco[] = {"FID=fid", "GEOMETRY_NAME=geom", nullptr};
            OGRLayer* l = ds->CreateLayer(name, &srs, t, const_cast<char**>(lco));
            if (!l) throw Error(Code::OutputExists, "-o '" + path + "': cannot create layer " + name);
            for (auto [n, ft] : fields) {
                OGRFieldDefn fd(n, ft);
                l->CreateField(&fd);
            }
            return l;
        };
        auto put = [&](OGRLayer* l, OGRFeature& f) {
            if (l->CreateFeature(&f) != OGRERR_NONE) throw Error(Code::OutputExists, "-o '" + path + "': write failed");
        };
        // Derived controls under names rockhatch does not read unless told (see the header).
        const char* orientation_name = fixed_controls ? "orientation" : "fall_line";
        const char* density_name = fixed_controls ? "density" : "shade";
        OGRLayer* faces = layer("faces", wkbPolygon,
                                {{"id", OFTInteger64}, {orientation_name, OFTReal}, {density_name, OFTReal}, {"area", OFTReal}});
        OGRLayer* lines = layer("lines", wkbLineString, {{"kind", OFTString}});
        OGRLayer* mask = layer("mask", wkbMultiPolygon, {});
        OGRLayer* net = network ? layer("network", wkbLineString, {{"kind", OFTString}}) : nullptr;
        ds->StartTransaction();
        OGRMultiPolygon all;
        for (const RockFace& rf : p.faces) {
            OGRFeature f(faces->GetLayerDefn());
            f.SetField("id", GIntBig(rf.id));
            if (rf.orientation) f.SetField(orientation_name, std::round(azimuth_degrees(*rf.orientation) * 100) / 100);
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
    const int w = std::max(1, int(std::ceil(b.width() / upp))), h = std::max(1, int(std::ceil(b.height() / upp)));
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
        for (int y = std::max(0, int(cy - radius - 1)); y <= std::min(h - 1, int(cy + radius + 1)); ++y)
            for (int x = std::max(0, int(cx - radius - 1)); x <= std::min(w - 1, int(cx + radius + 1)); ++x) {
                const double cover = std::clamp(radius + 0.5 - std::hypot(x + 0.5 - cx, y + 0.5 - cy), 0.0, 1.0);
                float* px = &rgb[(std::size_t(y) * w + x) * 3];
                for (int k = 0; k < 3; ++k) px[k] = float(px[k] * (1 - cover) + ink[k] * cover);
            }
    };
    const float red[3] = {0.85f, 0.05f, 0.05f}, blue[3] = {0.05f, 0.25f, 0.95f}, grey[3] = {0.25f, 0.25f, 0.25f};
    const double radius = std::max(0.7, pixels / 1600.0);
    for (int pass = 0; pass < 2; ++pass)  // other borders below, ridges and valleys on top
        for (const LabelledLine& l : r.partition.lines) {
            if ((l.kind == LineKind::Other) != (pass == 0)) continue;
            const float* ink = l.kind == LineKind::Ridge ? red : l.kind == LineKind::Valley ? blue : grey;
            for (std::size_t i = 0; i + 1 < l.points.size(); ++i) {
                const double ax = (l.points[i].x - b.xmin) / upp, ay = (b.ymax - l.points[i].y) / upp;
                const double bx = (l.points[i + 1].x - b.xmin) / upp, by = (b.ymax - l.points[i + 1].y) / upp;
                const int n = std::max(1, int(std::ceil(std::hypot(bx - ax, by - ay) * 2)));
                for (int k = 0; k <= n; ++k)
                    stamp(ax + (bx - ax) * k / n, ay + (by - ay) * k / n, pass ? radius * 1.4 : radius * 0.8, ink);
            }
        }
    std::vector<unsigned char> bytes(rgb.size());
    for (std::size_t i = 0; i < rgb.size(); ++i)
        bytes[i] = (unsigned char)std::lround(std::clamp(rgb[i], 0.0f, 1.0f) * 255);
    write_png_pixels(bytes, w, h, 3, path, "--png");
}

}  // namespace carto
