// The seven design iterations of the seed's Fig. 5.4, written as compositions of a few
// controlled building blocks (hatching.hpp). Parameters are in millimetres on paper and
// their defaults follow the seed's Appendix E scripts at 1:10000 (hatch spacing 3.5-15 m,
// hatch length 20-30 m, ridge shapes about 20 m).
#include "carto/styles.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "carto/error.hpp"

namespace carto {
namespace {

double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }

std::vector<StyleParam> fill_params(double length_mm, double jitter) {
    return {
        {"spacing_min", 0.35, "mm", "hatch spacing in the darkest faces"},
        {"spacing_max", 1.5, "mm", "hatch spacing in the lightest faces"},
        {"length", length_mm, "mm", "length of a hatch between two jittered break points"},
        {"jitter", jitter, "ratio", "jitter of the break points, as a fraction of spacing and length"},
        {"contrast", 1.0, "ratio", "how much height pushes dark faces darker and light faces lighter"},
    };
}

std::vector<StyleParam> operator+(std::vector<StyleParam> a, const std::vector<StyleParam>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

const std::vector<StyleParam> kTriangles = {
    {"ridge_spacing", 3.0, "mm", "spacing of the triangle grid along the ridges"},
    {"ridge_length", 1.5, "mm", "side of the triangles falling from the ridges"},
};
const std::vector<StyleParam> kCoarse = {
    {"cell_spacing", 3.0, "mm", "width of the coarse jittered cells that carry local density"},
    {"cell_jitter", 1.0, "ratio", "jitter of the coarse cells"},
};
const std::vector<StyleParam> kPeaks = {
    {"peak_spacing", 2.0, "mm", "distance between two ridge shapes"},
    {"peak_length", 2.0, "mm", "length of a ridge shape down the slope"},
    {"peak_width", 0.8, "mm", "width of a ridge shape at its base"},
    {"peak_fill", 0.2, "mm", "spacing of the fine hatching inside ridge shapes"},
};
const std::vector<StyleParam> kBalanced = {
    {"gap", 0.95, "ratio", "each hatch is shortened to this fraction, leaving gaps between strokes"},
};
const std::vector<StyleParam> kHigh = {
    {"peak_height_gain", 1.0, "ratio", "ridge shapes grow by this fraction on the highest ground"},
};
const std::vector<StyleParam> kCross = {
    {"roughness_min", 0.01, "ratio", "roughness (0..1) below which no cross hatching is drawn"},
    {"roughness_max", 0.08, "ratio", "roughness at which cross hatching is densest"},
    {"cross_spacing_min", 0.6, "mm", "cross hatch spacing at the highest roughness"},
    {"cross_spacing_max", 2.5, "mm", "cross hatch spacing at the lowest roughness"},
    {"cross_angle", 90.0, "deg", "angle between fill and cross hatches"},
};

}  // namespace

const char* family_name(Family f) {
    switch (f) {
        case Family::Fill: return "fill";
        case Family::Ridge: return "ridge";
        case Family::Valley: return "valley";
        case Family::Cross: return "cross";
    }
    return "?";
}

double family_width_mm(Family f) {
    switch (f) {
        case Family::Fill: return 0.10;
        case Family::Ridge: return 0.12;
        case Family::Valley: return 0.25;
        case Family::Cross: return 0.08;
    }
    return 0.1;
}

const std::vector<StyleInfo>& styles() {
    static const std::vector<StyleInfo> all = {
        {"noisy", "5.4a", "noisy hatching: one axis of a jittered grid per face", fill_params(3.0, 1.0)},
        {"ridge-triangles", "5.4b", "noisy hatching plus triangles falling from ridges into the darker face",
         fill_params(3.0, 1.0) + kTriangles},
        {"density-cells", "5.4c", "density varying inside faces: a coarse jittered grid, each cell hatched",
         fill_params(2.0, 0.5) + kCoarse + kTriangles},
        {"fine-ridges", "5.4d", "finer, sparser ridge shapes filled with sub-scale hatching",
         fill_params(2.0, 0.5) + kCoarse + kPeaks},
        {"balanced", "5.4e", "balanced density: linear height term, hatches broken into strokes",
         fill_params(2.0, 0.5) + kCoarse + kPeaks + kBalanced},
        {"high-ridges", "5.4f", "ridge shapes enhanced on higher ground, valleys drawn",
         fill_params(2.0, 0.5) + kCoarse + kPeaks + kBalanced + kHigh},
        {"bidirectional", "5.4g", "bidirectional hatching: cross hatches where the terrain is rough",
         fill_params(1.5, 0.5) + kCoarse + kPeaks + kBalanced + kHigh + kCross},
    };
    return all;
}

const std::string& default_style() { return styles().back().name; }

const StyleInfo& find_style(const std::string& name) {
    for (const auto& s : styles())
        if (s.name == name || s.figure == name || "5.4" + name == s.figure) return s;
    std::string names;
    for (const auto& s : styles()) names += (names.empty() ? "" : ", ") + s.name;
    throw Error(Code::UnknownStyle, "--style: unknown style '" + name + "' (known: " + names + ")");
}

ParamValues resolve_params(const StyleInfo& s, const std::map<std::string, double>& overrides, double scale) {
    ParamValues out;
    for (const auto& [k, v] : overrides) {
        const bool known = std::any_of(s.params.begin(), s.params.end(), [&](const StyleParam& p) { return p.name == k; });
        if (!known) throw Error(Code::UnknownStyle, "--param: style '" + s.name + "' has no parameter '" + k + "'");
    }
    for (const auto& p : s.params) {
        double v = p.value;
        if (auto it = overrides.find(p.name); it != overrides.end()) v = it->second;
        if (!std::isfinite(v) || (p.unit == "mm" && v <= 0) || (p.unit == "ratio" && v < 0)) {
            std::ostringstream m;
            m << "--param " << p.name << ": " << v << " is not a valid value (" << p.unit << ")";
            throw Error(Code::Usage, m.str());
        }
        if (p.unit == "mm") v = v * scale / 1000.0;
        if (p.unit == "deg") v = v * M_PI / 180.0;
        out[p.name] = v;
    }
    return out;
}

namespace {

bool has(const ParamValues& p, const char* k) { return p.count(k) != 0; }

// Spacing from density and height (seed App. E, `stripes_cycle`): height pushes dark faces
// darker and light faces lighter; `linear` selects the balanced (e) variant.
double spacing_for(const ParamValues& p, double density, double height, bool linear) {
    const double h = linear ? height : height * height;
    const double d = clamp01(0.5 + (density - 0.5) * (1 + p.at("contrast") * h));
    return p.at("spacing_min") + (p.at("spacing_max") - p.at("spacing_min")) * (1 - d);
}

void emit(std::vector<Hatch>& out, std::vector<Polyline>&& lines, Family f, double gap = 1.0) {
    for (auto& l : lines) {
        if (gap < 1) {
            for (auto& s : split_strokes(l, gap)) out.push_back({std::move(s), false, f});
        } else {
            out.push_back({std::move(l), false, f});
        }
    }
}

// Ridge segments of this face on which it is the darker side (the seed's
// `must_provide_coulis`): shapes fall from there into the face.
std::vector<int> dark_ridges(const RockFace& face, const FaceControls& c) {
    std::vector<int> out;
    for (std::size_t i = 0; i < face.boundary.size(); ++i) {
        if (face.boundary[i].kind != LineKind::Ridge) continue;
        const double other = c.neighbour_density(int(i));
        if (std::isnan(other) ? c.density >= 0.5 : c.density > other) out.push_back(int(i));
    }
    return out;
}

// (a) one axis of a jittered grid, clipped to the face.
void fill_face(std::vector<Hatch>& out, const ParamValues& p, const RockFace& face, const FaceControls& c,
               std::uint64_t seed) {
    const double s = spacing_for(p, c.density, c.height, false);
    const double j = p.at("jitter");
    const RegionClipper clip(face.region);
    for (auto& line : jittered_lines(face.region.bbox(), c.orientation, s, p.at("length"), j, j, seed, 1))
        emit(out, clip.clip(line), Family::Fill);
}

// (c) coarse jittered cells, each hatched with the density at its centre.
void fill_cells(std::vector<Hatch>& out, const ParamValues& p, const RockFace& face, const FaceControls& c,
                std::uint64_t seed, bool linear, double gap) {
    const double cs = p.at("cell_spacing"), len = p.at("length"), cj = p.at("cell_jitter");
    const double theta = c.orientation;
    // Coarse grid: lines along the hatch direction every cs, cut every 4 hatch lengths.
    const double along = 4 * len;
    const auto rows = jittered_lines(face.region.bbox(), theta, cs, along, cj * 0.5, cj * 0.5, seed, 2);
    const RegionClipper clip(face.region);
    for (std::size_t r = 0; r + 1 < rows.size(); ++r) {
        const Polyline& lo = rows[r];
        const Polyline& hi = rows[r + 1];
        for (std::size_t k = 0; k + 1 < lo.size() && k + 1 < hi.size(); ++k) {
            std::vector<Point> quad = {lo[k], lo[k + 1], hi[k + 1], hi[k]};
            if (tex::signed_area(quad) < 0) std::reverse(quad.begin(), quad.end());
            tex::BBox qb;
            for (const auto& q : quad) qb.add(q);
            if (!qb.intersects(face.region.bbox())) continue;
            const Point centre = ring_centroid(quad);
            double h = c.height_field(centre);
            if (std::isnan(h)) h = c.height;
            const double s = spacing_for(p, c.density, h, linear);
            const double j = p.at("jitter");
            for (auto& line : jittered_lines(qb, theta, s, len, j, j, seed, 3))
                for (auto& piece : clip_to_convex(line, quad)) emit(out, clip.clip(piece), Family::Fill, gap);
        }
    }
}

// (b) triangles: a grid at the hatch direction and 45 degrees, cells cut by the face, kept
// when they touch a ridge on which the face is the darker side.
void ridge_triangles(std::vector<Hatch>& out, const ParamValues& p, const RockFace& face, const FaceControls& c) {
    const std::vector<int> ridges = dark_ridges(face, c);
    if (ridges.empty()) return;
    const double a1 = c.orientation, a2 = c.orientation + M_PI / 4;
    const double s1 = p.at("ridge_spacing"), s2 = p.at("ridge_length");
    const Point n1{-std::sin(a1), std::cos(a1)}, n2{-std::sin(a2), std::cos(a2)};
    const double det = tex::cross(n1, n2);
    auto vertex = [&](long long i, long long j) {
        const double a = double(i) * s1, b = double(j) * s2;
        return Point{(a * n2.y - b * n1.y) / det, (n1.x * b - n2.x * a) / det};
    };
    auto index_of = [&](const Point& q) {
        return std::make_pair((long long)std::floor(tex::dot(q, n1) / s1), (long long)std::floor(tex::dot(q, n2) / s2));
    };
    std::vector<std::pair<long long, long long>> cells;
    for (int ri : ridges) {
        const BoundarySegment& seg = face.boundary[ri];
        const double len = tex::distance(seg.a, seg.b);
        const int steps = std::max(1, int(std::ceil(len / (0.25 * std::min(s1, s2)))));
        for (int k = 0; k <= steps; ++k) {
            const auto [i, j] = index_of(seg.a + (seg.b - seg.a) * (double(k) / steps));
            for (long long di = -1; di <= 1; ++di)
                for (long long dj = -1; dj <= 1; ++dj) cells.push_back({i + di, j + dj});
        }
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    auto touches_dark_ridge = [&](const std::vector<Point>& poly) {
        for (int ri : ridges) {
            const BoundarySegment& seg = face.boundary[ri];
            for (std::size_t k = 0; k < poly.size(); ++k) {
                const Point& a = poly[k];
                const Point& b = poly[(k + 1) % poly.size()];
                // An edge of the clipped cell lying on the ridge segment.
                const Point m = (a + b) / 2;
                const Point e = seg.b - seg.a;
                const double l2 = tex::dot(e, e);
                if (l2 == 0 || tex::distance(a, b) < 1e-9) continue;
                const double t = tex::dot(m - seg.a, e) / l2;
                if (t < 0 || t > 1) continue;
                if (std::abs(tex::cross(e, m - seg.a)) / std::sqrt(l2) < 1e-6 * (1 + std::sqrt(l2))) return true;
            }
        }
        return false;
    };
    for (const auto& [i, j] : cells) {
        std::vector<Point> cell = {vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)};
        if (tex::signed_area(cell) < 0) std::reverse(cell.begin(), cell.end());
        std::vector<Point> piece = clip_polygon_convex(face.region.outer(), cell);
        if (piece.size() < 3 || std::abs(tex::signed_area(piece)) < 1e-9) continue;
        if (!touches_dark_ridge(piece)) continue;
        // Drawn slightly shrunk, so that neighbouring shapes stay apart; the cell is shrunk
        // before the cut, so that the shape stays inside the face (a cut piece may be
        // concave, and shrinking it about its centroid could leave the face).
        std::vector<Point> shape = clip_polygon_convex(face.region.outer(), scale_ring(cell, 0.98));
        if (shape.size() < 3 || std::abs(tex::signed_area(shape)) < 1e-9) continue;
        out.push_back({std::move(shape), true, Family::Ridge});
    }
}

// (d) ridge shapes: small triangles hanging from the dark ridges down the hatch direction,
// placed where the ridge crosses lines of a stripes family (anchored to the plane), filled
// with sub-scale hatching.
void ridge_peaks(std::vector<Hatch>& out, const ParamValues& p, const RockFace& face, const FaceControls& c,
                 std::uint64_t seed, double height_gain) {
    const std::vector<int> ridges = dark_ridges(face, c);
    if (ridges.empty()) return;
    const double theta = c.orientation;
    const Point d{std::cos(theta), std::sin(theta)}, n{-d.y, d.x};
    const double spacing = p.at("peak_spacing"), fill = p.at("peak_fill");
    std::optional<RegionClipper> clip;
    for (int ri : ridges) {
        const BoundarySegment& seg = face.boundary[ri];
        const double ta = tex::dot(seg.a, n), tb = tex::dot(seg.b, n);
        if (ta == tb) continue;
        const long long k0 = (long long)std::ceil(std::min(ta, tb) / spacing);
        const long long k1 = (long long)std::floor(std::max(ta, tb) / spacing);
        for (long long k = k0; k <= k1; ++k) {
            // Half-open on the far end so a point shared by two segments is placed once.
            const double t = double(k) * spacing;
            if (t == std::max(ta, tb) && t != std::min(ta, tb)) continue;
            const Point apex = seg.a + (seg.b - seg.a) * ((t - ta) / (tb - ta));
            // Down the slope = into the face along +d or -d.
            const double probe = 0.05 * spacing;
            const Point dir = face.region.contains(apex + d * probe) ? d : face.region.contains(apex - d * probe) ? -d : Point{0, 0};
            if (dir == Point(0, 0)) continue;
            double h = c.height_field(apex);
            if (std::isnan(h)) h = c.height;
            const Point jt = jitter_at(apex, seed, 4);
            const double len = p.at("peak_length") * (1 + height_gain * h) * (0.85 + 0.15 * jt.x);
            const double half = p.at("peak_width") / 2 * (1 + 0.5 * height_gain * h);
            std::vector<Point> tri = {apex, apex + dir * len + n * half, apex + dir * len - n * half};
            if (tex::signed_area(tri) < 0) std::reverse(tri.begin(), tri.end());
            std::vector<Point> shape = clip_polygon_convex(face.region.outer(), tri);
            if (shape.size() < 3 || std::abs(tex::signed_area(shape)) < 1e-9) continue;
            if (tex::signed_area(shape) < 0) std::reverse(shape.begin(), shape.end());
            out.push_back({shape, true, Family::Ridge});
            tex::BBox sb;
            for (const auto& q : shape) sb.add(q);
            // The fine hatching stays inside the shape: the triangle and the face.
            if (!clip) clip.emplace(face.region);
            for (auto& line : jittered_lines(sb, theta, fill, 4 * fill, 0.2, 0.2, seed, 5))
                for (auto& piece : clip_to_convex(line, tri)) emit(out, clip->clip(piece), Family::Ridge);
        }
    }
}

// (f) valleys: the face's valley segments drawn as strokes (from the face with the smaller
// id, so a valley between two faces is drawn once).
void valleys(std::vector<Hatch>& out, const RockFace& face, const std::function<std::int64_t(int)>& neighbour_id) {
    Polyline cur;
    for (std::size_t i = 0; i < face.boundary.size(); ++i) {
        const BoundarySegment& s = face.boundary[i];
        const std::int64_t other = neighbour_id(int(i));
        const bool draw = s.kind == LineKind::Valley && (other < 0 || face.id < other);
        if (draw) {
            if (cur.empty() || cur.back() != s.a) {
                if (cur.size() >= 2) out.push_back({cur, false, Family::Valley});
                cur = {s.a};
            }
            cur.push_back(s.b);
        } else if (!cur.empty()) {
            if (cur.size() >= 2) out.push_back({cur, false, Family::Valley});
            cur.clear();
        }
    }
    if (cur.size() >= 2) out.push_back({cur, false, Family::Valley});
}

// (g) cross hatching where the terrain is rough: cells of a coarse grid whose roughness
// exceeds the threshold get hatches in the second direction, denser when rougher.
void cross_hatch(std::vector<Hatch>& out, const ParamValues& p, const RockFace& face, const FaceControls& c,
                 std::uint64_t seed) {
    const double r0 = p.at("roughness_min"), r1 = std::max(p.at("roughness_max"), r0 + 1e-9);
    const double cs = p.at("cell_spacing");
    const double angle = c.orientation + p.at("cross_angle");
    const auto rows = jittered_lines(face.region.bbox(), c.orientation, cs, cs, 0, 0, seed, 6);
    const RegionClipper clip(face.region);
    for (std::size_t r = 0; r + 1 < rows.size(); ++r)
        for (std::size_t k = 0; k + 1 < rows[r].size() && k + 1 < rows[r + 1].size(); ++k) {
            std::vector<Point> quad = {rows[r][k], rows[r][k + 1], rows[r + 1][k + 1], rows[r + 1][k]};
            if (tex::signed_area(quad) < 0) std::reverse(quad.begin(), quad.end());
            tex::BBox qb;
            for (const auto& q : quad) qb.add(q);
            if (!qb.intersects(face.region.bbox())) continue;
            const double rough = c.roughness_field(ring_centroid(quad));
            if (!(rough > r0)) continue;
            const double t = clamp01((rough - r0) / (r1 - r0));
            const double s = p.at("cross_spacing_max") - (p.at("cross_spacing_max") - p.at("cross_spacing_min")) * t;
            for (auto& line : jittered_lines(qb, angle, s, p.at("length"), 0.5, 0.5, seed, 7))
                for (auto& piece : clip_to_convex(line, quad))
                    emit(out, clip.clip(piece), Family::Cross, p.at("gap"));
        }
}

}  // namespace

FaceControls face_controls(const RockFace& face, const ControlFields& f,
                           std::function<std::int64_t(int)> neighbour_id) {
    FaceControls c;
    const Point inside = interior_point(face);
    c.orientation = f.orientation(inside);
    c.density = f.density(inside);
    if (std::isnan(c.orientation)) c.orientation = 0;
    if (std::isnan(c.density)) c.density = 0.5;
    // Highest point of the face's border (seed App. E, `highest_height`).
    double h = -1e300;
    for (const auto& q : face.region.outer()) {
        const double v = f.height(q);
        if (!std::isnan(v)) h = std::max(h, v);
    }
    c.height = h > -1e300 ? clamp01(h) : 0.5;
    // Density across a border segment: the field just outside its middle.
    Field density = f.density;
    std::vector<double> across(face.boundary.size(), std::nan(""));
    for (std::size_t i = 0; i < face.boundary.size(); ++i) {
        const BoundarySegment& s = face.boundary[i];
        const Point d = s.b - s.a;
        const double len = tex::norm(d);
        if (len == 0 || s.kind != LineKind::Ridge) continue;  // only ridges need it
        // Rings run with the inside on the left: outside is on the right.
        const Point out{d.y / len, -d.x / len};
        const double eps = std::min(0.5, 0.05 * len);
        across[i] = density((s.a + s.b) / 2 + out * eps);
    }
    c.neighbour_density = [across](int i) { return across[std::size_t(i)]; };
    c.neighbour_id = std::move(neighbour_id);
    c.height_field = f.height;
    c.roughness_field = f.roughness;
    return c;
}

std::vector<Hatch> hatch_face(const StyleInfo& style, const ParamValues& p, const RockFace& face,
                              const FaceControls& c, std::uint64_t seed) {
    std::vector<Hatch> out;
    const std::string& n = style.name;
    const bool linear = has(p, "gap");  // (e) onwards
    const double gap = has(p, "gap") ? p.at("gap") : 1.0;
    if (n == "noisy" || n == "ridge-triangles") fill_face(out, p, face, c, seed);
    else fill_cells(out, p, face, c, seed, linear, gap);
    if (has(p, "ridge_spacing")) ridge_triangles(out, p, face, c);
    if (has(p, "peak_spacing")) ridge_peaks(out, p, face, c, seed, has(p, "peak_height_gain") ? p.at("peak_height_gain") : 0.0);
    if (has(p, "peak_height_gain")) {
        // Valleys are drawn from (f) on; neighbour ids come through the controls.
        valleys(out, face, c.neighbour_id);
    }
    if (has(p, "roughness_min")) cross_hatch(out, p, face, c, seed);
    return out;
}

Style builtin_style(const std::string& name) {
    const StyleInfo& info = find_style(name);
    Style s{info, {}};
    s.bind = [&info](const ControlFields& fields, const ParamValues& params, std::uint64_t seed) -> FaceHatcher {
        return [&info, fields, params, seed](const RockFace& face, const NeighbourId& neighbour_id) {
            return hatch_face(info, params, face, face_controls(face, fields, neighbour_id), seed);
        };
    };
    return s;
}

}  // namespace carto
