#include "blocks.hpp"

#include <algorithm>
#include <cmath>

namespace carto::blocks {
using namespace tex;

namespace {
double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }
Point dir(double a) { return {std::cos(a), std::sin(a)}; }
Stripes stripes(double angle, double width, const std::string& label = "") {
    Stripes s = StripesProperties(angle, width);
    if (!label.empty()) SetEdgeLabels(s, {label});
    return s;
}
}  // namespace

std::vector<StyleParam> fill_params(double length_mm, double jitter) {
    return {
        {"spacing_min", 0.35, "mm", "hatch spacing in the darkest faces"},
        {"spacing_max", 1.5, "mm", "hatch spacing in the lightest faces"},
        {"length", length_mm, "mm", "length of a hatch between two jittered break points"},
        {"jitter", jitter, "ratio", "jitter of the break points, as a fraction of spacing and length"},
        {"contrast", 1.0, "ratio", "how much height pushes dark faces darker and light faces lighter"},
        {"slope_min", 0.0, "%", "no fill hatch where the slope is below this (percent; 0: everywhere)"},
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

FaceReading read_face(const ControlFields& f, const Region& r) {
    FaceReading out;
    const Point inside = interior_point(r);
    const double t = f.orientation(inside), d = f.density(inside);
    if (!std::isnan(t)) out.theta = t;
    if (!std::isnan(d)) out.density = d;
    // The highest relief on the face's outer ring (App. E `highest_height`).
    double h = -1e300;
    for (const Point& q : r.outer()) {
        const double v = f.height(q);
        if (!std::isnan(v)) h = std::max(h, v);
    }
    if (h > -1e300) out.height = clamp01(h);
    return out;
}

double spacing_for(const ParamValues& p, double density, double height, bool linear) {
    const double h = linear ? height : height * height;
    const double d = clamp01(0.5 + (density - 0.5) * (1 + p.at("contrast") * h));
    return p.at("spacing_min") + (p.at("spacing_max") - p.at("spacing_min")) * (1 - d);
}

Arrangement noisy_lines(const std::string& label, double theta, double spacing, double length, double r, double gap,
                        Field slope, double slope_min) {
    return MapToEdges(JitterEdges(label, theta, spacing, length, r, gap, std::move(slope), slope_min),
                      GridPartition(stripes(theta, spacing, label), stripes(theta + pi / 2, length), KEEP_OUTSIDE));
}

Arrangement cell_hatching(const ControlFields& f, const ParamValues& p, const FaceReading& face, bool linear,
                          double gap) {
    const double cs = p.at("cell_spacing"), len = p.at("length"), theta = face.theta;
    const Arrangement grid =
        MapToEdges(JitterEdges("grid", theta, cs, cs, 0.5 * p.at("cell_jitter")),
                   GridPartition(stripes(theta, cs, "grid"), stripes(theta + pi / 2, cs, "grid"), KEEP_OUTSIDE));
    // Each cell: the noisy lines of its spacing (broken every `len` at jittered points the
    // pieces share), cut to the cell; lines of equal spacing run on across cells.
    auto hatch_cell = [f, p, face, linear, gap, len](const Face& cell) {
        double h = f.height(Centroid(cell));
        if (std::isnan(h)) h = face.height;
        const double s = spacing_for(p, face.density, h, linear);
        return Crop(noisy_lines("fill", face.theta, s, len, p.at("jitter"), gap, f.slope, p.at("slope_min")),
                    CROP)(cell);
    };
    return MapToFaces(hatch_cell, grid);
}

bool darker_across(const ControlFields& f, const FaceReading& face, const Edge& e, const Face& cell) {
    const Point a = LocationAt(e, 0.49), b = LocationAt(e, 0.51), mid = LocationAt(e, 0.5);
    const double l = distance(a, b);
    if (l == 0) return false;
    Point out{(b - a).y / l, -(b - a).x / l};  // right of the edge
    if (RightFace(e) == cell) out = -out;
    const double eps = std::min(0.5, 2.5 * l);  // 2.5 l: 5 % of the edge's length
    const double other = f.density(mid + out * eps);
    return std::isnan(other) ? face.density >= 0.5 : face.density > other;
}

Arrangement ridge_triangles(const ControlFields& f, const ParamValues& p, const FaceReading& face) {
    auto keep_ridge = [f, face](const Face& cell) {
        for (const Edge& e : IncidentEdges(cell))
            if (HasLabel(e, "ridge") && darker_across(f, face, e, cell))  // the outline as one closed stroke
                return Labelled(Scale(tex::Polyline(ToRegion(cell).outer(), true), 0.98), "ridge");
        return Nothing();
    };
    return MapToFaces(keep_ridge, GridPartition(stripes(face.theta, p.at("ridge_spacing")),
                                                stripes(face.theta + pi / 4, p.at("ridge_length")), CROP_ADD_BOUNDARY));
}

Arrangement ridge_peaks(const ControlFields& f, const ParamValues& p, const FaceReading& face, double gain) {
    auto shape = [f, p, face, gain](const Vertex& v) {
        Edge ridge, into;
        bool dark = false, has_into = false;
        for (const Edge& e : IncidentEdges(v)) {
            if (HasLabel(e, "ridge")) {
                const Face cell = record(LeftFace(e)).unbounded ? RightFace(e) : LeftFace(e);
                dark |= darker_across(f, face, e, cell);
            } else if (!HasLabel(e, "valley") && !HasLabel(e, "other")) {
                into = e;
                has_into = true;
            }
        }
        if (!dark || !has_into) return Nothing();
        const Point apex = Location(v), d = dir(face.theta), n{-d.y, d.x};
        // Down the slope: along the stripe that leaves the ridge into the face.
        const Point down = dot(LocationAt(into, 0.5) - apex, d) >= 0 ? d : -d;
        double h = f.height(apex);
        if (std::isnan(h)) h = face.height;
        const double len = p.at("peak_length") * (1 + gain * h) * Random(v, 0.7, 1.0, 4);
        const double half = p.at("peak_width") / 2 * (1 + 0.5 * gain * h);
        const Region tri({apex, apex + down * len + n * half, apex + down * len - n * half}, {}, "ridge shape");
        return Labelled(StripesPartition(stripes(face.theta, p.at("peak_fill")))(tri), "ridge");
    };
    return MapToVertices(shape, StripesPartition(stripes(face.theta, p.at("peak_spacing"))));
}

Arrangement valleys() {
    return MapToEdges(
        [](const Edge& e) { return HasLabel(e, "valley") && HasLabel(e, "owned") ? ToCurve(e) : Nothing(); },
        Outline());
}

Arrangement cross_hatching(const ControlFields& f, const ParamValues& p, const FaceReading& face) {
    const double cs = p.at("cell_spacing"), theta = face.theta, angle = theta + p.at("cross_angle");
    auto hatch_cell = [f, p, angle](const Face& cell) {
        const double r0 = p.at("roughness_min"), r1 = std::max(p.at("roughness_max"), r0 + 1e-9);
        const double rough = f.roughness(Centroid(cell));
        if (!(rough > r0)) return Nothing();
        const double t = clamp01((rough - r0) / (r1 - r0));
        const double s = p.at("cross_spacing_max") - (p.at("cross_spacing_max") - p.at("cross_spacing_min")) * t;
        return MapToEdges(JitterEdges("cross", angle, s, p.at("length"), 0.5, p.at("gap")),
                          StripesPartition(stripes(angle, s, "cross"), CROP))(cell);
    };
    return MapToFaces(hatch_cell, GridPartition(stripes(theta, cs), stripes(theta + pi / 2, cs), KEEP_OUTSIDE));
}

StyleProgram per_face(FaceBody body, bool with_valleys) {
    return [body = std::move(body), with_valleys](const ControlFields& f, const ParamValues& p) {
        return Arrangement([body, with_valleys, f, p](const Region& r) {
            const FaceReading face = read_face(f, r);
            Curves out = Crop(body(f, p, face), CROP)(r);
            if (with_valleys) out.append(valleys()(r));
            return out;
        });
    };
}

}  // namespace carto::blocks
