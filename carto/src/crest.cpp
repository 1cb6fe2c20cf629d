#include "carto/crest.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "carto/error.hpp"
#include "corner_cut.hpp"
#include "libtex/error.hpp"
#include "libtex/parallel.hpp"
#include "libtex/random.hpp"
#include "libtex/svg.hpp"
#include "libtex/synthesis.hpp"

namespace carto {
namespace {

// The project's exemplar: a spine 600 long and 10 high with twelve glyphs of 50, each a
// centred barb (24 wide at the spine, 6 at its blunt tip, so that the tip still prints at
// 1:10000) up, down, both or neither, of different lengths. The uniform slicing below cuts
// exactly between the glyphs, through the spine only, so every portal is the spine itself:
// any sequence of glyphs is one connected band and the solver is free to vary them. The
// extremes are +-50, so the spine lies on the ridge.
constexpr const char* kCrestSvg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="-5 -55 610 110">
<!-- rockhatch crest exemplar: a spine with barbs on both sides, twelve glyphs of 50 -->
<path d="M 0 5 L 63 5 L 72 30 L 78 30 L 87 5 L 113 5 L 122 50 L 128 50 L 137 5 L 263 5 L 272 20 L 278 20 L 287 5
L 313 5 L 322 38 L 328 38 L 337 5 L 413 5 L 422 50 L 428 50 L 437 5 L 513 5 L 522 26 L 528 26 L 537 5
L 563 5 L 572 44 L 578 44 L 587 5 L 600 5 L 600 -5 L 587 -5 L 578 -28 L 572 -28 L 563 -5 L 487 -5 L 478 -46
L 472 -46 L 463 -5 L 437 -5 L 428 -20 L 422 -20 L 413 -5 L 387 -5 L 378 -34 L 372 -34 L 363 -5 L 287 -5
L 278 -50 L 272 -50 L 263 -5 L 187 -5 L 178 -42 L 172 -42 L 163 -5 L 87 -5 L 78 -30 L 72 -30 L 63 -5 L 37 -5
L 28 -50 L 22 -50 L 13 -5 L 0 -5 Z"/>
</svg>
)";
constexpr int kCrestGlyphs = 12;

// Stream of the crest keys, so that a ridge's key differs from any other use of the seed.
constexpr std::uint64_t kCrestStream = 0xc4e57ULL;

// Corner-cutting passes tried in turn on a ridge the band would fold on: none, then rounder
// and rounder curves (each pass moves a corner by at most a quarter of its shorter segment).
constexpr int kSmoothingPasses[] = {0, 2, 4, 6};

bool is_default(const std::string& spec) { return spec == kDefaultCrest; }

// The synthesis options of a crest: one connected component, holes free, uniform slicing
// (seed 002, 5.1). The project's exemplar is cut exactly between its glyphs. A user's
// exemplar is cut every quarter of its height: a crest exemplar is long and its shapes hang
// on a line running through it, so such cuts mostly cross that line alone, and pieces that
// start and end on it can follow one another in any order and number. (The topological
// slicing of 5.2 cuts only where columns split or merge: a spine with barbs has no such
// event, so it would stay one piece that cannot repeat.)
constexpr int kMinUserCuts = 4, kMaxUserCuts = 80;

tex::SynthesisOptions crest_options(const tex::Curves& exemplar, bool default_exemplar) {
    tex::SynthesisOptions o;
    o.components = 1;
    o.holes = std::nullopt;
    o.slicing = tex::Slicing::Uniform;
    if (default_exemplar) {
        o.slicing_lines = kCrestGlyphs - 1;
    } else {
        const tex::BBox b = exemplar.bbox();
        const double cuts = b.height() > 0 ? 4 * b.width() / b.height() : kMinUserCuts;
        o.slicing_lines = int(std::clamp(std::round(cuts), double(kMinUserCuts), double(kMaxUserCuts)));
    }
    return o;
}

double length(const std::vector<Point>& pts) {
    double l = 0;
    for (std::size_t i = 1; i < pts.size(); ++i) l += tex::distance(pts[i - 1], pts[i]);
    return l;
}

// The part of a polyline between arc lengths `from` and `to` (0 <= from < to <= length).
std::vector<Point> between(const std::vector<Point>& pts, double from, double to) {
    std::vector<Point> out;
    double at = 0;
    for (std::size_t i = 1; i < pts.size(); ++i) {
        const double l = tex::distance(pts[i - 1], pts[i]);
        const double a = at, b = at + l;
        at = b;
        if (b <= from || l == 0) continue;
        const auto point = [&](double s) { return pts[i - 1] + (pts[i] - pts[i - 1]) * ((s - a) / l); };
        if (out.empty()) out.push_back(a >= from ? pts[i - 1] : point(from));
        if (b >= to) {
            out.push_back(point(to));
            break;
        }
        out.push_back(pts[i]);
    }
    return out;
}

// Where ridge lines meet, their ornaments would overlap. At a node (ends within
// kNodeTolerance x the band of each other), an end that continues another ridge almost
// straight (kContinuation or more between the two directions leaving the node) is kept; the
// others are cut back along the line, far enough that their band clears the band of the
// nearest other ridge there: band / sin(angle) for an angle under 90 degrees, one band
// beyond, at most kMaxTrim bands. Every ridge line of the partition counts (not only those
// drawn), so windows agree. Returns, per line, the length cut from its start and its end.
constexpr double kNodeTolerance = 0.01;
constexpr double kContinuation = 150.0 * tex::pi / 180.0;
constexpr double kMaxTrim = 3.0;

std::vector<std::pair<double, double>> junction_trims(const Partition& p, double band) {
    struct End {
        std::size_t line;
        bool at_start;
        Point node, out;  // the node and the unit direction leaving it along the line
    };
    std::vector<End> ends;
    for (std::size_t i = 0; i < p.lines.size(); ++i) {
        const LabelledLine& l = p.lines[i];
        if (l.kind != LineKind::Ridge || l.points.size() < 2) continue;
        const double len = length(l.points);
        if (!(len > 0)) continue;
        const double reach = std::min(band, len / 2);  // the direction over one band of line
        for (bool at_start : {true, false}) {
            std::vector<Point> pts = l.points;
            if (!at_start) std::reverse(pts.begin(), pts.end());
            const std::vector<Point> head = between(pts, 0, reach);
            const Point d = head.back() - head.front();
            const double n = tex::norm(d);
            if (n > 0) ends.push_back({i, at_start, pts.front(), d / n});
        }
    }
    std::vector<std::pair<double, double>> trims(p.lines.size(), {0.0, 0.0});
    const double tol = kNodeTolerance * band;
    for (std::size_t a = 0; a < ends.size(); ++a) {
        double nearest = tex::pi;  // smallest angle to another ridge leaving the same node
        bool continued = false;
        for (std::size_t b = 0; b < ends.size(); ++b) {
            if (a == b || tex::distance(ends[a].node, ends[b].node) > tol) continue;
            const double angle = std::acos(std::clamp(tex::dot(ends[a].out, ends[b].out), -1.0, 1.0));
            if (angle >= kContinuation) continued = true;
            nearest = std::min(nearest, angle);
        }
        if (continued || nearest == tex::pi) continue;
        const double trim = nearest >= tex::pi / 2 ? band : std::min(kMaxTrim * band, band / std::sin(nearest));
        (ends[a].at_start ? trims[ends[a].line].first : trims[ends[a].line].second) = trim;
    }
    return trims;
}

}  // namespace

std::int64_t ridge_key(const std::vector<Point>& line) {
    std::uint64_t key = 0x52494447454b4559ULL;  // "RIDGEKEY"
    for (const Point& q : line) key = tex::hash_point(key, q);
    return std::int64_t(key >> 1);
}

Point ridge_anchor(const std::vector<Point>& line) { return std::min(line.front(), line.back()); }

double crest_context(double band_height) { return std::max(1.0, kNodeTolerance) * band_height; }

const std::string& default_crest_svg() {
    static const std::string text = kCrestSvg;
    return text;
}

CrestExemplar load_crest_exemplar(const std::string& spec) {
    const std::string what = "--crest-ornament '" + spec + "'";
    tex::Curves ex;
    if (is_default(spec)) {
        ex = tex::ParseSVG(default_crest_svg(), "the default crest exemplar");
    } else {
        if (!std::filesystem::exists(spec)) throw Error(Code::InputMissing, what + ": no such file");
        try {
            ex = tex::ImportSVG(spec);
        } catch (const tex::Error& e) {
            throw Error(Code::InputMissing, what + ": not an SVG file rockhatch can read (" + e.what() + ")");
        }
    }
    // A trial along a straight line four times as long as the exemplar (at its aspect): an
    // exemplar that holds no polygon, or whose pieces cannot repeat into one connected band,
    // is refused here, before any work, rather than ridge by ridge.
    const tex::SynthesisOptions options = crest_options(ex, is_default(spec));
    try {
        tex::SynthesisOptions trial = options;
        trial.seed = 1;
        const tex::BBox b = ex.bbox();
        const double aspect = b.height() > 0 ? b.width() / b.height() : 1.0;
        tex::SynthesizeAlongCurve(ex, tex::Polyline({{0, 0}, {4 * std::max(1.0, aspect), 0}}), 1.0, trial);
    } catch (const tex::Error& e) {
        throw Error(Code::BadLayer, what + ": cannot make one connected crest band from it (" + e.what() + ")");
    }
    return {std::move(ex), options};
}

CrestResult draw_crests(const Partition& p, const CrestExemplar& exemplar, double band_height, std::uint64_t seed,
                        const std::optional<tex::BBox>& window) {
    if (!(band_height > 0) || !std::isfinite(band_height))
        throw Error(Code::Usage, "--crest-height: the band must be a positive length");
    std::vector<std::size_t> ridges;
    for (std::size_t i = 0; i < p.lines.size(); ++i) {
        const LabelledLine& l = p.lines[i];
        if (l.kind != LineKind::Ridge || l.points.size() < 2) continue;
        if (window) {
            const Point a = ridge_anchor(l.points);
            const tex::BBox& w = *window;
            if (!(a.x >= w.xmin && a.x < w.xmax && a.y >= w.ymin && a.y < w.ymax)) continue;
        }
        ridges.push_back(i);
    }
    const std::vector<std::pair<double, double>> trims = junction_trims(p, band_height);
    enum class Outcome { Drawn, Short, Refused };
    std::vector<Outcome> outcome(ridges.size(), Outcome::Drawn);
    std::vector<CrestOrnament> drawn(ridges.size());
    tex::parallel_for(ridges.size(), [&](std::size_t k) {
        const std::vector<Point>& line = p.lines[ridges[k]].points;
        const auto [cut_start, cut_end] = trims[ridges[k]];
        const double len = length(line);
        if (len - cut_start - cut_end < band_height) {
            outcome[k] = Outcome::Short;
            return;
        }
        const std::vector<Point> pts = cut_start > 0 || cut_end > 0 ? between(line, cut_start, len - cut_end) : line;
        // Keyed by the ridge line itself: the same ridge gets the same ornament whatever
        // order the partition holds its lines in, on any number of threads.
        std::uint64_t key = tex::hash_combine(seed, kCrestStream);
        for (const Point& q : line) key = tex::hash_point(key, q);
        tex::SynthesisOptions o = exemplar.synthesis;
        o.seed = key;
        for (int passes : kSmoothingPasses) {
            try {
                const tex::Curves c = tex::SynthesizeAlongCurve(exemplar.shapes, tex::Polyline(cut_corners(pts, passes)),
                                                                band_height, o);
                drawn[k].ridge = ridges[k];
                drawn[k].id = ridge_key(line);
                for (const auto& cv : c.curves) drawn[k].rings.push_back(cv.points);
                return;
            } catch (const tex::Error&) {
                // Too short for a sequence of pieces, or a turn too tight for the band: try a
                // smoother ridge, then give up on this one (counted in the notes).
            }
        }
        outcome[k] = Outcome::Refused;
    });
    CrestResult r;
    std::size_t too_short = 0, refused = 0;
    for (std::size_t k = 0; k < ridges.size(); ++k) {
        if (outcome[k] == Outcome::Drawn) r.ornaments.push_back(std::move(drawn[k]));
        else if (outcome[k] == Outcome::Short) ++too_short;
        else ++refused;
    }
    std::ostringstream n;
    n << "crest ornaments on " << r.ornaments.size() << " of " << ridges.size() << " ridge line(s)";
    if (too_short)
        n << "; " << too_short << " shorter than the band height (" << band_height
          << ", once cut back where ridges meet) skipped";
    if (refused)
        n << "; " << refused << " skipped: no pattern fits them (too short for the exemplar's pieces, or turning too "
                                "tightly for the band even when smoothed)";
    r.notes.push_back(n.str());
    return r;
}

}  // namespace carto
