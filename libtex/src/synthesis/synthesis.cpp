// SynthesizeAlongCurve: offsets (seed 002, 4.1), stitching (4.2), contours (4.3), the band
// along the curve, and the rectangle (6.2).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "libtex/error.hpp"
#include "libtex/random.hpp"
#include "synthesis_internal.hpp"

namespace tex {
namespace synth {
namespace {

// Offsets of the pieces (4.1): least squares of sum_s m_s (d_{s+1} - d_s - tau_s)^2 with the
// first offset (and, on an open curve, the last) held at zero, by conjugate gradients (the
// matrix is a weighted path or cycle Laplacian; a tiny ridge keeps pieces joined by no
// portal at the centre line).
std::vector<double> offsets(const std::vector<double>& m, const std::vector<double>& tau, std::size_t n,
                            bool cyclic) {
    std::vector<double> x(n, 0.0);
    if (n < 2) return x;
    std::vector<char> fixed(n, 0);
    fixed[0] = 1;
    if (!cyclic) fixed[n - 1] = 1;
    const double ridge = 1e-6;
    auto apply = [&](const std::vector<double>& v, std::vector<double>& out) {
        out.assign(n, 0.0);
        for (std::size_t i = 0; i < n; ++i) out[i] = ridge * v[i];
        for (std::size_t s = 0; s < m.size(); ++s) {
            const std::size_t a = s, b = (s + 1) % n;
            const double d = m[s] * (v[b] - v[a]);
            out[b] += d;
            out[a] -= d;
        }
        for (std::size_t i = 0; i < n; ++i)
            if (fixed[i]) out[i] = 0;
    };
    std::vector<double> rhs(n, 0.0);
    for (std::size_t s = 0; s < m.size(); ++s) {
        rhs[(s + 1) % n] += m[s] * tau[s];
        rhs[s] -= m[s] * tau[s];
    }
    for (std::size_t i = 0; i < n; ++i)
        if (fixed[i]) rhs[i] = 0;
    std::vector<double> r = rhs, p = rhs, ap;
    double rr = 0;
    for (double v : r) rr += v * v;
    const double stop = 1e-24 * std::max(1.0, rr);
    for (std::size_t it = 0; it < 10 * n && rr > stop; ++it) {
        apply(p, ap);
        double pap = 0;
        for (std::size_t i = 0; i < n; ++i) pap += p[i] * ap[i];
        if (pap <= 0) break;
        const double alpha = rr / pap;
        double rr2 = 0;
        for (std::size_t i = 0; i < n; ++i) {
            x[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
            rr2 += r[i] * r[i];
        }
        for (std::size_t i = 0; i < n; ++i) p[i] = r[i] + (rr2 / rr) * p[i];
        rr = rr2;
    }
    return x;
}

// A monotone map of heights: piecewise linear through the knots (from -> to), a shift
// beyond them; the identity without knots. Knots and images increase strictly, so the map
// is increasing and the deformation below cannot fold a piece.
struct HeightMap {
    std::vector<double> from, to;
    double operator()(double y) const {
        if (from.empty()) return y;
        if (y <= from.front()) return y + (to.front() - from.front());
        if (y >= from.back()) return y + (to.back() - from.back());
        const std::size_t k = std::size_t(std::upper_bound(from.begin(), from.end(), y) - from.begin());
        const double f = (y - from[k - 1]) / (from[k] - from[k - 1]);
        return to[k - 1] + f * (to[k] - to[k - 1]);
    }
};

void resample_into(std::vector<Point>& out, const Point& a, const Point& b, double step) {
    const int n = std::max(1, int(std::ceil(distance(a, b) / step)));
    for (int i = 1; i < n; ++i) out.push_back(a + (b - a) * (double(i) / n));
}

// Points at most `step` apart along a polyline. With a period (the length of a closed
// curve), x is an angle-like coordinate: each segment goes the short way round.
std::vector<Point> resampled(const std::vector<Point>& pts, bool closed, double step, double period = 0) {
    std::vector<Point> out;
    auto next = [&](const Point& a, Point b) {
        if (period > 0) {
            const double d = b.x - a.x;
            if (d > 0.5 * period) b.x -= period;
            if (d < -0.5 * period) b.x += period;
        }
        resample_into(out, a, b, step);
    };
    for (std::size_t i = 0; i < pts.size(); ++i) {
        out.push_back(pts[i]);
        if (i + 1 < pts.size()) next(pts[i], pts[i + 1]);
        else if (closed) next(pts[i], pts[0]);
    }
    return out;
}

double smoothstep(double t) {
    t = std::clamp(t, 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// How far from a seam its chains turn (times the band height), and by how much at most.
constexpr double kSeamReach = 1.0 / 6.0;
constexpr double kMaxSeamTurn = 0.8;  // radians (46 degrees) each side

// The direction of a polyline at one end, over `reach` of its length (towards the end).
Point end_direction(const std::vector<Point>& pts, bool at_end, double reach) {
    const std::size_t n = pts.size();
    const Point tip = at_end ? pts[n - 1] : pts[0];
    Point other = tip;
    double walked = 0;
    for (std::size_t k = 1; k < n; ++k) {
        const Point a = at_end ? pts[n - k] : pts[k - 1], b = at_end ? pts[n - 1 - k] : pts[k];
        walked += distance(a, b);
        other = b;
        if (walked > reach) break;  // past zero-length steps at least
    }
    const Point d = at_end ? tip - other : other - tip;
    const double l = norm(d);
    return l > 0 ? d / l : Point{0, 0};
}

// Turns the points of `pts` within `reach` (along the line) of one end about that end, by
// `angle` at the end fading to 0 at `reach`.
void turn_near_end(std::vector<Point>& pts, bool at_end, double angle, double reach) {
    const std::size_t n = pts.size();
    const Point centre = at_end ? pts[n - 1] : pts[0];
    double walked = 0;
    for (std::size_t k = 1; k < n; ++k) {
        const std::size_t i = at_end ? n - 1 - k : k, prev = at_end ? i + 1 : i - 1;
        walked += distance(pts[prev], pts[i]);
        if (walked >= reach) break;
        const double w = (1 - smoothstep(walked / reach)) * angle;
        const double c = std::cos(w), s = std::sin(w);
        const Point d = pts[i] - centre;
        pts[i] = centre + Point{c * d.x - s * d.y, s * d.x + c * d.y};
    }
}

// The seam where chain `a` ends and chain `b` starts (the same point): both turn onto the
// average of their directions there. Each turns over at most a third of its own length, so
// the two ends of a short chain do not meet.
void smooth_seam(std::vector<Point>& a, std::vector<Point>& b, double reach) {
    auto length = [](const std::vector<Point>& p) {
        double l = 0;
        for (std::size_t i = 1; i < p.size(); ++i) l += distance(p[i - 1], p[i]);
        return l;
    };
    if (a.size() < 3 || b.size() < 3) return;
    const double ra = std::min(reach, length(a) / 3), rb = std::min(reach, length(b) / 3);
    // The directions of the two segments meeting at the seam.
    const Point ta = end_direction(a, true, 0), tb = end_direction(b, false, 0);
    const Point sum = ta + tb;
    if (norm(sum) < 1e-9 || norm(ta) == 0 || norm(tb) == 0) return;  // a cusp: left as it is
    const Point avg = sum / norm(sum);
    const double turn_a = std::atan2(cross(ta, avg), dot(ta, avg)), turn_b = std::atan2(cross(tb, avg), dot(tb, avg));
    if (std::abs(turn_a) > kMaxSeamTurn || std::abs(turn_b) > kMaxSeamTurn) return;  // a corner meant to be there
    if (std::abs(turn_a) < 1e-9 && std::abs(turn_b) < 1e-9) return;  // already smooth: left bit for bit
    turn_near_end(a, true, turn_a, ra);
    turn_near_end(b, false, turn_b, rb);
}

// Places, stitches and links the pieces of `seq` in the (U, V) plane of the band: U from 0 to
// `length`, V around 0. Returns closed contours, inside on the left.
std::vector<std::vector<Point>> lay_out(const std::vector<Piece>& P, const std::vector<std::vector<Join>>& J,
                                        const std::vector<int>& seq, bool cyclic, double length, double H) {
    const std::size_t n = seq.size();
    const std::size_t nseams = cyclic ? n : n - 1;
    std::vector<double> m(nseams), tau(nseams);
    for (std::size_t s = 0; s < nseams; ++s) {
        m[s] = double(P[seq[s]].yr.size());
        tau[s] = J[seq[s]][seq[(s + 1) % n]].tau;
    }
    const std::vector<double> delta = offsets(m, tau, n, cyclic);
    // Stitching (4.2): both sides of a seam move their portal end points to the average.
    std::vector<std::vector<double>> target(nseams);
    for (std::size_t s = 0; s < nseams; ++s) {
        const Piece& a = P[seq[s]];
        const Piece& b = P[seq[(s + 1) % n]];
        for (std::size_t k = 0; k < a.yr.size(); ++k)
            target[s].push_back(0.5 * (a.yr[k] + delta[s] + b.yl[k] + delta[(s + 1) % n]));
    }
    std::vector<double> X(n + 1, 0.0);
    for (std::size_t p = 0; p < n; ++p) X[p + 1] = X[p] + P[seq[p]].width();
    const double scale = length / X[n];
    const double step = H / 16;

    // Deformed chains, and the chain leaving each seam end point.
    struct Placed {
        std::vector<Point> pts;
        long end_seam = -1;
        int end_k = -1;
    };
    std::vector<Placed> placed;
    std::map<std::pair<long, int>, std::size_t> leaving;
    std::vector<std::vector<Point>> contours;
    for (std::size_t p = 0; p < n; ++p) {
        const Piece& pc = P[seq[p]];
        const long ls = p > 0 ? long(p) - 1 : (cyclic ? long(n) - 1 : -1);
        const long rs = p + 1 < n ? long(p) : (cyclic ? long(p) : -1);
        HeightMap gl, gr;
        if (ls >= 0)
            for (std::size_t k = 0; k < pc.yl.size(); ++k) {
                gl.from.push_back(pc.yl[k] + delta[p]);
                gl.to.push_back(target[ls][k]);
            }
        if (rs >= 0)
            for (std::size_t k = 0; k < pc.yr.size(); ++k) {
                gr.from.push_back(pc.yr[k] + delta[p]);
                gr.to.push_back(target[rs][k]);
            }
        auto deform = [&](const Point& q) {
            const double s = smoothstep((q.x - pc.a) / pc.width());
            const double y = q.y + delta[p];
            return Point{(X[p] + (q.x - pc.a)) * scale, (1 - s) * gl(y) + s * gr(y)};
        };
        auto seam_point = [&](int side, int k) {
            return side == kLeft ? Point{X[p] * scale, target[ls][k]} : Point{X[p + 1] * scale, target[rs][k]};
        };
        for (const Chain& ch : pc.chains) {
            std::vector<Point> fine = resampled(ch.pts, ch.whole(), step);
            std::vector<Point> out;
            out.reserve(fine.size());
            for (const Point& q : fine) out.push_back(deform(q));
            if (ch.whole()) {
                contours.push_back(std::move(out));
                continue;
            }
            out.front() = seam_point(ch.start_side, ch.start_k);
            out.back() = seam_point(ch.end_side, ch.end_k);
            Placed pl;
            pl.pts = std::move(out);
            pl.end_seam = ch.end_side == kLeft ? ls : rs;
            pl.end_k = ch.end_k;
            leaving[{ch.start_side == kLeft ? ls : rs, ch.start_k}] = placed.size();
            placed.push_back(std::move(pl));
        }
    }
    // Tangents (4.2): the chain arriving at a seam point and the chain leaving it agree on the
    // point already; each now turns, over a short stretch next to it, onto the average of the
    // two directions, so the contour has no kink at the seam. The turn fades out smoothly away
    // from the seam and is at most kMaxSeamTurn; the piece keeps its shape elsewhere.
    for (std::size_t c = 0; c < placed.size(); ++c) {
        const auto it = leaving.find({placed[c].end_seam, placed[c].end_k});
        if (it == leaving.end()) continue;  // reported below
        smooth_seam(placed[c].pts, placed[it->second].pts, kSeamReach * H);
    }
    // Contours (4.3): follow each chain into the one leaving where it ends.
    std::vector<char> used(placed.size(), 0);
    for (std::size_t c0 = 0; c0 < placed.size(); ++c0) {
        if (used[c0]) continue;
        std::vector<Point> ring;
        for (std::size_t c = c0; !used[c];) {
            used[c] = 1;
            ring.insert(ring.end(), placed[c].pts.begin(), placed[c].pts.end() - 1);
            const auto it = leaving.find({placed[c].end_seam, placed[c].end_k});
            if (it == leaving.end()) throw Error("SynthesizeAlongCurve", "internal: an open portal remains");
            c = it->second;
        }
        contours.push_back(std::move(ring));
    }
    return contours;
}

// The band along a curve: the curve resampled at equal steps, with normals smoothed over
// half the band height so that the frames turn smoothly.
class Band {
public:
    Band(std::vector<Point> pts, bool closed, double H) : closed_(closed) {
        if (closed) pts.push_back(pts.front());
        std::vector<double> acc{0.0};
        for (std::size_t i = 1; i < pts.size(); ++i) acc.push_back(acc.back() + distance(pts[i - 1], pts[i]));
        length_ = acc.back();
        const std::size_t n = std::size_t(std::clamp(std::ceil(length_ / (H / 8)), 16.0, 200000.0));
        ds_ = length_ / double(n);
        std::size_t seg = 0;
        for (std::size_t i = 0; i <= n; ++i) {
            const double s = i == n ? length_ : ds_ * double(i);
            while (seg + 2 < acc.size() && acc[seg + 1] < s) ++seg;
            const double span = acc[seg + 1] - acc[seg];
            const double f = span > 0 ? std::clamp((s - acc[seg]) / span, 0.0, 1.0) : 0.0;
            p_.push_back(pts[seg] + (pts[seg + 1] - pts[seg]) * f);
        }
        if (closed) p_.back() = p_.front();
        std::vector<Point> t(n + 1);
        for (std::size_t i = 0; i <= n; ++i) {
            const std::size_t a = i > 0 ? i - 1 : (closed ? n - 1 : 0);
            const std::size_t b = i < n ? i + 1 : (closed ? 1 : n);
            t[i] = p_[b] - p_[a];
            const double l = norm(t[i]);
            t[i] = l > 0 ? t[i] / l : Point{1, 0};
        }
        const long r = long(std::ceil(0.5 * H / ds_));
        std::vector<Point> sm(n + 1);
        for (long i = 0; i <= long(n); ++i) {
            Point sum{0, 0};
            for (long d = -r; d <= r; ++d) {
                long j = i + d;
                if (closed) j = ((j % long(n)) + long(n)) % long(n);
                else j = std::clamp(j, 0L, long(n));
                sum += t[std::size_t(j)];
            }
            const double l = norm(sum);
            sm[std::size_t(i)] = l > 0 ? sum / l : t[std::size_t(i)];
        }
        for (const Point& d : sm) n_.push_back({-d.y, d.x});
        if (closed) n_.back() = n_.front();
        // Where (u, v) -> p(u) + v n(u) stops being one-to-one: its Jacobian is
        // dot(t_raw, t_smooth) - v * (turn rate of n), per sample.
        for (std::size_t i = 0; i < n; ++i) {
            align_.push_back(dot(t[i], sm[i]));
            turn_.push_back(norm(n_[i + 1] - n_[i]) / ds_);
        }
    }
    // The sample where a pattern reaching `reach` from the curve comes closest to folding,
    // and its margin (<= 0: the band folds there).
    std::pair<double, Point> fold_margin(double reach) const {
        double worst = std::numeric_limits<double>::infinity();
        Point where = p_.front();
        for (std::size_t i = 0; i < align_.size(); ++i) {
            const double m = align_[i] - reach * turn_[i];
            if (m < worst) {
                worst = m;
                where = p_[i];
            }
        }
        return {worst, where};
    }
    double length() const { return length_; }
    Point at(double u, double v) const {
        if (closed_) {
            u = std::fmod(u, length_);
            if (u < 0) u += length_;
        } else {
            u = std::clamp(u, 0.0, length_);
        }
        const std::size_t n = p_.size() - 1;
        const std::size_t i = std::min(n - 1, std::size_t(u / ds_));
        const double f = std::clamp(u / ds_ - double(i), 0.0, 1.0);
        const Point p = p_[i] + (p_[i + 1] - p_[i]) * f;
        Point nn = n_[i] + (n_[i + 1] - n_[i]) * f;
        const double l = norm(nn);
        nn = l > 0 ? nn / l : n_[i];
        return p + nn * v;
    }

private:
    bool closed_;
    double length_ = 0, ds_ = 1;
    std::vector<Point> p_, n_;
    std::vector<double> align_, turn_;
};

void check_options(const SynthesisOptions& o, const std::string& op) {
    auto bad = [&](const std::string& what) { throw Error(op, what); };
    if (o.components && *o.components < 1)
        bad("components must be at least 1 (or free), not " + std::to_string(*o.components));
    if (o.holes && *o.holes < 0) bad("holes must be 0 or more (or free), not " + std::to_string(*o.holes));
    if (!std::isfinite(o.autocorrelation) || o.autocorrelation < 0)
        bad("autocorrelation must be a finite weight >= 0, not " + std::to_string(o.autocorrelation));
    if (o.slicing == Slicing::Uniform && (o.slicing_lines < 1 || o.slicing_lines > 1000))
        bad("slicing_lines must be between 1 and 1000, not " + std::to_string(o.slicing_lines));
    if (o.event_grouping && !(*o.event_grouping > 0 && *o.event_grouping <= 1))
        bad("event_grouping must be in (0, 1] or unset (chosen from the exemplar), not " +
            std::to_string(*o.event_grouping));
    if (!std::isfinite(o.thin_portal) || o.thin_portal < 0)
        bad("thin_portal must be a finite width >= 0, not " + std::to_string(o.thin_portal));
    if (!(o.alpha >= 0 && o.alpha <= 1)) bad("alpha must be in [0, 1], not " + std::to_string(o.alpha));
    if (!(o.length_tolerance > 0 && o.length_tolerance < 1))
        bad("length_tolerance must be in (0, 1), not " + std::to_string(o.length_tolerance));
    if (!(o.max_length_deviation >= o.length_tolerance && o.max_length_deviation < 1))
        bad("max_length_deviation must be in [length_tolerance, 1), not " + std::to_string(o.max_length_deviation));
    if (!std::isfinite(o.randomness) || o.randomness < 0)
        bad("randomness must be a finite value >= 0, not " + std::to_string(o.randomness));
}

// A grouping as a user would type it (0.2, 0.07).
std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// One slicing of the exemplar and what the solver made of it.
struct Attempt {
    double grouping = 0;
    std::vector<double> cuts;
    std::vector<Piece> pieces;
    std::vector<std::vector<Join>> joins;
    SynthesisReport report;
    std::optional<Solution> solution;
};

Attempt attempt(const Exemplar& ex, const SynthesisOptions& o, double grouping, std::vector<double> cuts,
                SolveInput in, const std::string& op) {
    Attempt a;
    a.grouping = grouping;
    a.cuts = std::move(cuts);
    a.pieces = make_pieces(ex, a.cuts);
    a.joins = join_table(a.pieces, in.band_height, o.alpha);
    a.report.pieces_in_exemplar = int(a.pieces.size());
    a.report.target_length = in.length;
    a.report.event_grouping = o.slicing == Slicing::Topology ? grouping : 0.0;
    in.pieces = &a.pieces;
    in.joins = &a.joins;
    a.solution = solve(in, a.report, op);
    return a;
}

// When nothing met the request: what else would, tried only now (the error path), so that
// the error can name the option to change.
std::string what_to_change(const Exemplar& ex, const SynthesisOptions& o, const std::vector<Attempt>& tried,
                           const SolveInput& in, const std::string& op) {
    auto cut_before = [&](const std::vector<double>& cuts) {
        for (const Attempt& a : tried)
            if (a.cuts == cuts) return true;
        return false;
    };
    if (o.slicing == Slicing::Topology && o.event_grouping) {
        // An explicit grouping: would the automatic choice meet it?
        for (double g : automatic_groupings(ex)) {
            std::vector<double> cuts = cut_positions(ex, o, g);
            if (cut_before(cuts)) continue;
            if (attempt(ex, o, g, std::move(cuts), in, op).solution)
                return "; event_grouping=" + number(g) + " meets it (leave event_grouping unset to choose it from "
                       "the exemplar)";
        }
    }
    if (o.slicing == Slicing::Topology) {
        SynthesisOptions u = o;
        u.slicing = Slicing::Uniform;
        // Events only at the exemplar's two ends (a band running straight through): no
        // grouping can cut it anywhere else.
        bool inner = false;
        const double end = kFinestGrouping * ex.width;
        for (double x : topology_events(ex)) inner = inner || (x > end && x < ex.width - end);
        const std::string note =
            inner ? "" : " (the exemplar has no topological event but its ends, so no event_grouping can cut it)";
        if (attempt(ex, u, 0, cut_positions(ex, u, 0), in, op).solution)
            return "; slicing=uniform (slicing_lines=" + std::to_string(o.slicing_lines) + ") meets it" + note;
        if (!o.event_grouping)
            return note + "; try slicing=uniform with more slicing_lines, a larger max_length_deviation, a longer "
                          "exemplar or another constraint";
        return note + "; try another event_grouping, slicing=uniform, a larger max_length_deviation or another "
                      "constraint";
    }
    return "; try more or fewer slicing_lines, slicing=topology, a larger max_length_deviation, another exemplar "
           "or another constraint";
}

}  // namespace
}  // namespace synth

Curves SynthesizeAlongCurve(const Curves& exemplar, const Curves& curve, double band_height,
                            const SynthesisOptions& o, SynthesisReport* report) {
    using namespace synth;
    const std::string op = "SynthesizeAlongCurve";
    if (!std::isfinite(band_height) || band_height <= 0)
        throw Error(op, "band_height must be a finite length > 0, not " + std::to_string(band_height));
    check_options(o, op);
    if (curve.curves.size() != 1)
        throw Error(op, "the curve must be exactly one polyline, not " + std::to_string(curve.curves.size()));
    const Curve& cv = curve.curves.front();
    std::vector<Point> pts;
    for (const Point& p : cv.points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error(op, "the curve has a point that is not finite");
        if (pts.empty() || p != pts.back()) pts.push_back(p);
    }
    if (cv.closed)
        while (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
    if (pts.size() < 2 || (cv.closed && pts.size() < 3)) throw Error(op, "the curve has too few distinct points (two for an open curve, three for a closed one)");
    if (o.closed_pattern && !cv.closed) throw Error(op, "closed_pattern asks for a closed curve; this one is open");
    const Band band(pts, cv.closed, band_height);
    if (!(band.length() > 0)) throw Error(op, "the curve has no length");

    const Exemplar ex = make_exemplar(exemplar, band_height, op);
    SolveInput in;
    in.length = band.length();
    in.band_height = band_height;
    in.cyclic = cv.closed;
    in.options = o;
    if (o.seed) {
        in.key = mix64(*o.seed ^ 0x5eed002ULL);
    } else {
        std::uint64_t h = mix64(GetSeed() ^ 0x5eed002ULL);
        for (const Point& p : pts) h = hash_point(h, p);
        in.key = h;
    }
    // The event grouping: the option when set, else the seed's 0.2 W and then finer ones, the
    // first whose pieces meet the request (a grouping that cuts as the one before is skipped).
    std::vector<double> groupings{0.0};
    if (o.slicing == Slicing::Topology)
        groupings = o.event_grouping ? std::vector<double>{*o.event_grouping} : automatic_groupings(ex);
    std::vector<Attempt> tried;
    for (double g : groupings) {
        std::vector<double> cuts = cut_positions(ex, o, g);
        bool seen = false;
        for (const Attempt& a : tried) seen = seen || a.cuts == cuts;
        if (seen) continue;
        tried.push_back(attempt(ex, o, g, std::move(cuts), in, op));
        tried.back().report.groupings_tried = int(tried.size());
        if (tried.back().solution) break;
    }
    if (!tried.back().solution) {
        std::string pieces = std::to_string(tried.front().pieces.size());
        if (tried.size() > 1)
            pieces += " to " + std::to_string(tried.back().pieces.size()) + " pieces (event_grouping " +
                      number(tried.front().grouping) + " to " + number(tried.back().grouping) + ")";
        else
            pieces += " pieces";
        throw Error(op, no_sequence(in, pieces) + what_to_change(ex, o, tried, in, op));
    }
    const Attempt& chosen = tried.back();
    const std::vector<Piece>& pieces = chosen.pieces;
    const auto& joins = chosen.joins;
    SynthesisReport rep = chosen.report;
    const Solution& sol = *chosen.solution;
    rep.pieces_in_result = int(sol.sequence.size());
    rep.components = sol.components;
    rep.holes = sol.holes;
    rep.closed_pattern = sol.closed_pattern;
    rep.natural_length = sol.length;
    if (report) *report = rep;

    const auto rings = lay_out(pieces, joins, sol.sequence, cv.closed, band.length(), band_height);
    // Bent into the band, the pattern must not fold over itself: refuse a curve that turns
    // too tightly for how far the pattern reaches from it (a margin keeps the polygonal
    // approximation clear of the limit).
    double reach = 0;
    for (const auto& ring : rings)
        for (const Point& q : ring) reach = std::max(reach, std::abs(q.y));
    const auto [margin, where] = band.fold_margin(reach);
    if (margin < 0.1)
        throw Error(op, "the curve turns too tightly for the band near (" + std::to_string(where.x) + ", " +
                            std::to_string(where.y) + "): the pattern reaches " + std::to_string(reach) +
                            " from the curve and would fold over itself; use a smaller band_height or a smoother curve");
    Curves out;
    for (auto& ring : rings) {
        std::vector<Point> fine = resampled(ring, true, band_height / 16, cv.closed ? band.length() : 0.0);
        Curve c;
        c.closed = true;
        c.points.reserve(fine.size());
        for (const Point& q : fine) c.points.push_back(band.at(q.x, q.y));
        out.curves.push_back(std::move(c));
    }
    return out;
}

Curves SynthesizeInRectangle(const Curves& exemplar, double width, double height, double row_height,
                             const SynthesisOptions& o) {
    const std::string op = "SynthesizeInRectangle";
    for (auto [name, v] : {std::pair<const char*, double>{"width", width}, {"height", height}, {"row_height", row_height}})
        if (!std::isfinite(v) || v <= 0) throw Error(op, std::string(name) + " must be a finite length > 0, not " + std::to_string(v));
    if (o.closed_pattern) throw Error(op, "closed_pattern has no meaning in a rectangle");
    try {
        // Along U: a strip of height row_height as long as the rectangle is wide.
        SynthesisOptions o1 = o;
        if (o.seed) o1.seed = mix64(*o.seed + 1);
        const Curves strip = SynthesizeAlongCurve(exemplar, Polyline({{0, 0}, {width, 0}}), row_height, o1);
        // Along V: the strip turned a quarter turn clockwise ((x, y) -> (y, -x)) is the new
        // exemplar, its height the rectangle's width; the result is turned back.
        Curves turned = strip;
        turned.transform(Affine{0, 1, 0, -1, 0, 0});
        SynthesisOptions o2 = o;
        if (o.seed) o2.seed = mix64(*o.seed + 2);
        Curves r = SynthesizeAlongCurve(turned, Polyline({{0, 0}, {height, 0}}), width, o2);
        r.transform(Affine{0, -1, 0.5 * width, 1, 0, 0});
        return r;
    } catch (const Error& e) {
        throw Error(op, e.what());
    }
}

}  // namespace tex
