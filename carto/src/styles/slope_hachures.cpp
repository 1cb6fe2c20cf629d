// Slope hachures in Lehmann's manner for the ground outside the rock: short strokes down
// the fall line, each running from one contour to the next so that the rows of strokes read
// as steps of the terrain, closer and heavier where the ground is steeper (or darker), white
// where it is flat. One greedy distribution of seed 004 per contour band (section 3.1), the
// darts being stream lines (section 3.3) along the fall-line field: a pin climbs to the
// upper contour of its band, a stream line follows the fall line down to the lower one and
// is thickened (tapered downhill); the check keeps it clear of the strokes of its band by
// the local spacing and of the rock hatches. The bands run in parallel (a band's program
// draws nothing at random); then, from the highest band down, a stroke nearer than the
// contour gap to the strokes kept above it is dropped.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "libtex/error.hpp"
#include "libtex/parallel.hpp"
#include "libtex/random.hpp"
#include "terrain.hpp"

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
    const RockProximity near = rock_proximity(in.partition, t.elevation);
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

    const double step = std::min(cell / kStepsPerCell, spacing_min / kStepsPerSpacing);
    const FlowField down = fall_line(elevation, step);
    const FlowField up = [down](const Point& q) { return -down(q); };
    const double max_length = kMaxIntervals * interval / std::max(slope_min / 100.0, 1e-3);

    // Candidate pins: a grid at the smallest spacing, jittered and shuffled by the seed,
    // sorted into their contour bands.
    tex::SeedScope seed(in.seed);
    tex::StreamScope streams(tex::hash_combine(0x48414348ULL, in.seed));
    const Region domain = frame(t.elevation);
    const int nx = std::max(1, int(domain.bbox().width() / spacing_min));
    const int ny = std::max(1, int(domain.bbox().height() / spacing_min));
    const RealGen jitter = RandomR(-0.5 * spacing_min, 0.5 * spacing_min);
    // Only the pins on hachured ground are shuffled (the order among them is the same as when
    // all were: each keeps its key).
    std::vector<std::pair<std::uint64_t, Point>> shuffled;
    std::uint64_t k = 0;
    for (const Point& q : RegularPinning(domain, nx, ny)) {
        const Point j = q + Point{jitter(), jitter()};
        const std::uint64_t key = tex::hash_combine(in.seed, k++);
        if (in_mask(*ground, j)) shuffled.push_back({key, j});
    }
    std::sort(shuffled.begin(), shuffled.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    std::map<long long, std::vector<Point>, std::greater<>> bands;  // highest band first
    for (const auto& [key, q] : shuffled) bands[band_of(q)].push_back(q);

    const RegionSet rock = hatch_obstacles(in.rock, in.scale, clearance, domain.bbox());
    // The bands are thrown in parallel, each on its own: its pins are fixed above and its
    // program draws nothing at random, so a band's strokes do not depend on the thread that
    // runs it. Then, band after band from the highest, a stroke that comes within the contour
    // gap of the strokes kept in the bands above is dropped (the white step along each
    // contour; few strokes, where bands meet).
    const std::vector<std::pair<long long, std::vector<Point>>> band_list(bands.begin(), bands.end());
    std::vector<std::vector<Region>> thrown(band_list.size());
    tex::parallel_for(band_list.size(), [&](std::size_t i) {
        const long long b = band_list[i].first;
        const std::vector<Point>& pins = band_list[i].second;
        const PointCheck in_band = [ground, band_of, b](const Point& q) {
            return in_mask(*ground, q) && band_of(q) == b;
        };
        RegionSet strokes;  // this band's strokes, filled by greedy_distribution
        // On the way down a stroke stops where it would come within the spacing of a kept
        // one (converging fall lines), rather than being traced to the contour and refused.
        const PointCheck open = [=](const Point& q) {
            return in_band(q) && !MinimalDistance(strokes, q, spacing_at(q) + 0.5 * width_max);
        };
        // Shaping: climb to the upper contour, then follow the fall line down to the lower one.
        const Shaping shaping = [=](const Point& pin) -> Region {
            // A stroke through a pin this close to a kept one would be refused by the check.
            if (MinimalDistance(strokes, pin, kPinReach * spacing_at(pin))) return Region();
            const Polyline climb = trace_stream(pin, up, in_band, max_length);
            const Point top = elevation->sample(climb.points.back()) > elevation->sample(pin)
                                  ? climb.points.back() : pin;
            if (top != pin && MinimalDistance(strokes, top, kPinReach * spacing_at(top))) return Region();
            Polyline line = trace_stream(top, down, open, max_length);
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
        const Check inside = all_vertices(in_band);
        const Check spaced = [strokes, spacing_at](const Region& r) {
            return !MinimalDistance(strokes, r, spacing_at(Centroid(r)));
        };
        const Check check = And(inside, And(spaced, Not(Overlap(rock))));
        greedy_distribution(strokes, CountUpTo((long long)pins.size()), Sequence(pins), shaping, check);
        thrown[i] = strokes.regions();
    });
    RegionSet drawn;  // the strokes kept in the bands done
    std::vector<Hatch> out;
    for (const std::vector<Region>& band : thrown) {
        // The strokes of one band are tested against the bands above only: in parallel.
        std::vector<char> clear(band.size());
        tex::parallel_for(band.size(), [&](std::size_t k) { clear[k] = !MinimalDistance(drawn, band[k], gap); });
        std::vector<Region> kept;
        for (std::size_t k = 0; k < band.size(); ++k)
            if (clear[k]) kept.push_back(band[k]);
        for (const Region& r : kept) out.push_back(ring_hatch(r, Family::Hachure));
        drawn.add(std::move(kept));
    }
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
                 {"contour_gap", 0.12, "mm", "white space between the strokes of neighbouring bands"},
                 {"min_length", 0.4, "mm", "shorter strokes are left out"},
                 {"clearance", 0.15, "mm", "white space kept from the rock faces and their hatches"},
             },
             true},
            draw_hachures};
}

}  // namespace carto::terrain
