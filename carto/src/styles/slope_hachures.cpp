// Slope hachures in Lehmann's manner for the ground outside the rock: short strokes down
// the fall line, each running from one contour to the next so that the rows of strokes read
// as steps of the terrain, closer and heavier where the ground is steeper (or darker), white
// where it is flat. Greedy distributions of seed 004 (section 3.1), one per contour band of
// each tile of the grid the terrain styles share (throw_in_phases), the darts being stream
// lines (section 3.3) along the fall-line field: a pin climbs to the upper contour of its
// band, a stream line follows the fall line down to the lower one, never farther than
// max_length from the pin, and is thickened (tapered downhill); the check keeps it clear of
// the strokes of its band by the local spacing, of every other stroke by the contour gap,
// and of the rock hatches. A tile throws its bands from the highest down.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "libtex/error.hpp"
#include "libtex/random.hpp"
#include "terrain_tools.hpp"

namespace carto::terrain {
using namespace tex::disc;
using tex::Region;
using tex::disc::Polyline;

namespace {

// Steps per cell of the DEM, and per smallest spacing, along a stream line: a step follows
// the bilinear DEM within a cell and draws the stroke within half the finest spacing
// (finer steps only add vertices that every distance check then has to visit).
constexpr double kStepsPerCell = 1.0, kStepsPerSpacing = 2.0;
// A stroke is at most this many contour intervals long on the gentlest hachured slope.
constexpr double kMaxIntervals = 1.5;
// Catmull-Rom pieces per step when the stroke is smoothed before thickening.
constexpr int kSmoothing = 2;
// A pin nearer than this fraction of the local spacing to a stroke of its band is not traced:
// the stroke through it would come nearer than the spacing (the fall line through a pin
// passes by the pin), so the check would refuse it after the costly tracing.
constexpr double kPinReach = 0.9;

double max_length(const ParamValues& p) { return kMaxIntervals * p.at("interval") / std::max(p.at("slope_min") / 100.0, 1e-3); }
double step_length(const ParamValues& p, double cell) {
    return std::min(cell / kStepsPerCell, p.at("spacing_min") / kStepsPerSpacing);
}

// The tile side: a stroke reaches at most max_length from its pin, plus its width and the
// smoothing's overshoot (E); strokes interact within the spacing and a width, or the contour
// gap (D); two tiles of one phase are a tile apart, more than 2 E + D.
double hachure_tile_side(const ParamValues& p, double cell) {
    const double reach = max_length(p) + p.at("width_max") + 2 * step_length(p, cell);
    const double interact = std::max(p.at("spacing_max") + p.at("width_max"), p.at("contour_gap"));
    return 2 * reach + interact + 2 * cell;
}

// Beyond a window: its tiles and those they depend on, a stroke past them, the rock cells
// within the clearance and a cell, the rock hatches within the clearance, the kernel cells.
double hachure_reach(const ParamValues& p, double cell) {
    return kPhasedReachTiles * hachure_tile_side(p, cell) + max_length(p) + p.at("width_max") + p.at("clearance") +
           p.at(kGroundPerMm) + 8 * cell;
}

std::vector<Hatch> draw_hachures(const TerrainInput& in, const ParamValues& p) {
    const Terrain& t = in.terrain;
    const double interval = p.at("interval"), slope_min = p.at("slope_min"), slope_max = p.at("slope_max");
    const double spacing_min = p.at("spacing_min"), spacing_max = p.at("spacing_max");
    const double width_min = p.at("width_min"), width_max = p.at("width_max"), taper = p.at("taper");
    const double illumination = p.at("illumination"), gap = p.at("contour_gap"), clearance = p.at("clearance");
    require_order("slope-hachures", "slope_min", slope_min, "slope_max", slope_max);
    require_order("slope-hachures", "spacing_min", spacing_min, "spacing_max", spacing_max);
    require_order("slope-hachures", "width_min", width_min, "width_max", width_max);
    require_order("slope-hachures", "taper", taper, "1", 1.0);
    require_order("slope-hachures", "illumination", illumination, "1", 1.0);

    // Where hachures may go: valid, not flat, and clear of the rock faces.
    const double cell = std::max(t.elevation.cell_x(), t.elevation.cell_y());
    const RockProximity near = rock_proximity(in.partition, t.elevation, clearance + 2 * cell);
    auto ground = std::make_shared<const Raster>(cell_mask(t.elevation, [&](int c, int r) {
        return near.distance.at(c, r) > clearance + cell && t.slope.at(c, r) >= slope_min;
    }));
    auto elevation = std::make_shared<const Raster>(t.elevation);
    auto band_of = [elevation, interval](const Point& q) {
        const double z = elevation->sample(q);
        return std::isnan(z) ? std::numeric_limits<long long>::min() : (long long)std::floor(z / interval);
    };
    // Steepness (or darkness) 0..1: closer, heavier strokes.
    const Weight weight = ground_weight(t, slope_min, slope_max, illumination);
    auto spacing_at = [=](const Point& q) { return spacing_max - (spacing_max - spacing_min) * weight(q); };

    const double step = step_length(p, cell);
    const FlowField down = fall_line(elevation, step);
    const FlowField up = [down](const Point& q) { return -down(q); };
    const double longest = max_length(p);

    // Candidate pins: the lattice of the working CRS at the smallest spacing, each node
    // jittered by a hash of its place and the seed (the same pin in any window), sorted into
    // the tiles by where it lands. A tile's pins are thrown band by band, from the highest,
    // in the order of their keys (a shuffle by the seed).
    struct Pin {
        long long band;
        std::uint64_t key;
        Point at;
    };
    const double tile = hachure_tile_side(p, cell);
    std::map<TileIndex, std::vector<Pin>> pins;
    const tex::BBox frame = t.elevation.bounds();
    const long long i0 = (long long)std::floor(frame.xmin / spacing_min) - 1, i1 = (long long)std::ceil(frame.xmax / spacing_min);
    const long long j0 = (long long)std::floor(frame.ymin / spacing_min) - 1, j1 = (long long)std::ceil(frame.ymax / spacing_min);
    const std::uint64_t salt = tex::hash_combine(0x48414348ULL, in.seed);
    for (long long j = j0; j <= j1; ++j)
        for (long long i = i0; i <= i1; ++i) {
            const std::uint64_t h = tex::hash_combine(tex::hash_combine(salt, std::uint64_t(i)), std::uint64_t(j));
            const double jx = tex::unit_from_hash(tex::hash_combine(h, 1)) - 0.5, jy = tex::unit_from_hash(tex::hash_combine(h, 2)) - 0.5;
            const Point q{(double(i) + 0.5 + jx) * spacing_min, (double(j) + 0.5 + jy) * spacing_min};
            if (in_mask(*ground, q)) pins[tile_of(q, tile)].push_back({band_of(q), h, q});
        }

    const RegionSet rock = hatch_obstacles(in.rock, in.scale, clearance, frame);
    const ThrowTile throw_tile = [&](const TileIndex& k, const Placed& before) -> std::vector<Element> {
        std::vector<Pin> mine = pins.at(k);
        std::sort(mine.begin(), mine.end(), [](const Pin& a, const Pin& b) {
            return std::tie(b.band, a.key) < std::tie(a.band, b.key);  // highest band first, then by key
        });
        RegionSet drawn;  // the tile's strokes of the bands done
        std::vector<Element> out;
        for (std::size_t first = 0; first < mine.size();) {
            const long long b = mine[first].band;
            std::size_t last = first;
            std::vector<Point> band_pins;
            while (last < mine.size() && mine[last].band == b) band_pins.push_back(mine[last++].at);
            first = last;
            const RegionSet& above = before.tagged(b);  // this band's strokes in the phases done
            const PointCheck in_band = [ground, band_of, b](const Point& q) {
                return in_mask(*ground, q) && band_of(q) == b;
            };
            RegionSet strokes;  // this band's strokes in the tile, filled by greedy_distribution
            auto crowded = [&strokes, &above](const Point& q, double d) {
                return MinimalDistance(strokes, q, d) || MinimalDistance(above, q, d);
            };
            // Shaping: climb to the upper contour, then follow the fall line down to the lower
            // one, within max_length of the pin.
            const Shaping shaping = [&](const Point& pin) -> Region {
                // A stroke through a pin this close to a kept one would be refused by the check.
                if (crowded(pin, kPinReach * spacing_at(pin))) return Region();
                const Polyline climb = trace_stream(pin, up, in_band, longest);
                const Point top = elevation->sample(climb.points.back()) > elevation->sample(pin)
                                      ? climb.points.back() : pin;
                if (top != pin && crowded(top, kPinReach * spacing_at(top))) return Region();
                // On the way down a stroke stops where it would come within the spacing of a
                // kept one (converging fall lines), rather than being traced and refused.
                const PointCheck open = [&](const Point& q) {
                    return in_band(q) && tex::distance(q, pin) <= longest && !crowded(q, spacing_at(q) + 0.5 * width_max);
                };
                Polyline line = trace_stream(top, down, open, longest);
                if (line.points.size() < 3) return Region();
                if (elevation->sample(line.points.front()) < elevation->sample(line.points.back()))
                    std::reverse(line.points.begin(), line.points.end());
                double length = 0;
                for (std::size_t i = 1; i < line.points.size(); ++i)
                    length += tex::distance(line.points[i - 1], line.points[i]);
                if (length < p.at("min_length")) return Region();
                const double w = width_min + (width_max - width_min) * weight(line.points.front());
                try {
                    return ApplyThickness(Interpolation(line.points, kSmoothing),
                                          [w, taper](double s) { return w * (1 - taper * s); });
                } catch (const tex::Error&) {
                    return Region();  // a line folded onto itself thickens to nothing: no dart
                }
            };
            // Check: in the band, the local spacing from the band's strokes, the contour gap
            // from every stroke, clear of the rock hatches.
            const Check inside = all_vertices(in_band);
            const Check spaced = [&](const Region& r) {
                const double d = spacing_at(Centroid(r));
                return !MinimalDistance(strokes, r, d) && !MinimalDistance(above, r, d) &&
                       !MinimalDistance(strokes, r, gap) && !MinimalDistance(drawn, r, gap) &&
                       !MinimalDistance(before.all, r, gap);
            };
            const Check check = And(inside, And(spaced, Not(Overlap(rock))));
            greedy_distribution(strokes, CountUpTo((long long)band_pins.size()), Sequence(band_pins), shaping, check);
            std::vector<Region> kept = strokes.regions();
            for (const Region& r : kept) out.push_back({r, b});
            drawn.add(std::move(kept));
        }
        return out;
    };
    std::vector<TileIndex> work;
    for (const auto& kv : pins) work.push_back(kv.first);
    std::vector<Hatch> out;
    for (const Element& e : throw_in_phases(std::move(work), tile, in.window, true, throw_tile))
        out.push_back(ring_hatch(e.region, Family::Hachure));
    return out;
}

}  // namespace

Builtin slope_hachures() {
    return {{"slope-hachures",
             "",
             "slope hachures (Lehmann): strokes down the fall line between contours, heavier on steeper ground",
             {
                 {"interval", 20.0, "m", "contour interval (ground metres): each stroke runs from one contour to the next"},
                 {"slope_min", 8.0, "%", "no hachure on flatter ground (white)"},
                 {"slope_max", 100.0, "%", "slope at which strokes are closest and heaviest"},
                 {"spacing_min", 0.45, "mm", "space between strokes of a band on the steepest ground"},
                 {"spacing_max", 1.0, "mm", "space between strokes of a band on the gentlest ground"},
                 {"width_min", 0.06, "mm", "stroke width at its top on the gentlest ground"},
                 {"width_max", 0.30, "mm", "stroke width at its top on the steepest ground"},
                 {"taper", 0.5, "ratio", "the stroke narrows downhill to (1 - taper) of its top width"},
                 {"illumination", 0.0, "ratio", "share of the shading (1 - hillshade) against the slope in the weight, 0..1"},
                 {"contour_gap", 0.12, "mm", "white space between a stroke and the strokes of other bands"},
                 {"min_length", 0.4, "mm", "shorter strokes are left out"},
                 {"clearance", 0.15, "mm", "white space kept from the rock faces and their hatches"},
             },
             true},
            draw_hachures,
            hachure_reach};
}

}  // namespace carto::terrain
