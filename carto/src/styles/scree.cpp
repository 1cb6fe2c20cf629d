// Scree: stones thrown in the band below the rock where the slope is moderate, denser and
// larger where the ground is steeper and darker (swisstopo's scree drawing), as greedy
// distributions of seed 004 (section 3.1), one per tile of the area: a pinning that follows
// the scree density, a shaping that scales and turns a stone at the pin, and a check that
// refuses a stone closer than the local gap to the stones kept or touching a rock hatch.
// The tiles run in four phases, the tiles of a phase in parallel (see draw_scree).
#include <algorithm>
#include <cmath>

#include "libtex/parallel.hpp"
#include "libtex/random.hpp"
#include "terrain.hpp"

namespace carto::terrain {
using namespace tex::disc;
using tex::Region;

namespace {

// Stones thrown per possible stone of the scree area (the packing saturates well before).
constexpr double kDartsPerStone = 3.0;
// Side of the tiles thrown in parallel, in stones plus gaps (the most a stone and its gap
// reach): large enough that few stones lie near a tile's border, small enough to give
// every thread many tiles.
constexpr double kTileInStones = 16.0;
// At most this many tiles along a side of the area.
constexpr double kMaxTilesPerSide = 256.0;
// Sides of the stone polygon: angular enough to read as a stone, round at print size.
constexpr int kStoneSides = 6;

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
    const RockProximity near = rock_proximity(in.partition, t.elevation);
    const std::vector<Region>& given = in.partition.scree;
    auto area = std::make_shared<const Raster>(cell_mask(t.elevation, [&](int c, int r) {
        const double d = near.distance.at(c, r), s = t.slope.at(c, r);
        if (!given.empty()) {
            const Point q = t.elevation.to_world(c + 0.5, r + 0.5);
            return d > 0 && std::any_of(given.begin(), given.end(), [&](const Region& g) { return g.contains(q); });
        }
        return d > 0 && d <= reach && t.elevation.at(c, r) < near.rock_elevation.at(c, r) && s >= slope_min &&
               s <= slope_max;
    }));
    // Steepness and darkness of the ground, 0..1: what makes the scree denser and coarser.
    const Weight weight = ground_weight(t, slope_min, slope_max, shade);
    auto size_at = [=](const Point& q) { return size_min + (size_max - size_min) * weight(q); };
    auto gap_at = [=](const Point& q) { return gap_max - (gap_max - gap_min) * weight(q); };

    // Tiles, thrown in four phases (the 2 x 2 colours of the tiles), the tiles of a phase in
    // parallel: two tiles of one colour are a tile apart, farther than a stone plus the gap
    // reaches, so their stones cannot meet and each tile only has to see its own stones and
    // those of the phases before. Each tile draws from a stream keyed by its place, and the
    // stones are joined in the order of the tiles: the same bytes at any thread count.
    tex::BBox box;
    for (int r = 0; r < area->height; ++r)
        for (int c = 0; c < area->width; ++c)
            if (area->at(c, r) == 1) box.add(area->to_world(c, r)), box.add(area->to_world(c + 1, r + 1));
    if (box.empty()) return {};
    // Larger tiles are always safe (only a smaller one could let two tiles of a phase meet):
    // tiny stones get larger tiles than kTileInStones of them, not millions of tiles.
    const double tile = std::max(kTileInStones * (size_max + gap_max), std::max(box.width(), box.height()) / kMaxTilesPerSide);
    const int nx = std::max(1, int(std::ceil(box.width() / tile))), ny = std::max(1, int(std::ceil(box.height() / tile)));
    // The pieces of each tile to pin in: the area's cells cut to the tile (squares or smaller
    // rectangles).
    std::vector<std::vector<Region>> pieces(std::size_t(nx) * ny);
    std::vector<double> piece_area(pieces.size(), 0.0);
    for (int r = 0; r < area->height; ++r)
        for (int c = 0; c < area->width; ++c) {
            if (area->at(c, r) != 1) continue;
            const Point a = area->to_world(c, r), z = area->to_world(c + 1, r + 1);
            const double x0 = std::min(a.x, z.x), x1 = std::max(a.x, z.x), y0 = std::min(a.y, z.y), y1 = std::max(a.y, z.y);
            const int tx0 = std::clamp(int((x0 - box.xmin) / tile), 0, nx - 1), tx1 = std::clamp(int((x1 - box.xmin) / tile), 0, nx - 1);
            const int ty0 = std::clamp(int((y0 - box.ymin) / tile), 0, ny - 1), ty1 = std::clamp(int((y1 - box.ymin) / tile), 0, ny - 1);
            for (int ty = ty0; ty <= ty1; ++ty)
                for (int tx = tx0; tx <= tx1; ++tx) {
                    const double cx0 = std::max(x0, box.xmin + tx * tile), cx1 = std::min(x1, box.xmin + (tx + 1) * tile);
                    const double cy0 = std::max(y0, box.ymin + ty * tile), cy1 = std::min(y1, box.ymin + (ty + 1) * tile);
                    if (!(cx1 > cx0 && cy1 > cy0)) continue;
                    const std::size_t k = std::size_t(ty) * nx + tx;
                    pieces[k].push_back(Region::rectangle(cx0, cy0, cx1, cy1));
                    piece_area[k] += (cx1 - cx0) * (cy1 - cy0);
                }
        }

    const RegionSet rock = hatch_obstacles(in.rock, in.scale, p.at("clearance"), box);
    const Region stone = BuiltinCircle(0.5, kStoneSides);
    const double per_stone = (size_min + gap_min) * (size_min + gap_min);
    const Check inside = all_vertices([area](const Point& q) { return in_mask(*area, q); });
    const Check clear_of_rock = Not(Overlap(rock));
    RegionSet kept;  // the stones of the phases done
    // One tile's greedy distribution: its darts in proportion to its share of the area.
    auto throw_tile = [&](std::size_t k) -> std::vector<Region> {
        if (pieces[k].empty()) return {};
        tex::SeedScope seed(in.seed);
        tex::StreamScope streams(tex::hash_combine(tex::hash_combine(0x5343524545ULL, in.seed), k));
        RegionSet stones;  // this tile's stones, filled by greedy_distribution
        // Pinning: uniform in the tile's cells of the area, kept with a probability growing
        // with the weight.
        const Pinning pin = RandomPinning(pieces[k], [=](const Point& q) {
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
        const long long darts = (long long)(kDartsPerStone * piece_area[k] / per_stone) + 1;
        greedy_distribution(stones, CountUpTo(darts), pin, shaping, And(inside, And(spaced, clear_of_rock)));
        return stones.regions();
    };
    for (int phase = 0; phase < 4; ++phase) {
        std::vector<std::size_t> tiles;
        for (int ty = phase / 2; ty < ny; ty += 2)
            for (int tx = phase % 2; tx < nx; tx += 2) tiles.push_back(std::size_t(ty) * nx + tx);
        std::vector<std::vector<Region>> thrown(tiles.size());
        tex::parallel_for(tiles.size(), [&](std::size_t i) { thrown[i] = throw_tile(tiles[i]); });
        std::vector<Region> joined;
        for (auto& v : thrown)
            for (auto& r : v) joined.push_back(std::move(r));
        kept.add(std::move(joined));
    }
    std::vector<Hatch> out;
    for (const Region& r : kept.regions()) out.push_back(ring_hatch(r, Family::Stone));
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
            draw_scree};
}

}  // namespace carto::terrain
