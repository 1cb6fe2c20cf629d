// Fig. 4.5 of the thesis redone with tiled maps: the operators run once on one period of
// the wall; every random decision is a ghost mapper's, taken copy by copy at conversion.
#include "gallery_tiled.hpp"

#include <cmath>

#include "gallery_teasers.hpp"

namespace gallery::tiled {
using namespace tex;

namespace {

// Smooth value noise in [0, 1): random values on a square lattice of side `cell`, keyed by
// the lattice node and the seed, blended with a smoothstep. A pure function of the point.
double value_noise(const Point& p, double cell) {
    const double gx = p.x / cell, gy = p.y / cell;
    const double fx = std::floor(gx), fy = std::floor(gy);
    auto node = [](double i, double j) {
        return unit_from_hash(hash_double(hash_double(mix64(GetSeed() ^ 0x4e4f495345ULL), i), j));
    };
    auto smooth = [](double t) { return t * t * (3 - 2 * t); };
    const double tx = smooth(gx - fx), ty = smooth(gy - fy);
    const double a = node(fx, fy) + (node(fx + 1, fy) - node(fx, fy)) * tx;
    const double b = node(fx, fy + 1) + (node(fx + 1, fy + 1) - node(fx, fy + 1)) * tx;
    return a + (b - a) * ty;
}

}  // namespace

TiledMap wall(const std::string& dir) {
    const Curves pebble = ImportSVG(dir + "/pebble.svg");
    auto brick = [pebble](const Face& f) {
        Curves c = teasers::shrink_brick(f);
        if (HasLabel(IncidentEdges(f), "v1")) c.append(Scale(MatchFace(pebble, f), 0.35));
        return c;
    };
    return MapToFaces(brick, MapToEdges(teasers::keep_brick_joints,
                                        GridPartition(teasers::brick_rows(), teasers::brick_columns(), Tiled(CROP))));
}

Arrangement regular_wall(const std::string& dir) { return wall(dir); }

Arrangement jittered_wall(const std::string& dir) {
    auto jitter = [](const TiledElement& e) {
        const Curves turned = Rotate(Scale(e.curves, Random(e, 0.75, 1.0, 0)), Random(e, -0.12, 0.12, 1));
        return Translate(turned, {Random(e, -18, 18, 2), Random(e, -12, 12, 3)});
    };
    return GhostMap(jitter, wall(dir));
}

Arrangement thinned_wall(const std::string& dir) {
    return GhostMap([](const TiledElement& e) { return Random(e, 0, 1, 0) < 0.35 ? Nothing() : e.curves; }, wall(dir));
}

Arrangement clustered_wall(const std::string& dir) {
    auto cluster = [](const TiledElement& e) {
        const double v = value_noise(e.anchor, 450);
        if (v < 0.5) return Nothing();
        return Scale(e.curves, std::min(1.0, 0.5 + (v - 0.5) * 2.5));
    };
    return GhostMap(cluster, wall(dir));
}

}  // namespace gallery::tiled
