// Fig. 4.5 of the thesis redone with tiled maps: the operators run once on one period of
// the wall; every random decision is a ghost mapper's, taken copy by copy at conversion.
#include "gallery_tiled.hpp"
#include "gallery.hpp"

#include <algorithm>
#include <cmath>

#include "gallery_teasers.hpp"

namespace gallery::tiled {
using namespace tex;

namespace {

// A smooth field of the position with broad highs and lows (closed form, so that the Python
// twin computes the same doubles).
double cluster_field(const Point& p) {
    return 0.5 + 0.35 * std::sin(p.x / 210.0 + 0.7) * std::sin(p.y / 160.0 + 1.9) + 0.1 * std::sin((p.x + 2 * p.y) / 390.0);
}

}  // namespace

TiledMap wall(const std::string& dir) {
    const Curves pebble = gallery::element(dir + "/pebble.svg");
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
        const double v = cluster_field(e.anchor) + Random(e, -0.08, 0.08, 0);
        if (v < 0.45) return Nothing();
        return Scale(e.curves, std::min(1.0, 0.5 + (v - 0.45) * 2.5));
    };
    return GhostMap(cluster, wall(dir));
}

}  // namespace gallery::tiled
