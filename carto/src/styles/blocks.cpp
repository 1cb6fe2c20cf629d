#include "carto/blocks.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "carto/error.hpp"
#include "hanging.hpp"

namespace carto::blocks {
using namespace tex;

namespace {
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
const std::vector<StyleParam> kRockTone = [] {
    std::vector<StyleParam> t = kTone;
    for (StyleParam& q : t)
        if (q.name == "tone_gamma") q.value = 2.0;
    return t;
}();
const std::vector<StyleParam> kCrest = {
    {"crest_spacing", 0.4, "mm", "distance between two shadow-side strokes along a crest line"},
    {"crest_length", 0.8, "mm", "longest shadow-side stroke on low ground"},
    {"crest_height_gain", 0.5, "ratio", "shadow-side strokes grow by this fraction on the highest ground"},
    {"crest_smoothing", 0.8, "mm", "crest lines are drawn smooth at this length (shorter bends and steps go)"},
};
const std::vector<StyleParam> kFray = {
    {"fray_min", 0.2, "mm", "strokes end at least this far from the rock's edge (where nothing lies across it)"},
    {"fray_max", 0.75, "mm", "and at most this far: they end irregularly in the band between"},
    {"fray_beyond", 0.5, "ratio",
     "this share of the fill strokes reaching the edge go on past it by as much instead, where they cross it at 60 degrees or more (0 to 1: ends on both sides; the cross strokes all end inside)"},
};
const std::vector<StyleParam> kRows = {
    {"band_height", 1.2, "mm",
     "fill strokes hang in rows from level lines of the elevation this x the scale apart (1.2 mm: 12 m at 1:10000)"},
    {"band_gap", 0.15, "mm", "white paper above each row's level line"},
    {"band_slope", 70.0, "%", "rows where the ground is at least this steep (percent; 70: 35 degrees), long strokes on gentler slabs"},
    {"band_wander", 0.5, "ratio", "the rows' level lines wander up and down by this share of band_height (over 5 mm on paper)"},
    {"band_ragged", 0.3, "ratio",
     "fill strokes in rows are laid this much denser, then shortened from their lower ends by random shares to the tone: rows end raggedly"},
};
const std::vector<StyleParam> kCliff = {
    {"cliff_slope", 100.0, "%", "cliff bands are where the slope passes this (percent; 100: 45 degrees)"},
    {"cliff_length", 3.0, "mm", "longest stroke hanging from a cliff top (strokes end at the band's foot)"},
    {"cliff_min_length", 2.0, "mm", "cliff tops shorter than this are not drawn"},
    {"cliff_smoothing", 0.5, "mm", "cliff tops follow the slope of the elevation differenced over this either side"},
    {"cliff_break", 30.0, "%", "a cliff top is drawn only where the slope below it exceeds the slope above by this (percent: a break of slope)"},
    {"foot_gap", 0.15, "mm",
     "the fill strokes below the foot of a cliff band start this far under it (the band's strokes reach the foot: a seam of white paper, no line)"},
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
    const Point inside = InteriorPoint(r);
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

// The strokes hanging from lines (hanging.hpp).
namespace detail {

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

double hanging_length(double base, long long k, double spacing, double to_end, double longest) {
    const double from_end = std::min((double(k) + 0.5) * spacing, to_end);
    const double taper = std::min(1.0, kCrestEndTaper + from_end / longest);
    return base * (kShortestCrestStroke + (1 - kShortestCrestStroke) * ThinRank(k)) * taper;
}
}  // namespace detail

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
    // Structure lines are traced over a margin round each face as long as the shortest line
    // drawn, so that a line's length is read alike in every face and tile: beyond 50 mm on
    // paper that margin is more than a sheet.
    for (const char* key : {"cliff_min_length", "crease_min_length"})
        if (p.count(key) && p.at(key) > 50 * p.at(kGroundPerMm)) {  // lengths are ground units here
            m << "--param " << key << "=" << p.at(key) / p.at(kGroundPerMm) << " is above 50 mm (to draw no "
              << (key[1] == 'l' ? "cliff tops, raise cliff_slope" : "extracted crests or couloirs, raise crease_bend") << ")";
            bad(m.str());
        }
    // Rows: strokes laid more than twice as dense as the tone asks would cost time for nothing.
    if (p.count("band_ragged") && p.at("band_ragged") > 1) {
        m << "--param band_ragged=" << p.at("band_ragged") << " is above 1";
        bad(m.str());
    }
}

double tone_coverage(const ParamValues& p, double shade) {
    return p.at("tone_min") + (p.at("tone_max") - p.at("tone_min")) * std::pow(clamp01(shade), p.at("tone_gamma"));
}

namespace {

// The curve less `cut` of its length at its end (back) or its start.
void trim_curve(Curve& c, double cut, bool back) {
    if (!back) std::reverse(c.points.begin(), c.points.end());
    while (cut > 0 && c.points.size() >= 2) {
        Point& b = c.points.back();
        const Point a = c.points[c.points.size() - 2];
        const double l = distance(a, b);
        if (l > cut) {
            b = a + (b - a) * ((l - cut) / l);
            break;
        }
        cut -= l;
        c.points.pop_back();
    }
    if (!back) std::reverse(c.points.begin(), c.points.end());
}

// The distance on paper over which the rows' level lines wander (band_wander).
constexpr double kBandWanderMm = 5.0;

constexpr std::uint64_t kRaggedTag = 0x52414747ULL;
// In rows, no fill stroke shorter than this many times its width: a shorter one reads as a speck.
constexpr double kShortestStroke = 2.0;

// Shortens the strokes from their lower ends (down the direction `down`, radians) so that
// their length is `keep` at most: each by a random share (keyed by its upper end and the
// seed), the shares scaled together so that the lengths add up to `keep`. A stroke that
// would be left shorter than `shortest` goes whole (a speck, not a stroke), the others
// taking up the difference.
void shorten_to_ink(Curves& strokes, double keep, double down, double shortest) {
    const std::size_t n = strokes.curves.size();
    std::vector<double> len(n);
    double total = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const auto& pts = strokes.curves[i].points;
        for (std::size_t k = 1; k < pts.size(); ++k) len[i] += distance(pts[k - 1], pts[k]);
        total += len[i];
    }
    const double remove = total - std::max(keep, 0.0);
    const Point d{std::cos(down), std::sin(down)};
    const std::uint64_t key = hash_combine(kRaggedTag, GetSeed());
    std::vector<double> share(n, 0.0);
    std::vector<char> back(n);
    const double mean = remove > 0 ? remove / total : 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const auto& pts = strokes.curves[i].points;
        if (pts.size() < 2 || len[i] < shortest) {
            share[i] = 1;
            continue;
        }
        back[i] = dot(pts.back() - pts.front(), d) >= 0;  // the last point is the lower
        share[i] = std::min(1.0, 2 * mean * unit_from_hash(hash_point(key, back[i] ? pts.front() : pts.back())));
    }
    // Scaled until the shares take off `remove` (capped at whole strokes, a few rounds); a
    // stroke left under `shortest` goes.
    for (int round = 0; round < 4 && remove > 0; ++round) {
        double taken = 0, partial = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (share[i] < 1 && (1 - share[i]) * len[i] < shortest) share[i] = 1;
            taken += share[i] * len[i];
            if (share[i] < 1) partial += share[i] * len[i];
        }
        if (!(partial > 0) || std::abs(taken - remove) <= 1e-9 * total) break;
        const double scale = std::max(0.0, (remove - (taken - partial)) / partial);
        for (double& v : share)
            if (v < 1) v = std::min(1.0, v * scale);
    }
    std::vector<Curve> kept;
    kept.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (share[i] >= 1 - 1e-9 || (1 - share[i]) * len[i] < shortest) continue;
        Curve& c = strokes.curves[i];
        trim_curve(c, share[i] * len[i], back[i]);
        kept.push_back(std::move(c));
    }
    strokes.curves = std::move(kept);
}

}  // namespace

Arrangement toned_hatching(const ControlFields& f, const ParamValues& p, const FaceReading& face,
                           const Region& region, const Curves& spent) {
    const double cs = p.at("cell_spacing");
    const Arrangement grid = MapToEdges(
        JitterEdges("grid", face.theta, cs, cs, 0.5 * p.at("cell_jitter")),
        GridPartition(stripes(face.theta, cs, "grid"), stripes(face.theta + pi / 2, cs, "grid"), KEEP_OUTSIDE));
    // The ink of each segment of `spent` at its middle, in ink_area's order: a cell sums those
    // whose middle it holds, as ink_area(spent, mm, &cell) does, without walking every curve.
    // Their order by x lets a cell look only at those within its box (summed then in
    // ink_area's order: the same sum to the bit).
    struct SpentInk {
        Point mid;
        double ink;
    };
    struct Spent {
        std::vector<SpentInk> ink;        // in ink_area's order
        std::vector<std::uint32_t> by_x;  // indices into ink, by the x of the middle
    };
    auto spent_ink = std::make_shared<Spent>();
    for (const Curve& cv : spent.curves) {
        const std::size_t n = cv.points.size();
        if (n < 2) continue;
        const double width = family_width_mm(family_of(cv.labels)) * p.at(kGroundPerMm);
        for (std::size_t i = 0; i + 1 < n + (cv.closed ? 1 : 0); ++i) {
            const Point& a = cv.points[i];
            const Point& b = cv.points[(i + 1) % n];
            spent_ink->ink.push_back({(a + b) * 0.5, distance(a, b) * width});
        }
    }
    spent_ink->by_x.resize(spent_ink->ink.size());
    for (std::size_t i = 0; i < spent_ink->by_x.size(); ++i) spent_ink->by_x[i] = std::uint32_t(i);
    std::sort(spent_ink->by_x.begin(), spent_ink->by_x.end(), [&ink = spent_ink->ink](std::uint32_t a, std::uint32_t b) {
        return ink[a].mid.x < ink[b].mid.x || (ink[a].mid.x == ink[b].mid.x && a < b);
    });
    // The field the rows are cut on: the elevation, its level lines wandering by up to
    // band_wander x band_height over kBandWanderMm on paper, so that the rows thicken and thin
    // as bands of rock do rather than run as regular contours.
    const Field levels = p.count("band_height") ? f.elevation + Noise(kBandWanderMm * p.at(kGroundPerMm)) *
                                                                    Field(p.at("band_wander") * p.at("band_height"))
                                                  : f.elevation;
    // What a cell reads of the parameters, looked up once.
    struct CellParams {
        double mm, gap, len, ink_max, r0, r1, cross_max, cross_min, cross_angle, jitter, slope_min, min_gap;
        double band, band_gap, band_slope, band_ragged;  // 0 without rows
        bool follow;
    };
    const bool banded = p.count("band_height") > 0;
    const CellParams q{p.at(kGroundPerMm),
                       p.at("gap"),
                       p.at("length"),
                       p.at("ink_max"),
                       p.at("roughness_min"),
                       std::max(p.at("roughness_max"), p.at("roughness_min") + 1e-9),
                       p.at("cross_spacing_max"),
                       p.at("cross_spacing_min"),
                       p.at("cross_angle"),
                       p.at("jitter"),
                       p.at("slope_min"),
                       p.at("min_gap"),
                       banded ? p.at("band_height") : 0.0,
                       banded ? p.at("band_gap") : 0.0,
                       banded ? p.at("band_slope") : 0.0,
                       banded ? p.at("band_ragged") : 0.0,
                       p.at("follow_fall_line") > 0};
    auto hatch_cell = [f, p, q, face, region, spent_ink, levels](const Face& cell) {
        const double mm = q.mm, gap = q.gap, len = q.len;
        const Region box = ToRegion(cell);
        const Point c = Centroid(cell);
        double shade = f.shade(c);
        if (std::isnan(shade)) shade = face.density;
        // The tone under the ceiling, less what the crests and valleys already put in this
        // cell (they run along the face's border, where cells reach out of the face: its part
        // counts): the cell's ink, lines included, follows the shade.
        // The face's area in the cell is asked only where lines put ink (a clip of the face's
        // ring by the cell: most cells have none, and then nothing is used whatever the area).
        double inside = 0;
        const BBox bb = box.bbox();
        {
            const std::vector<SpentInk>& ink = spent_ink->ink;
            const std::vector<std::uint32_t>& by_x = spent_ink->by_x;
            auto it = std::lower_bound(by_x.begin(), by_x.end(), bb.xmin,
                                       [&ink](std::uint32_t i, double x) { return ink[i].mid.x < x; });
            std::vector<std::uint32_t> held;
            for (; it != by_x.end() && ink[*it].mid.x <= bb.xmax; ++it)
                if (bb.contains(ink[*it].mid) && box.contains(ink[*it].mid)) held.push_back(*it);
            std::sort(held.begin(), held.end());
            for (std::uint32_t i : held) inside += ink[i].ink;
        }
        const double area = inside == 0 ? 0.0 : region.area_within(box);
        const double used = area > 0 ? inside / area : 0.0;
        const double target = std::min(tone_coverage(p, shade), q.ink_max) - used;
        if (!(target > 0)) return Nothing();
        const bool follow = q.follow;
        double theta = face.theta;
        if (follow) {
            const double local = f.fall_line(c);
            if (!std::isnan(local)) theta = local;
        }
        Curves out;
        double cross_cover = 0;
        const double r0 = q.r0, r1 = q.r1;
        const double rough = f.roughness(c);
        // Rough cells: cross strokes take up to half the cell's tone, denser when rougher;
        // none where that half is too little ink to space them within cross_spacing_max
        // (lone crosses on lit ground read as noise, not texture).
        const double wc = family_width_mm(Family::Cross) * mm;
        const double s_cross = std::max(
            q.cross_max - (q.cross_max - q.cross_min) * clamp01((rough - r0) / (r1 - r0)),
            wc * gap / (0.5 * target));
        if (rough > r0 && s_cross <= q.cross_max) {
            const double s = s_cross;
            cross_cover = wc * gap / s;
            const double angle = theta + q.cross_angle;
            out = MapToEdges(JitterEdges("cross", angle, s, len, 0.5, gap),
                             StripesPartition(stripes(angle, s, "cross"), CROP))(box);
        }
        // Fill strokes of width w every s cover w x gap / s of the cell; min_gap keeps white
        // paper between neighbours whatever the tone asks.
        const double wf = family_width_mm(Family::Fill) * mm;
        // In rows (band_height > 0): the strokes are also cut where the elevation crosses a
        // level every band_height (ground units, as every length here), band_gap above each
        // level, and laid band_ragged denser than the tone asks; each is then shortened from
        // its lower end by a random share so that the cell's ink is the tone's exactly: the
        // rows start together on their level line and end raggedly.
        const double band = q.band;
        double drawn = 1;
        bool rows = false;
        if (band > 0) {
            // The grade of the elevation the rows are cut on, differenced over a millimetre:
            // rows where it is at least band_slope (walls), long strokes on slabs.
            const double h = 0.5 * mm;
            const double gx = (f.elevation(Point{c.x + h, c.y}) - f.elevation(Point{c.x - h, c.y})) / (2 * h);
            const double gy = (f.elevation(Point{c.x, c.y + h}) - f.elevation(Point{c.x, c.y - h})) / (2 * h);
            const double grade = std::hypot(gx, gy);
            rows = grade * 100 >= q.band_slope;
            if (rows) {
                const double row = band / grade, cut = q.band_gap;  // a row's length on the ground
                drawn = std::max(0.25, row > cut ? 1 - cut / row : 0.0) / (1 + q.band_ragged);
            }
        }
        const double want = target - cross_cover;
        const double s = std::max(wf * gap * drawn / want, wf + q.min_gap);
        // In rows, the strokes are broken at twice their length: the rows break them too.
        const Arrangement lines = Crop(
            noisy_lines("fill", theta, s, rows ? 2 * len : len, q.jitter, gap, f.slope, q.slope_min),
            CROP);
        // Each stroke laid on the fall line at its middle (where the partition gave no
        // orientation), else on the cell's direction: the jitter of the break points moves
        // strokes, it does not tilt them (tilted, sparse strokes read as zigzags).
        const Arrangement fill = AlignToField(lines, follow ? Fallback(f.fall_line, Field(theta)) : Field(theta));
        if (!rows) {
            out.append(fill(box));  // the cell as a region, made once
            return out;
        }
        Curves hanging = CutAtLevels(fill, levels, band, q.band_gap, 0.5 * mm)(box);
        shorten_to_ink(hanging, want * box.area() / wf, theta, kShortestStroke * wf);
        out.append(std::move(hanging));
        return out;
    };
    return MapToFaces(hatch_cell, grid);
}

void check_fray(const ParamValues& p) {
    if (!(p.at("fray_beyond") <= 1)) {
        std::ostringstream m;
        m << "style: --param fray_beyond=" << p.at("fray_beyond") << " must lie between 0 and 1";
        throw Error(Code::Usage, m.str());
    }
    if (!(p.at("fray_min") >= 0) || !(p.at("fray_max") >= p.at("fray_min"))) {
        std::ostringstream m;
        m << "style: --param fray_min=" << p.at("fray_min") / p.at(kGroundPerMm) << " and fray_max="
          << p.at("fray_max") / p.at(kGroundPerMm) << " must satisfy 0 <= fray_min <= fray_max";
        throw Error(Code::Usage, m.str());
    }
}

Arrangement frayed(const ControlFields& f, const ParamValues& p, Arrangement a) {
    // The cross strokes are only drawn back from the rim: drawn on past it, a texture with no
    // fall line to follow reads as stray hairs round the rock. The fill strokes end on both
    // sides of it (fray_beyond of them past it).
    const double lo = p.at("fray_min"), hi = p.at("fray_max"), beyond = p.at("fray_beyond");
    const tex::LabelId cross = tex::intern_label("cross");
    return Arrangement([a = std::move(a), across = f.density, lo, hi, beyond, cross](const Region& r) {
        Curves strokes, crosses;
        Curves all = a(r);
        strokes.curves.reserve(all.curves.size());
        for (Curve& c : all.curves) (c.labels.has(cross) ? crosses : strokes).curves.push_back(std::move(c));
        Curves out = FrayedCrop(std::move(strokes), r, lo, hi, across, {"ridge", "cliff"}, beyond);
        out.append(FrayedCrop(std::move(crosses), r, lo, hi, across, {"ridge", "cliff"}, 0));
        return out;
    });
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
