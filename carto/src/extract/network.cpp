#include "network.hpp"

#include <algorithm>
#include <cmath>

#include "flow.hpp"
#include "mask.hpp"

namespace carto::extraction {
namespace {

// The network's distances, with their units (the comments where each is used say more).
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
constexpr double kTraceToleranceCells = 1.0;  // the traced lines simplified within one cell

}  // namespace

Network find_network(const Grid& g, const Raster& dem, const std::vector<char>& rock,
                     const std::vector<char>& inside_mask, const ExtractOptions& o) {
    const double dx = dem.cell_x(), dy = dem.cell_y(), cell_area = dx * dy;
    Network net;
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
    net.lines = trace_network(g, ridge_down, ridge, rock, LineKind::Ridge, dem, kTraceToleranceCells);
    for (auto& l : trace_network(g, valley_down, valley, rock, LineKind::Valley, dem, kTraceToleranceCells))
        net.lines.push_back(std::move(l));
    net.ridge = std::move(ridge);
    net.valley = std::move(valley);

    net.straight = std::move(straight);
    net.z = std::move(z);
    return net;
}

}  // namespace carto::extraction
