// Parquetry, Table, Bottle and Teapot: textures filling an outline (see gallery_domain.hpp).
#include "gallery_domain.hpp"
#include "gallery.hpp"

#include <array>
#include <cmath>
#include <vector>

namespace gallery::domain {
using namespace tex;

namespace {

Curves load(const std::string& dir, const std::string& name) { return gallery::element(dir + "/" + name); }

// One element of `elements` on the vertex, chosen at random (stream 3), turned by `angle`,
// its bounding-box centre on the vertex moved by up to dx and dy at random (streams 1, 2).
Curves place_jittered(const std::vector<Curves>& elements, const Vertex& v, double angle, double dx, double dy) {
    const double rx = Random(v, -dx, dx, 1);
    const double ry = Random(v, -dy, dy, 2);
    const Point loc = Location(v) + Point{rx, ry};
    const auto n = elements.size();
    const auto i = std::min(n - 1, std::size_t(std::floor(Random(v, 0.0, double(n), 3))));
    const Curves elem = Rotate(elements[i], angle);
    return MatchPoint(elem, BBoxCenter(elem), loc);
}

}  // namespace

// ---- Parquetry ----

Arrangement parquet_grid() {
    const double scale = 50, gap = 0.2 * scale;
    Stripes h = StripesProperties(0.0, scale, gap, scale, gap);
    SetFaceLabels(h, {"h1", "h2", "h3", "h4"});
    Stripes v = StripesProperties(pi / 6 + pi / 32 + pi / 100, 8 * scale, gap, 8 * scale, gap);
    SetFaceLabels(v, {"v1", "v2", "v3", "v4"});
    return GridPartition(h, v, KEEP_OUTSIDE);
}

bool parquet_joint(const Edge& e) {
    const std::vector<Face> faces = {LeftFace(e), RightFace(e)};
    if (record(faces[0]).unbounded || record(faces[1]).unbounded) return false;
    auto has = [&](const char* l) { return HasLabel(faces, l); };
    // (first, second, third): the two faces carry the three labels between them.
    static const std::array<std::array<const char*, 3>, 16> rules = {{
        {"v1", "v2", "h1"}, {"v2", "v3", "h1"}, {"v3", "v4", "h1"}, {"v4", "v1", "h1"},
        {"v1", "v2", "h3"}, {"v2", "v3", "h3"}, {"v3", "v4", "h3"}, {"v4", "v1", "h3"},
        {"h1", "h2", "v1"}, {"h2", "h3", "v1"}, {"h3", "h4", "v3"}, {"h4", "h1", "v3"},
        {"v2", "v3", "h2"}, {"v3", "v4", "h2"}, {"v4", "v1", "h4"}, {"v1", "v2", "h4"},
    }};
    for (const auto& r : rules)
        if (has(r[0]) && has(r[1]) && has(r[2])) return true;
    return false;
}

Arrangement parquet_slats() {
    return MapToEdges([](const Edge& e) { return parquet_joint(e) ? Nothing() : ToCurve(e); }, parquet_grid());
}

Arrangement parquetry(const std::string& dir) { return InDomain(parquet_slats(), load(dir, kParquetryFrame)); }

// ---- Table ----

Arrangement table_grain(const std::string& dir) {
    const std::vector<Curves> grains = {load(dir, "table_grain1.svg"), load(dir, "table_grain2.svg"),
                                        load(dir, "table_grain3.svg")};
    const double side = 0;
    Arrangement part = GridPartition(StripesProperties(side + pi / 3, 60), StripesProperties(side + 2 * pi / 3, 150),
                                     KEEP_OUTSIDE);
    return MapToVertices([grains, side](const Vertex& v) { return place_jittered(grains, v, side, 20, 80); }, part);
}

Arrangement table(const std::string& dir) { return InDomain(table_grain(dir), load(dir, kTableFrame)); }

// ---- Bottle ----

Arrangement bottle_bubbles(const std::string& dir) {
    const std::vector<Curves> bubbles = {load(dir, "fizz1.svg"), load(dir, "fizz2.svg"), load(dir, "fizz3.svg"),
                                         load(dir, "fizz4.svg")};
    const double side = pi / 2;
    Arrangement part = GridPartition(StripesProperties(side + pi / 3, 60), StripesProperties(side + 2 * pi / 3, 60),
                                     KEEP_OUTSIDE);
    return MapToVertices([bubbles, side](const Vertex& v) { return place_jittered(bubbles, v, side, 20, 40); }, part);
}

Arrangement bottle(const std::string& dir) { return InDomain(bottle_bubbles(dir), load(dir, kBottleFrame)); }

// ---- Teapot ----

Arrangement teapot_dots(const std::string& dir) {
    const Curves ring = load(dir, "pot_ring.svg");
    Arrangement part = UniformPartition(IrregularProperties(kTeapotDensity), KEEP_OUTSIDE);
    return MapToFaces(
        [ring](const Face& f) {
            return Scale(MatchPoint(ring, BBoxCenter(ring), Centroid(f)), Random(f, 0.05, 0.15, 0));
        },
        part);
}

Arrangement teapot(const std::string& dir) { return InDomain(teapot_dots(dir), load(dir, kTeapotFrame)); }

}  // namespace gallery::domain
