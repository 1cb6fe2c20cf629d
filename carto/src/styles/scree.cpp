// Scree: stones thrown in the band below the rock where the slope is moderate, denser and
// larger where the ground is steeper and darker (swisstopo's scree drawing), as greedy
// distributions of seed 004 (section 3.1), one per tile of the grid the terrain styles
// share (throw_in_phases): a pinning that follows the scree density, a shaping that scales
// and turns a stone at the pin, and a check that refuses a stone closer than the local gap
// to the stones kept or touching a rock hatch.
#include <algorithm>
#include <cmath>
#include <map>

#include "libtex/random.hpp"
#include "terrain_tools.hpp"

namespace carto::terrain {
using namespace tex::disc;
using tex::Region;

namespace {

// Stones thrown per possible stone of the scree area (the packing saturates well before).
constexpr double kDartsPerStone = 3.0;
// Side of the tiles, in stones plus gaps (the most a stone and its gap reach): large enough
// that few stones lie near a tile's border, small enough to give every thread many tiles.
constexpr double kTileInStones = 16.0;
// and at least this many DEM cells (tiny stones: not a tile per stone).
constexpr double kTileInCells = 8.0;
// Sides of the stone polygon: angular enough to read as a stone, round at print size.
constexpr int kStoneSides = 6;

double scree_tile_side(const ParamValues& p, double cell) {
    return std::max(kTileInStones * (p.at("stone_max") + p.at("gap_max")), kTileInCells * cell);
}

// Beyond a window: its tiles and those they depend on, a stone past them, the rock within
// `reach` of their cells and the hatches within a stone and the clearance, with the cells of
// the terrain kernels.
double scree_reach(const ParamValues& p, double cell) {
    return kPhasedReachTiles * scree_tile_side(p, cell) + p.at("stone_max") + p.at("reach") + p.at("clearance") +
           p.at(kGroundPerMm) + 8 * cell;
}

std::vector<Hatch> draw_scree(const TerrainInput& in, const ParamValues& p) {
    const Terrain& t = in.terrain;
    const double reach = p.at("reach"), slope_min = p.at("slope_min"), slope_max = p.at("slope_max");
    const double size_min = p.at("stone_min"), size_max = p.at("stone_max");
    const double gap_min = p.at("gap_min"), gap_max = p.at("gap_max"), shade = p.at("shade_weight");
    require_order("scree", "slope_min", slope_min, "slope_max", slope_max);
    require_order("scree", "stone_min", size_min, "stone_max", size_max);
    require_order("scree", "gap_min", gap_min, "gap_max", gap_max);
    require_order("scree", "shade_weight", shade, "1", 1.0);
    // The scree area: below the nearest rock, within `reach` of it, slope in range, outside
    // the faces themselves.
    // With scree areas given (--scree-layer) they replace the band, the faces kept out.
    const RockProximity near = rock_proximity(in.partition, t.elevation, reach);
    const std::vector<Region>& given = in.partition.scree;
    auto area = std::make_shared<const Raster>(cell_mask(t.elevation, [&](int c, int r) {
        const double d = near.distance.at(c, r), s = t.slope.at(c, r);
        if (!given.empty()) {
            const Point q = t.elevation.grid_world(c + 0.5, r + 0.5);
            return d > 0 && std::any_of(given.begin(), given.end(), [&](const Region& g) { return g.contains(q); });
        }
        return d > 0 && d <= reach && t.elevation.at(c, r) < near.rock_elevation.at(c, r) && s >= slope_min &&
               s <= slope_max;
    }));
    // Steepness and darkness of the ground, 0..1: what makes the scree denser and coarser.
    const Weight weight = ground_weight(t, slope_min, slope_max, shade);
    auto size_at = [=](const Point& q) { return size_min + (size_max - size_min) * weight(q); };
    auto gap_at = [=](const Point& q) { return gap_max - (gap_max - gap_min) * weight(q); };

    // The tiles of the shared grid, thrown in colour phases (throw_in_phases). A tile and its
    // gap reach at most a stone plus the gap past its tile, far less than the tile between
    // two tiles of one phase. Each tile draws from a stream keyed by its place: the same
    // stones at any thread count, in any window.
    const double tile = scree_tile_side(p, std::max(t.elevation.cell_x(), t.elevation.cell_y()));
    // The pieces of each tile to pin in: the area's cells cut to the tile (squares or smaller
    // rectangles).
    std::map<TileIndex, std::vector<Region>> pieces;
    std::map<TileIndex, double> piece_area;
    tex::BBox box;
    for (int r = 0; r < area->height; ++r)
        for (int c = 0; c < area->width; ++c) {
            if (area->at(c, r) != 1) continue;
            const Point a = area->grid_world(c, r), z = area->grid_world(c + 1, r + 1);
            const double x0 = std::min(a.x, z.x), x1 = std::max(a.x, z.x), y0 = std::min(a.y, z.y), y1 = std::max(a.y, z.y);
            box.add(Point{x0, y0}), box.add(Point{x1, y1});
            const TileIndex lo = tile_of({x0, y0}, tile), hi = tile_of({x1, y1}, tile);
            for (long long ty = lo.second; ty <= hi.second; ++ty)
                for (long long tx = lo.first; tx <= hi.first; ++tx) {
                    const tex::BBox tb = tile_box({tx, ty}, tile);
                    const double cx0 = std::max(x0, tb.xmin), cx1 = std::min(x1, tb.xmax);
                    const double cy0 = std::max(y0, tb.ymin), cy1 = std::min(y1, tb.ymax);
                    if (!(cx1 > cx0 && cy1 > cy0)) continue;
                    pieces[{tx, ty}].push_back(Region::rectangle(cx0, cy0, cx1, cy1));
                    piece_area[{tx, ty}] += (cx1 - cx0) * (cy1 - cy0);
                }
        }
    if (pieces.empty()) return {};

    const RegionSet rock = hatch_obstacles(in.rock, in.scale, p.at("clearance"), box);
    const Region stone = BuiltinCircle(0.5, kStoneSides);
    const double per_stone = (size_min + gap_min) * (size_min + gap_min);
    const Check inside = all_vertices([area](const Point& q) { return in_mask(*area, q); });
    const Check clear_of_rock = Not(Overlap(rock));
    // One tile's greedy distribution: its darts in proportion to its share of the area.
    const ThrowTile throw_tile = [&](const TileIndex& k, const Placed& before) -> std::vector<Element> {
        const RegionSet& kept = before.all;  // the stones of the phases done
        tex::SeedScope seed(in.seed);
        tex::StreamScope streams(tex::hash_combine(
            tex::hash_combine(tex::hash_combine(0x5343524545ULL, in.seed), std::uint64_t(k.first)), std::uint64_t(k.second)));
        RegionSet stones;  // this tile's stones, filled by greedy_distribution
        // Pinning: uniform in the tile's cells of the area, kept with a probability growing
        // with the weight.
        const Pinning pin = RandomPinning(pieces.at(k), [=](const Point& q) {
            return in_mask(*area, q) ? 0.3 + 0.7 * weight(q) : 0.0;
        });
        // Shaping: a unit stone scaled to the local size, turned at random, put on the pin.
        // A pin nearer than the gap to a stone makes no stone: the stone holds its pin, so
        // the check would refuse it; testing the point first spares most darts of a nearly
        // full area the shaping and the region tests.
        const RealGen angle = RandomR(0, 2 * M_PI);
        const Shaping shaping = [=, &kept](const Point& q) {
            const double turn = angle(), gap = gap_at(q);
            if (MinimalDistance(stones, q, gap) || MinimalDistance(kept, q, gap)) return Region();
            return Translation(Rotation(Scale(stone, size_at(q)), turn), q);
        };
        // Check: wholly in the scree area, at least the local gap from the stones of the
        // tile and of the phases before, and clear of the rock hatches.
        const Check spaced = [stones, &kept, gap_at](const Region& r) {
            const double gap = gap_at(Centroid(r));
            return !MinimalDistance(stones, r, gap) && !MinimalDistance(kept, r, gap);
        };
        const long long darts = (long long)(kDartsPerStone * piece_area.at(k) / per_stone) + 1;
        greedy_distribution(stones, CountUpTo(darts), pin, shaping, And(inside, And(spaced, clear_of_rock)));
        std::vector<Element> out;
        for (const Region& r : stones.regions()) out.push_back({r, 0});
        return out;
    };
    std::vector<TileIndex> work;
    for (const auto& kv : pieces) work.push_back(kv.first);
    std::vector<Hatch> out;
    for (const Element& e : throw_in_phases(std::move(work), tile, in.window, false, throw_tile))
        out.push_back(ring_hatch(e.region, Family::Stone));
    return out;
}
}  // namespace

Builtin scree() {
    return {{"scree",
             "",
             "scree: stones below the rock, denser and larger on steeper, darker ground, clear of the hatches",
             {
                 {"reach", 8.0, "mm", "how far below the rock faces scree may lie"},
                 {"slope_min", 25.0, "%", "no scree on flatter ground"},
                 {"slope_max", 110.0, "%", "no scree on steeper ground (it is rock there); densest just below"},
                 {"stone_min", 0.12, "mm", "stone diameter on the gentlest, lightest scree"},
                 {"stone_max", 0.35, "mm", "stone diameter on the steepest, darkest scree"},
                 {"gap_min", 0.10, "mm", "space between stones on the steepest, darkest scree"},
                 {"gap_max", 0.60, "mm", "space between stones on the gentlest, lightest scree"},
                 {"shade_weight", 0.3, "ratio", "share of the shading (1 - hillshade) against the slope, 0..1"},
                 {"clearance", 0.10, "mm", "white space kept between a stone and a rock hatch"},
             },
             true},
            draw_scree,
            scree_reach};
}

}  // namespace carto::terrain
