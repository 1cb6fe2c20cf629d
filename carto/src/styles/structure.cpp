// The structure of the rock (the rock style's blocks, carto/blocks.hpp): crests and couloirs
// as crease lines of the elevation, cliff tops as a level line of the slope, the partition's
// given lines first, crest lines widened above walls, and the strokes hanging from them.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "carto/blocks.hpp"
#include "hanging.hpp"

namespace carto::blocks {
using namespace tex;

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

// The length of a curve (round a closed one).
double curve_length(const Curve& c) {
    double length = 0;
    const std::size_t n = c.points.size();
    for (std::size_t i = 0; i + 1 < n + (c.closed ? 1 : 0); ++i) length += distance(c.points[i], c.points[(i + 1) % n]);
    return length;
}

// Lines traced on a lattice of `cell`, smoothed over about crest_smoothing, the pieces at
// least `min_length` long, labelled.
Curves structure_pieces(const Curves& traced, const ParamValues& p, double cell, double min_length,
                        const std::string& label) {
    const int half = std::max(1, int(std::lround(p.at("crest_smoothing") / cell)));
    Curves out;
    for (Curve& c : MovingAverage(traced, half).curves) {
        if (c.points.size() < 2 || curve_length(c) < min_length) continue;
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

namespace {
// A cliff edge runs across the slope: the cosine of the angle between its normal and the fall
// line is at least this (0.5: within 60 degrees of the level line of the elevation).
constexpr double kAcrossSlope = 0.5;

// The edges of the cliff bands around a face: the level line slope = cliff_slope of the
// smoothed elevation where the slope breaks by cliff_break, the band on the line's left.
// Its runs along which the band lies lower are the tops (the ground falls into the band);
// those along which it lies higher are the feet (the band falls onto gentler ground).
std::pair<Curves, Curves> cliff_edges(const ControlFields& f, const ParamValues& p, const Region& region) {
    const double cell = std::max(p.at("crest_smoothing"), dem_cell(p)) / 4;
    // The slope of the smoothed elevation, differenced over cliff_smoothing either side: the
    // DEM's own slope wanders round every cell-sized bump, and its level line with it.
    const double h = p.at("cliff_smoothing");
    const Field slope = tex::Norm(tex::Gradient(f.elevation, h)) * Field(100.0);
    // The fall line over 1 mm on paper, which the drawing's strokes follow.
    const tex::VectorField gradient = tex::Gradient(f.elevation, p.at(kGroundPerMm));
    const Curves levels = IsoLines(slope, p.at("cliff_slope"), cell)(grown_box(p, region));
    Curves runs[2];  // tops, feet
    for (const Curve& c : levels.curves) {
        // A closed line is read from its smallest point, not from where its tracing started
        // (which depends on the box), and kept closed when it is one kind of edge all round.
        std::vector<Point> pts = c.points;
        if (c.closed) {
            std::rotate(pts.begin(), std::min_element(pts.begin(), pts.end()), pts.end());
            pts.push_back(pts.front());
        }
        // Each segment's kind, read once: 0 a top, 1 a foot, -1 neither.
        std::vector<int> kind_of(pts.size() > 0 ? pts.size() - 1 : 0, -1);
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
            const Point a = pts[i], b = pts[i + 1];
            const double l = distance(a, b);
            if (!(l > 0)) continue;
            const Point mid = (a + b) / 2, left{-(b - a).y / l, (b - a).x / l};
            // Across the slope: the ground rises into the band (a foot) or falls into it (a
            // top) within kAcrossSlope of straight; a run of the level line down the side of a
            // rib or a couloir is neither. NaN: no edge.
            const Point g = gradient(mid);
            const double rise = dot(left, g) / std::hypot(g.x, g.y);
            const int kind = rise <= -kAcrossSlope ? 0 : rise >= kAcrossSlope ? 1 : -1;
            // A break of slope: steeper in the band than beyond the line by cliff_break (a
            // slope that only hovers round cliff_slope, as on an even flank, is no edge).
            if (kind >= 0 && !(slope(mid + left * h) - slope(mid - left * h) < p.at("cliff_break"))) kind_of[i] = kind;
        }
        for (int kind = 0; kind < 2; ++kind) {
            Curves& out = runs[kind];
            const std::size_t before = out.curves.size();
            std::vector<Point> run;
            auto flush = [&] {
                if (run.size() >= 2) out.append(tex::Polyline(run));
                run.clear();
            };
            for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
                if (kind_of[i] == kind) {
                    if (run.empty()) run.push_back(pts[i]);
                    run.push_back(pts[i + 1]);
                } else {
                    flush();
                }
            }
            flush();
            if (c.closed && out.curves.size() == before + 1 && out.curves.back().points.size() == pts.size()) {
                out.curves.back().points.pop_back();
                out.curves.back().closed = true;
            }
        }
    }
    return {structure_pieces(runs[0], p, cell, p.at("cliff_min_length"), "cliff"),
            structure_pieces(runs[1], p, cell, p.at("cliff_min_length"), "cliff_foot")};
}
}  // namespace

tex::Curves cliff_tops(const ControlFields& f, const ParamValues& p, const Region& region) {
    return cliff_edges(f, p, region).first;
}

tex::Curves cliff_feet(const ControlFields& f, const ParamValues& p, const Region& region) {
    return cliff_edges(f, p, region).second;
}

tex::Curves seam_below(const tex::Curves& feet, double width) {
    Curves out;
    for (const Curve& c : feet.curves) {
        const std::size_t n = c.points.size();
        if (n < 2) continue;
        Curve k = c;
        for (std::size_t i = 0; i < n; ++i) {
            // The tangent from the neighbours (round a closed curve); the band lies on the
            // left, the ground below on the right.
            const std::size_t a = c.closed ? (i + n - 1) % n : (i > 0 ? i - 1 : 0);
            const std::size_t b = c.closed ? (i + 1) % n : std::min(i + 1, n - 1);
            const Point t = c.points[b] - c.points[a];
            const double l = std::hypot(t.x, t.y);
            if (l > 0) k.points[i] = c.points[i] + Point{t.y / l, -t.x / l} * (width / 2);
        }
        out.curves.push_back(std::move(k));
    }
    return out;
}

Structure structure_lines(const ControlFields& f, const ParamValues& p, const Region& region) {
    Structure s;
    const double cell = std::max(p.at("crest_smoothing"), dem_cell(p)) / 2, snap = p.at("crest_smoothing");
    const double bend = p.at("crease_bend") / p.at(kGroundPerMm);
    const Region box = grown_box(p, region);
    std::tie(s.cliffs, s.feet) = cliff_edges(f, p, region);
    // Crests and couloirs from one sampling of the elevation, told apart by their label.
    Curves crests, couloirs;
    for (Curve& c : Creases(f.elevation, CreaseKind::Both, cell, bend)(box).curves) {
        Curves& to = c.labels.has("ridge") ? crests : couloirs;
        c.labels = tex::Labels();
        to.curves.push_back(std::move(c));
    }
    // Crests: not along a cliff top (drawn as such).
    s.ridges = structure_pieces(Apart(Constant(crests), s.cliffs, snap)(box), p, cell, p.at("crease_min_length"),
                                "ridgeline");
    s.couloirs = structure_pieces(couloirs, p, cell, p.at("crease_min_length"), "couloir");
    return s;
}

Structure given_first(const ParamValues& p, const Structure& s, const Region& region) {
    const double snap = p.at("crest_smoothing");
    auto apart = [&](const Curves& lines, const std::string& given, double min_length) {
        const Curves on_border = border_lines(region, given);
        if (on_border.empty()) return lines;
        Curves out;
        for (Curve& c : Apart(Constant(lines), on_border, snap)(region).curves)
            if (curve_length(c) >= min_length) out.curves.push_back(std::move(c));
        return out;
    };
    return {apart(s.ridges, "ridge", p.at("crease_min_length")), apart(s.couloirs, "valley", p.at("crease_min_length")),
            apart(s.cliffs, "cliff", p.at("cliff_min_length")), s.feet};
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
constexpr double kTaperWidthMm = 0.1;  // the widest offset of a crest line's shadow edge (under the 0.12 mm stroke)
constexpr double kTaperMinMm = 0.05;   // an offset under this draws no shadow edge (it would hardly show)
constexpr double kTaperEndMm = 1.0;    // the width grows from nothing at a line's end over this
constexpr double kTaperFull = 2.0 / 3;  // the wall (share of a full one) from which the width is whole
constexpr double kTaperFall = 1.5;     // the fall (per length) over 1 mm on paper of a full wall below
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
        std::vector<double> width(n, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
            const Point t = c.points[std::min(i + 1, n - 1)] - c.points[i > 0 ? i - 1 : 0];
            const double l = std::hypot(t.x, t.y);
            if (l == 0) continue;
            Point nrm{-t.y / l, t.x / l};
            const double sl = f.shade(c.points[i] + nrm * (0.5 * mm)), sr = f.shade(c.points[i] - nrm * (0.5 * mm));
            if (std::isnan(sl) || (!std::isnan(sr) && sr > sl)) nrm = -nrm;
            const double z0 = f.elevation(c.points[i]), z1 = f.elevation(c.points[i] + nrm * mm);
            normal[i] = nrm;
            const double wall = std::isnan(z0) || std::isnan(z1) ? 0.0 : clamp01((z0 - z1) / (kTaperFall * mm));
            const double from_end = clamp01(std::min(at[i], total - at[i]) / (kTaperEndMm * mm));
            width[i] = kTaperWidthMm * mm * std::min(1.0, wall / kTaperFull) * from_end;
        }
        // The shadow edge: one stroke beside the line, offset by the width, which follows the
        // wall and grows from nothing at the ends. The offset stays under the stroke's width,
        // so on paper the two strokes are one shape, as wide as the wall below is high.
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
            if (!(width[i] >= kTaperMinMm * mm) || (!run.empty() && dot(normal[i], normal[i - 1]) <= 0)) {
                flush();
                if (!(width[i] >= kTaperMinMm * mm)) continue;
            }
            run.push_back(c.points[i] + normal[i] * width[i]);
        }
        flush();
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

}  // namespace carto::blocks
