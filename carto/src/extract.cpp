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
#include "extract/borders.hpp"
#include "extract/faces.hpp"
#include "extract/flow.hpp"
#include "extract/grid.hpp"
#include "extract/mask.hpp"
#include "extract/polygons.hpp"
#include "gdal_scope.hpp"

namespace carto {

using namespace extraction;

namespace {

// The extraction's distances, with their units and reasons (the comments where each is used
// say more).
constexpr double kMmPerM = 1000.0;            // paper millimetres per metre at 1:1
constexpr double kKeepAreaFactor = 1.5;       // specks and gaps kept above 1.5 x the minimum area
constexpr double kRockWindowRadiusM = 12.5;   // slope and roughness averaged over about 25 m
constexpr double kClosingRadiusM = 15.0;      // the rock mask closed by a disc of about 15 m
constexpr double kMinThalwegCells = 50;       // a thalweg drains at least 50 cells (coarse DEMs)
constexpr double kMinRidgeCells = 100;        // a ridge "drains" at least 100 cells
constexpr int kEdgeMarginCells = 2;           // no lines within 2 cells of the DEM's edge or NoData
constexpr double kBesideLineM = 15.0;         // a line this close to another runs beside it
constexpr double kMinSpurM = 100.0;           // spurs shorter than 100 m go ...
constexpr int kMinSpurCells = 3;              // ... and shorter than 3 cells on any DEM
constexpr double kMaxExtensionM = 1000.0;     // heads prolonged along their floor over at most 1 km
constexpr int kMinReachCells = 3;             //   (at least 3 cells)
constexpr double kMaxFinishM = 150.0;         // the steepest finish of a walk: at most 150 m
constexpr int kMinFinishCells = 4;            //   (at least 4 cells)
constexpr double kConcavityDistanceM = 20.0;  // cross-profile concavity read 20 m (2 cells at least) away
constexpr double kFloorDepthRatio = 0.05;     // a floor is 5 % of that distance below both sides
constexpr double kMinLabelRunM = 40.0;        // a border is labelled where it runs 40 m along a line
constexpr int kMinRunCells = 3;               //   (3 cells at least)
constexpr double kLabelSnapCells = 0.1;       // lines are the borders: matched within a tenth of a cell

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
    const double ground_m_per_mm = o.scale / kMmPerM;  // metres on the ground per millimetre on paper
    const double min_area = o.min_area_mm2 * ground_m_per_mm * ground_m_per_mm;  // m2 on the ground
    // Rock specks are dropped and gaps filled unless their cells cover 1.5 times the minimum
    // area: generalising their outlines (step 4) takes area from small pieces, and one that
    // fell under `min_area` would be a speck on paper. (Faces under the minimum area merge
    // into a neighbour as before: a margin there would remove ridge and thalweg borders; a
    // face that generalising makes too small keeps borders closer to its cell edges.)
    const double keep_area = kKeepAreaFactor * min_area;

    // ---- 1. Rock mask
    step(progress, 0.2, "rock mask");
    // Slope and roughness averaged over about 25 m (at least 3x3 cells): single cells are noisy.
    const int radius = std::max(1, int(std::lround(kRockWindowRadiusM / dx)));
    const std::vector<float> slope = box_mean(g, res.terrain.slope.data, radius);
    const std::vector<float> rough = box_mean(g, res.terrain.roughness.data, radius);
    std::vector<char> inside_mask;
    if (!o.mask.empty()) inside_mask = rasterize_mask(o.mask, dem);
    std::vector<char> rock(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i)
        rock[i] = !std::isnan(dem.data[i]) && slope[i] >= o.min_slope && rough[i] >= o.min_roughness &&
                  (inside_mask.empty() || inside_mask[i]);
    // Closing over about 15 m (at least the 4 neighbours), specks dropped and gaps filled:
    // close_rock (extract/mask.hpp).
    close_rock(g, rock, dem.data, inside_mask, std::max(1, int(std::lround(kClosingRadiusM / dx))), cell_area, keep_area);
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
    const double thalweg_area = std::max(o.thalweg_area, kMinThalwegCells * cell_area);
    const double ridge_area = std::max(o.ridge_area, kMinRidgeCells * cell_area);
    // Flow along the DEM's edges and NoData border is an artefact of the cut: no lines within
    // two cells of them.
    std::vector<char> edge(g.size(), 0);
    for (int r = 0; r < g.h; ++r)
        for (int c = 0; c < g.w; ++c)
            for (int dr = -kEdgeMarginCells; dr <= kEdgeMarginCells; ++dr)
                for (int dc = -kEdgeMarginCells; dc <= kEdgeMarginCells; ++dc)
                    if (!g.inside(c + dc, r + dr) || std::isnan(dem.data[g.at(c + dc, r + dr)])) edge[g.at(c, r)] = 1;
    const int near = std::max(1, int(std::lround(kBesideLineM / dx)));
    const Flow valley_flow = flow(g, z, dx, dy, o.max_fill);
    std::vector<char> valley = channels(g, valley_flow, thalweg_area, o.converge, edge, near);
    step(progress, 0.45, "ridges");
    for (float& v : z) v = -v;
    const Flow ridge_flow = flow(g, z, dx, dy, o.max_fill);
    std::vector<char> ridge = channels(g, ridge_flow, ridge_area, o.converge, edge, near);
    // Spurs shorter than 100 m (at least 3 cells) go.
    const int spur = std::max(kMinSpurCells, int(std::lround(kMinSpurM / dx)));
    prune_spurs(g, valley_flow, valley, spur, near);
    prune_spurs(g, ridge_flow, ridge, spur, near);
    // Line heads prolonged along their floor (thalwegs up their couloir, ridges down their
    // crest, which is the same walk on the inverted DEM) to a line of the other kind or out of
    // the rock, over at most 1000 m, along cells at least 5 % of 20 m (two cells at least)
    // below (above) both sides, finishing by steepest ascent (descent) over at most 150 m.
    const int reach = std::max(kMinReachCells, int(std::lround(kMaxExtensionM / dx)));
    const int finish = std::max(kMinFinishCells, int(std::lround(kMaxFinishM / dx)));
    const double across = std::max(2 * dx, kConcavityDistanceM);
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
        extend_heads(g, ridge_down, ridge, straight, z, conc, kFloorDepthRatio * across, stop, rock, open, reach, finish);
    }
    for (float& v : z) v = -v;  // back to the (smoothed) DEM
    for (float& v : conc) v = -v;
    for (std::size_t i = 0; i < g.size(); ++i) stop[i] = ridge[i];
    extend_heads(g, valley_down, valley, steep_valley, z, conc, kFloorDepthRatio * across, stop, rock, open, reach,
                 finish);
    res.network = trace_network(g, ridge_down, ridge, rock, LineKind::Ridge, dem, 1.0);
    for (auto& l : trace_network(g, valley_down, valley, rock, LineKind::Valley, dem, 1.0))
        res.network.push_back(std::move(l));
    res.line_cells.assign(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i) res.line_cells[i] = ridge[i] ? 1 : (valley[i] ? 2 : 0);

    // ---- 3. Faces
    step(progress, 0.6, "faces");
    int nfaces = 0;
    std::vector<int> face = face_grid(g, rock, res.line_cells, cell_area, min_area, nfaces);
    res.faces = dem;
    for (std::size_t i = 0; i < g.size(); ++i) res.faces.data[i] = float(face[i]);

    // ---- 4. Polygons: shared, simplified borders
    step(progress, 0.75, "polygons");
    // Border pieces are labelled when they run along line cells for at least 40 m (3 cells).
    const int min_run = std::max(kMinRunCells, int(std::lround(kMinLabelRunM / dx)));
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
    label_boundaries(p, kLabelSnapCells * dx);  // lines are the borders themselves
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

}  // namespace carto
