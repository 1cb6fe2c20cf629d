#include "carto/blocks.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "carto/error.hpp"

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
const std::vector<StyleParam> kToneCells = {
    {"cell_spacing", 2.0, "mm", "width of the coarse jittered cells that carry local tone"},
    kCoarse[1],  // cell_jitter
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
const std::vector<StyleParam> kTone = {
    {"length", 1.5, "mm", "length of a hatch between two jittered break points"},
    {"jitter", 0.5, "ratio", "jitter of the break points, as a fraction of spacing and length"},
    {"slope_min", 0.0, "%", "no fill hatch where the slope is below this (percent; 0: everywhere)"},
    {"tone_min", 0.05, "ratio", "ink coverage of fill and cross strokes on fully lit ground"},
    {"tone_max", 0.36, "ratio", "ink coverage of fill and cross strokes in full shade"},
    {"tone_gamma", 1.0, "ratio", "exponent of the tone curve (above 1: mid-tones lighter)"},
    {"ink_max", 0.40, "ratio", "ceiling of the ink coverage of every cell, crests and valleys included"},
    {"min_gap", 0.15, "mm", "least white paper between two neighbouring fill strokes"},
    {"follow_fall_line", 1.0, "ratio", "1: strokes follow the local fall line; 0: one direction per face"},
};
const std::vector<StyleParam> kCrest = {
    {"crest_spacing", 0.4, "mm", "distance between two shadow-side strokes along a crest line"},
    {"crest_length", 0.8, "mm", "longest shadow-side stroke on low ground"},
    {"crest_height_gain", 0.5, "ratio", "shadow-side strokes grow by this fraction on the highest ground"},
    {"crest_smoothing", 0.8, "mm", "crest lines are drawn smooth at this length (shorter bends and steps go)"},
};
const std::vector<StyleParam> kFray = {
    {"fray_min", 0.2, "mm", "strokes end at least this far inside the rock's edge (where nothing lies across it)"},
    {"fray_max", 1.5, "mm", "and at most this far: they end irregularly in the band between"},
};
const std::vector<StyleParam> kCliff = {
    {"cliff_slope", 100.0, "%", "cliff bands are where the slope passes this (percent; 100: 45 degrees)"},
    {"cliff_length", 3.0, "mm", "longest stroke hanging from a cliff top (strokes end at the band's foot)"},
    {"cliff_min_length", 2.0, "mm", "cliff tops shorter than this are not drawn"},
};
const std::vector<StyleParam> kStructure = {
    {"crease_bend", 0.25, "ratio",
     "crests and couloirs are drawn where the slope changes by this much across 1 mm on paper (0.25: +12% to -12%)"},
    {"crease_min_length", 3.0, "mm", "crest and couloir lines shorter than this are not drawn"},
    {"couloir_gap", 0.2, "mm", "fill strokes keep this far from a couloir line (it reads as a gap)"},
    {"structure_gap", 0.15, "mm",
     "fill strokes keep this far from the structure lines (crests, cliff tops: they end at the lines, not across)"},
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

RidgeFoot ridge_foot(const ControlFields& f, const FaceReading& face, const Vertex& v) {
    RidgeFoot foot;
    for (const Edge& e : IncidentEdges(v)) {
        if (HasLabel(e, "ridge")) {
            const Face cell = record(LeftFace(e)).unbounded ? RightFace(e) : LeftFace(e);
            foot.dark = foot.dark || darker_across(f, face, e, cell);
        } else if (!HasLabel(e, "valley") && !HasLabel(e, "other")) {
            foot.into = e;
            foot.has_into = true;
        }
    }
    return foot;
}

Arrangement ridge_peaks(const ControlFields& f, const ParamValues& p, const FaceReading& face, double gain) {
    auto shape = [f, p, face, gain](const Vertex& v) {
        const RidgeFoot foot = ridge_foot(f, face, v);
        if (!foot.dark || !foot.has_into) return Nothing();
        const Point apex = Location(v), d = dir(face.theta), n{-d.y, d.x};
        // Down the slope: along the stripe that leaves the ridge into the face.
        const Point down = dot(LocationAt(foot.into, 0.5) - apex, d) >= 0 ? d : -d;
        double h = f.height(apex);
        if (std::isnan(h)) h = face.height;
        const double len = p.at("peak_length") * (1 + gain * h) * Random(v, 0.7, 1.0, 4);
        const double half = p.at("peak_width") / 2 * (1 + 0.5 * gain * h);
        const Region tri({apex, apex + down * len + n * half, apex + down * len - n * half}, {}, "ridge shape");
        return Labelled(StripesPartition(stripes(face.theta, p.at("peak_fill")))(tri), "ridge");
    };
    return MapToVertices(shape, StripesPartition(stripes(face.theta, p.at("peak_spacing"))));
}

namespace {
// Stroke k hanging from a crest line has (kShortestCrestStroke + (1 - kShortestCrestStroke) x
// ThinRank(k)) of the longest length: golden-ratio ranks spread the lengths evenly, so the ink
// fades down the slope from the line instead of ending in a comb's edge.
constexpr double kShortestCrestStroke = 0.35;
// Near a ridge's end the strokes shrink, to this fraction of their length at the end itself,
// growing to their full length (1 - this) x crest_length from it: the fringe tapers with the crest.
constexpr double kCrestEndTaper = 0.3;
// A stroke leaves the crest line within 60 degrees of its normal (this cosine): where the fall
// line runs nearly along the crest (a spur falling away), the line is drawn alone; a stroke
// turned off the fall line there would cross the fill strokes and read as a net.
constexpr double kCrestStrokeMinCos = 0.5;
// The share of the strokes hanging from a cliff top kept on fully lit rock (all in full shade).
constexpr double kLitCliffStrokes = 0.33;

// The direction of a stroke hanging from a line at `foot` into the side `n` (unit normal):
// the fall line read half the longest stroke down that side (on the line itself it averages
// two opposite slopes), the face's orientation when not following it or where it reads NaN;
// none where it runs within 60 degrees of the line.
std::optional<Point> hanging_direction(const ControlFields& f, const FaceReading& face, bool follow,
                                       const Point& foot, const Point& n, double longest) {
    double angle = face.theta;
    if (follow) {
        const double local = f.fall_line(foot + n * (0.5 * longest));
        if (!std::isnan(local)) angle = local;
    }
    Point d = dir(angle);
    if (dot(d, n) < 0) d = -d;
    if (dot(d, n) < kCrestStrokeMinCos) return std::nullopt;
    return d;
}

// The length of stroke k hanging from a line, `base` for the longest: a golden-ratio share
// kShortestCrestStroke .. 1 of it, shorter within `longest` of the line's nearer end
// (`to_end` from stroke k's foot).
double hanging_length(double base, long long k, double spacing, double to_end, double longest) {
    const double from_end = std::min((double(k) + 0.5) * spacing, to_end);
    const double taper = std::min(1.0, kCrestEndTaper + from_end / longest);
    return base * (kShortestCrestStroke + (1 - kShortestCrestStroke) * ThinRank(k)) * taper;
}
}  // namespace

Arrangement crest_lines(const ParamValues& p) {
    const double step = p.at("crest_smoothing");
    return Crop(MapToEdges([step](const Edge& e) { return HasLabel(e, "ridge") ? Smoothed(ToCurve(e), step) : Nothing(); },
                           Outline()),
                CROP);
}

Arrangement crest_strokes(const ControlFields& f, const ParamValues& p, const FaceReading& face, const Region& region) {
    auto strokes = [f, p, face, region](const Edge& e) -> Curves {
        if (!HasLabel(e, "ridge")) return Nothing();
        // Which side of the ridge the face lies on, and whether it is the darker one (the
        // density just across the ridge's middle; NaN: no face there).
        const Point a = LocationAt(e, 0.49), b = LocationAt(e, 0.51), mid = LocationAt(e, 0.5);
        const double l = distance(a, b);
        if (l == 0) return Nothing();
        const Point left{-(b - a).y / l, (b - a).x / l};
        const double eps = std::min(0.5, 2.5 * l);  // 2.5 l: 5 % of the edge's length
        const double side = region.contains(mid + left * eps) ? 1.0 : -1.0;
        const double other = f.density(mid - left * (side * eps));
        if (!(std::isnan(other) ? face.density >= 0.5 : face.density > other)) return Nothing();
        const double longest = p.at("crest_length"), spacing = p.at("crest_spacing");
        const bool follow = p.at("follow_fall_line") > 0;
        auto hang = [&](const Point& foot, const Point& t, long long k, double to_end) -> Curves {
            const Point n = Point{-t.y, t.x} * side;  // into the face
            const std::optional<Point> d = hanging_direction(f, face, follow, foot, n, longest);
            if (!d) return Nothing();
            double h = f.height(foot);
            if (std::isnan(h)) h = face.height;
            const double base = longest * (1 + p.at("crest_height_gain") * clamp01(h));
            const double len = hanging_length(base, k, spacing, to_end, longest);
            return Labelled(tex::Polyline({foot, foot + *d * len}), "ridge");
        };
        // The feet on the crest line as crest_lines draws it.
        return MapAlong(Smoothed(ToCurve(e), p.at("crest_smoothing")), spacing, hang);
    };
    return MapToEdges(strokes, Outline());
}

void check_tone(const ParamValues& p) {
    auto bad = [](const std::string& what) { throw Error(Code::Usage, "style 'print': " + what); };
    std::ostringstream m;
    if (p.at("tone_min") > p.at("tone_max")) {
        m << "--param tone_min=" << p.at("tone_min") << " is above tone_max=" << p.at("tone_max");
        bad(m.str());
    }
    if (p.at("ink_max") <= 0 || p.at("ink_max") > 1) {
        m << "--param ink_max=" << p.at("ink_max") << " is not a coverage in (0, 1]";
        bad(m.str());
    }
    if (p.at("gap") <= 0 || p.at("gap") > 1) {
        m << "--param gap=" << p.at("gap") << " is not a fraction in (0, 1]";
        bad(m.str());
    }
}

double tone_coverage(const ParamValues& p, double shade) {
    return p.at("tone_min") + (p.at("tone_max") - p.at("tone_min")) * std::pow(clamp01(shade), p.at("tone_gamma"));
}

Arrangement toned_hatching(const ControlFields& f, const ParamValues& p, const FaceReading& face,
                           const Region& region, const Curves& spent) {
    const double cs = p.at("cell_spacing");
    const Arrangement grid = MapToEdges(
        JitterEdges("grid", face.theta, cs, cs, 0.5 * p.at("cell_jitter")),
        GridPartition(stripes(face.theta, cs, "grid"), stripes(face.theta + pi / 2, cs, "grid"), KEEP_OUTSIDE));
    // The ink of each segment of `spent` at its middle, in ink_area's order: a cell sums those
    // whose middle it holds, as ink_area(spent, mm, &cell) does, without walking every curve.
    struct SpentInk {
        Point mid;
        double ink;
    };
    auto spent_ink = std::make_shared<std::vector<SpentInk>>();
    for (const Curve& cv : spent.curves) {
        const std::size_t n = cv.points.size();
        if (n < 2) continue;
        const double width = family_width_mm(family_of(cv.labels)) * p.at(kGroundPerMm);
        for (std::size_t i = 0; i + 1 < n + (cv.closed ? 1 : 0); ++i) {
            const Point& a = cv.points[i];
            const Point& b = cv.points[(i + 1) % n];
            spent_ink->push_back({(a + b) * 0.5, distance(a, b) * width});
        }
    }
    auto hatch_cell = [f, p, face, region, spent_ink](const Face& cell) {
        const double mm = p.at(kGroundPerMm), gap = p.at("gap"), len = p.at("length");
        const Region box = ToRegion(cell);
        const Point c = Centroid(cell);
        double shade = f.shade(c);
        if (std::isnan(shade)) shade = face.density;
        // The tone under the ceiling, less what the crests and valleys already put in this
        // cell (they run along the face's border, where cells reach out of the face: its part
        // counts): the cell's ink, lines included, follows the shade.
        const double area = region.area_within(box);
        double inside = 0;
        if (area > 0) {
            const BBox bb = box.bbox();
            for (const SpentInk& s : *spent_ink)
                if (bb.contains(s.mid) && box.contains(s.mid)) inside += s.ink;
        }
        const double used = area > 0 ? inside / area : 0.0;
        const double target = std::min(tone_coverage(p, shade), p.at("ink_max")) - used;
        if (!(target > 0)) return Nothing();
        const bool follow = p.at("follow_fall_line") > 0;
        double theta = face.theta;
        if (follow) {
            const double local = f.fall_line(c);
            if (!std::isnan(local)) theta = local;
        }
        Curves out;
        double cross_cover = 0;
        const double r0 = p.at("roughness_min"), r1 = std::max(p.at("roughness_max"), r0 + 1e-9);
        const double rough = f.roughness(c);
        // Rough cells: cross strokes take up to half the cell's tone, denser when rougher;
        // none where that half is too little ink to space them within cross_spacing_max
        // (lone crosses on lit ground read as noise, not texture).
        const double wc = family_width_mm(Family::Cross) * mm;
        const double s_cross = std::max(
            p.at("cross_spacing_max") -
                (p.at("cross_spacing_max") - p.at("cross_spacing_min")) * clamp01((rough - r0) / (r1 - r0)),
            wc * gap / (0.5 * target));
        if (rough > r0 && s_cross <= p.at("cross_spacing_max")) {
            const double s = s_cross;
            cross_cover = wc * gap / s;
            const double angle = theta + p.at("cross_angle");
            out = MapToEdges(JitterEdges("cross", angle, s, len, 0.5, gap),
                             StripesPartition(stripes(angle, s, "cross"), CROP))(cell);
        }
        // Fill strokes of width w every s cover w x gap / s of the cell; min_gap keeps white
        // paper between neighbours whatever the tone asks.
        const double wf = family_width_mm(Family::Fill) * mm;
        const double s = std::max(wf * gap / (target - cross_cover), wf + p.at("min_gap"));
        const Arrangement lines =
            Crop(noisy_lines("fill", theta, s, len, p.at("jitter"), gap, f.slope, p.at("slope_min")), CROP);
        // Each stroke laid on the fall line at its middle (where the partition gave no
        // orientation), else on the cell's direction: the jitter of the break points moves
        // strokes, it does not tilt them (tilted, sparse strokes read as zigzags).
        out.append(AlignToField(lines, follow ? Fallback(f.fall_line, Field(theta)) : Field(theta))(cell));
        return out;
    };
    return MapToFaces(hatch_cell, grid);
}

namespace {
// The DEM's cell when the pipeline gave it (0: unknown).
double dem_cell(const ParamValues& p) {
    const auto it = p.find(kDemCell);
    return it == p.end() ? 0.0 : it->second;
}

// The box of a face grown by the structure margin, as a region to trace lines on.
Region grown_box(const ParamValues& p, const Region& region) {
    const BBox b = region.bbox().expanded(structure_margin(p));
    return Region::rectangle(b.xmin, b.ymin, b.xmax, b.ymax);
}

// Lines traced on a lattice of `cell`, smoothed over about crest_smoothing, the pieces at
// least `min_length` long, labelled.
Curves structure_pieces(const Curves& traced, const ParamValues& p, double cell, double min_length,
                        const std::string& label) {
    const int half = std::max(1, int(std::lround(p.at("crest_smoothing") / cell)));
    Curves out;
    for (Curve& c : MovingAverage(traced, half).curves) {
        double length = 0;
        const std::size_t n = c.points.size();
        for (std::size_t i = 0; i + 1 < n + (c.closed ? 1 : 0); ++i) length += distance(c.points[i], c.points[(i + 1) % n]);
        if (n < 2 || length < min_length) continue;
        c.labels.add(label);
        out.curves.push_back(std::move(c));
    }
    return out;
}

// The edges of the face's border labelled `label`, as curves.
Curves border_lines(const Region& region, const std::string& label) {
    return MapToEdges([label](const Edge& e) { return HasLabel(e, label) ? ToCurve(e) : Nothing(); }, Outline())(region);
}
}  // namespace

double structure_margin(const ParamValues& p) {
    return std::max(p.at("crease_min_length"), p.at("cliff_min_length")) + 2 * p.at("crest_smoothing");
}

tex::Curves cliff_tops(const ControlFields& f, const ParamValues& p, const Region& region) {
    const double cell = std::max(p.at("crest_smoothing"), dem_cell(p)) / 4;
    const Curves levels = IsoLines(f.slope, p.at("cliff_slope"), cell)(grown_box(p, region));
    Curves runs;
    for (const Curve& c : levels.curves) {
        // Runs of the line along which the band (on its left) lies lower: a cliff's top.
        std::vector<Point> pts = c.points;
        if (c.closed) pts.push_back(pts.front());
        std::vector<Point> run;
        auto flush = [&] {
            if (run.size() >= 2) runs.append(tex::Polyline(run));
            run.clear();
        };
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
            const Point a = pts[i], b = pts[i + 1];
            const double l = distance(a, b);
            bool top = false;
            if (l > 0) {
                const Point mid = (a + b) / 2, left{-(b - a).y / l, (b - a).x / l};
                const double into = f.height(mid + left * cell), out = f.height(mid - left * cell);
                top = into < out;  // NaN: not a top
            }
            if (top) {
                if (run.empty()) run.push_back(a);
                run.push_back(b);
            } else {
                flush();
            }
        }
        flush();
    }
    return structure_pieces(runs, p, cell, p.at("cliff_min_length"), "cliff");
}

Structure structure_lines(const ControlFields& f, const ParamValues& p, const Region& region) {
    Structure s;
    const double cell = std::max(p.at("crest_smoothing"), dem_cell(p)) / 2, snap = p.at("crest_smoothing");
    const double bend = p.at("crease_bend") / p.at(kGroundPerMm);
    const Region box = grown_box(p, region);
    s.cliffs = cliff_tops(f, p, region);
    // Crests: not along a cliff top (drawn as such).
    const Curves crests = Creases(f.elevation, CreaseKind::Ridge, cell, bend)(box);
    s.ridges = structure_pieces(Apart(Constant(crests), s.cliffs, snap)(box), p, cell, p.at("crease_min_length"),
                                "ridgeline");
    s.couloirs = structure_pieces(Creases(f.elevation, CreaseKind::Valley, cell, bend)(box), p, cell,
                                  p.at("crease_min_length"), "couloir");
    return s;
}

Structure given_first(const ParamValues& p, const Structure& s, const Region& region) {
    const double snap = p.at("crest_smoothing");
    auto apart = [&](const Curves& lines, const std::string& given, double min_length) {
        const Curves on_border = border_lines(region, given);
        if (on_border.empty()) return lines;
        Curves out;
        for (Curve& c : Apart(Constant(lines), on_border, snap)(region).curves) {
            double length = 0;
            for (std::size_t i = 0; i + 1 < c.points.size(); ++i) length += distance(c.points[i], c.points[i + 1]);
            if (length >= min_length) out.curves.push_back(std::move(c));
        }
        return out;
    };
    return {apart(s.ridges, "ridge", p.at("crease_min_length")), apart(s.couloirs, "valley", p.at("crease_min_length")),
            apart(s.cliffs, "cliff", p.at("cliff_min_length"))};
}

tex::Curves given_cliffs(const ControlFields& f, const Region& region) {
    Curves out;
    for (Curve& c : border_lines(region, "cliff").curves) {
        // Turned so that the ground falls on its left (into the band), by the heights a
        // step either side of its points.
        double lower_left = 0;
        const std::size_t n = c.points.size();
        for (std::size_t i = 0; i + 1 < n; ++i) {
            const Point a = c.points[i], b = c.points[i + 1];
            const double l = distance(a, b);
            if (l == 0) continue;
            const Point mid = (a + b) / 2, left{-(b - a).y / l, (b - a).x / l};
            const double step = std::max(l, 1e-9);
            const double zl = f.elevation(mid + left * step), zr = f.elevation(mid - left * step);
            if (!std::isnan(zl) && !std::isnan(zr)) lower_left += (zr - zl) * l;
        }
        if (lower_left < 0) std::reverse(c.points.begin(), c.points.end());
        // Drawn by the face its band lies in (below it), or, where no face lies there, by the
        // face above it.
        bool mine = false;
        for (std::size_t i = 0; i + 1 < n && !mine; ++i) {
            const Point a = c.points[i], b = c.points[i + 1];
            const double l = distance(a, b);
            if (l == 0) continue;
            const Point below = (a + b) / 2 + Point{-(b - a).y / l, (b - a).x / l} * std::min(0.5 * l, 1.0);
            mine = region.contains(below) || std::isnan(f.density(below));
            break;
        }
        if (!mine) continue;
        Curve k;
        k.points = std::move(c.points);
        k.closed = c.closed;
        k.labels.add("cliff");
        out.curves.push_back(std::move(k));
    }
    return out;
}

namespace {
constexpr double kTaperOffsetMm = 0.05;  // between the strokes that widen a crest line
constexpr double kTaperEndMm = 0.7;      // the first widening stroke starts this far from the line's ends
constexpr double kTaperFall = 1.5;       // the fall (per length) over 1 mm on paper of a full wall below
}  // namespace

tex::Curves tapered(const ControlFields& f, const ParamValues& p, const Curves& lines) {
    const double mm = p.at(kGroundPerMm);
    Curves out = lines;
    for (const Curve& c : lines.curves) {
        const std::size_t n = c.points.size();
        if (n < 3 || c.closed) continue;
        // Arc length at each point, the side and the wall below it.
        std::vector<double> at(n, 0.0);
        for (std::size_t i = 1; i < n; ++i) at[i] = at[i - 1] + distance(c.points[i - 1], c.points[i]);
        const double total = at.back();
        std::vector<Point> normal(n);
        std::vector<double> wall(n, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
            const Point t = c.points[std::min(i + 1, n - 1)] - c.points[i > 0 ? i - 1 : 0];
            const double l = std::hypot(t.x, t.y);
            if (l == 0) continue;
            Point nrm{-t.y / l, t.x / l};
            const double sl = f.shade(c.points[i] + nrm * (0.5 * mm)), sr = f.shade(c.points[i] - nrm * (0.5 * mm));
            if (std::isnan(sl) || (!std::isnan(sr) && sr > sl)) nrm = -nrm;
            const double z0 = f.elevation(c.points[i]), z1 = f.elevation(c.points[i] + nrm * mm);
            normal[i] = nrm;
            wall[i] = std::isnan(z0) || std::isnan(z1) ? 0.0 : clamp01((z0 - z1) / (kTaperFall * mm));
        }
        for (int k = 1; k <= 2; ++k) {
            std::vector<Point> run;
            auto flush = [&] {
                if (run.size() >= 2) {
                    Curve w;
                    w.points = std::move(run);
                    w.labels = c.labels;
                    out.curves.push_back(std::move(w));
                }
                run.clear();
            };
            for (std::size_t i = 0; i < n; ++i) {
                const bool on = wall[i] >= k / 3.0 && std::min(at[i], total - at[i]) >= k * kTaperEndMm * mm &&
                                (run.empty() || dot(normal[i], normal[i - 1]) > 0);
                if (!on) {
                    flush();
                    continue;
                }
                run.push_back(c.points[i] + normal[i] * (k * kTaperOffsetMm * mm));
            }
            flush();
        }
    }
    return out;
}

tex::Curves shadow_strokes(const ControlFields& f, const ParamValues& p, const FaceReading& face, const Curves& lines) {
    const double longest = p.at("crest_length"), spacing = p.at("crest_spacing");
    const bool follow = p.at("follow_fall_line") > 0;
    auto hang = [&](const Point& foot, const Point& t, long long k, double to_end) -> Curves {
        Point n{-t.y, t.x};
        double shade = f.shade(foot + n * (0.5 * longest));
        const double other = f.shade(foot - n * (0.5 * longest));
        if (std::isnan(shade) || (!std::isnan(other) && other > shade)) {
            n = -n;
            shade = other;
        }
        if (std::isnan(shade)) return Nothing();
        if (ThinRank(k) > kLitCliffStrokes + (1 - kLitCliffStrokes) * clamp01(shade)) return Nothing();
        const std::optional<Point> d = hanging_direction(f, face, follow, foot, n, longest);
        if (!d) return Nothing();
        double h = f.height(foot);
        if (std::isnan(h)) h = face.height;
        const double base = longest * (1 + p.at("crest_height_gain") * clamp01(h));
        return Labelled(tex::Polyline({foot, foot + *d * hanging_length(base, k, spacing, to_end, longest)}), "ridge");
    };
    return MapAlong(lines, spacing, hang);
}

tex::Curves cliff_strokes(const ControlFields& f, const ParamValues& p, const FaceReading& face, const Curves& tops) {
    const double longest = p.at("cliff_length"), spacing = p.at("crest_spacing");
    const bool follow = p.at("follow_fall_line") > 0;
    auto hang = [&](const Point& foot, const Point& t, long long k, double to_end) -> Curves {
        const Point n{-t.y, t.x};  // into the band: the line runs with the band on its left
        const std::optional<Point> d = hanging_direction(f, face, follow, foot, n, longest);
        if (!d) return Nothing();
        // Dense in shade, sparse on lit rock: stroke k is kept when its golden-ratio rank is
        // under the shade (from a third of them on fully lit ground).
        double shade = f.shade(foot + n * (0.5 * longest));
        if (std::isnan(shade)) shade = face.density;
        if (ThinRank(k) > kLitCliffStrokes + (1 - kLitCliffStrokes) * std::clamp(shade, 0.0, 1.0)) return Nothing();
        // As long as the band is high: down to where the slope falls under cliff_slope again.
        const double step = 0.1 * p.at(kGroundPerMm);
        double band = longest;
        for (double t = step; t < longest; t += step)
            if (!(f.slope(foot + *d * t) >= p.at("cliff_slope"))) {
                band = t;
                break;
            }
        return Labelled(tex::Polyline({foot, foot + *d * hanging_length(band, k, spacing, to_end, longest)}), "ridge");
    };
    return MapAlong(tops, spacing, hang);
}

void check_fray(const ParamValues& p) {
    if (!(p.at("fray_min") >= 0) || !(p.at("fray_max") >= p.at("fray_min"))) {
        std::ostringstream m;
        m << "style: --param fray_min=" << p.at("fray_min") / p.at(kGroundPerMm) << " and fray_max="
          << p.at("fray_max") / p.at(kGroundPerMm) << " must satisfy 0 <= fray_min <= fray_max";
        throw Error(Code::Usage, m.str());
    }
}

Arrangement frayed(const ControlFields& f, const ParamValues& p, Arrangement a) {
    return FrayedCrop(std::move(a), p.at("fray_min"), p.at("fray_max"), f.density, {"ridge", "cliff"});
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
