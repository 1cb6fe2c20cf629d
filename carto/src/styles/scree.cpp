// Scree: stones thrown in the band below the rock where the slope is moderate, denser and
// larger where the ground is steeper and darker (swisstopo's scree drawing), as one greedy
// distribution of seed 004 (section 3.1): a pinning that follows the scree density, a
// shaping that scales and turns a stone at the pin, and a check that refuses a stone
// closer than the local gap to the stones kept or touching a rock hatch.
#include <algorithm>
#include <cmath>

#include "libtex/random.hpp"
#include "terrain.hpp"

namespace carto::terrain {
using namespace tex::disc;
using tex::Region;

namespace {

// Stones thrown per possible stone of the scree area (the packing saturates well before).
constexpr double kDartsPerStone = 3.0;
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
    double cells = 0;
    tex::BBox box;
    for (int r = 0; r < area->height; ++r)
        for (int c = 0; c < area->width; ++c)
            if (area->at(c, r) == 1) {
                ++cells;
                box.add(area->to_world(c, r)), box.add(area->to_world(c + 1, r + 1));
            }
    if (cells == 0) return {};
    // Steepness and darkness of the ground, 0..1: what makes the scree denser and coarser.
    const Weight weight = ground_weight(t, slope_min, slope_max, shade);
    auto size_at = [=](const Point& q) { return size_min + (size_max - size_min) * weight(q); };
    auto gap_at = [=](const Point& q) { return gap_max - (gap_max - gap_min) * weight(q); };

    tex::SeedScope seed(in.seed);
    tex::StreamScope streams(tex::hash_combine(0x5343524545ULL, in.seed));
    // Pinning: uniform in the frame, kept with a probability growing with the weight.
    const Pinning pin = RandomPinning(frame(t.elevation), [=](const Point& q) {
        return in_mask(*area, q) ? 0.3 + 0.7 * weight(q) : 0.0;
    });
    // Shaping: a unit stone scaled to the local size, turned at random, put on the pin.
    const Region stone = BuiltinCircle(0.5, kStoneSides);
    const RealGen angle = RandomR(0, 2 * M_PI);
    const Shaping shaping = [=](const Point& q) {
        return Translation(Rotation(Scale(stone, size_at(q)), angle()), q);
    };
    // Check: wholly in the scree area, clear of the rock hatches, and at least the local gap
    // from the stones kept so far (the set greedy_distribution fills).
    RegionSet stones;
    const RegionSet rock = hatch_obstacles(in.rock, in.scale, p.at("clearance"), box);
    const Check inside = all_vertices([area](const Point& q) { return in_mask(*area, q); });
    const Check spaced = [stones, gap_at](const Region& r) { return !MinimalDistance(stones, r, gap_at(Centroid(r))); };
    const Check check = And(inside, And(Not(Overlap(rock)), spaced));
    const double cell_area = t.elevation.cell_x() * t.elevation.cell_y();
    const double per_stone = (size_min + gap_min) * (size_min + gap_min);
    greedy_distribution(stones, CountUpTo((long long)(kDartsPerStone * cells * cell_area / per_stone) + 1), pin,
                        shaping, check);
    std::vector<Hatch> out;
    for (const Region& r : stones.regions()) out.push_back(ring_hatch(r, Family::Stone));
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
