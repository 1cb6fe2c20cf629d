// Exemplar rings, slicing and pieces (seed 002, sections 3.2, 3.3 and 5).
#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "libtex/error.hpp"
#include "synthesis_internal.hpp"

namespace tex::synth {
namespace {

// Even-odd test of p against a ring.
bool inside_ring(const std::vector<Point>& ring, const Point& p) {
    bool in = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
        const Point& a = ring[i];
        const Point& b = ring[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
    }
    return in;
}

bool segments_cross(const Point& a, const Point& b, const Point& c, const Point& d) {
    const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
    const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
    return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

// Refuses rings that cross each other or themselves (the exemplar must be polygons with
// holes). Quadratic, with a box filter: exemplars are small.
void check_simple(const std::vector<Ring>& rings, const std::string& op) {
    struct Seg {
        Point a, b;
        std::size_t ring, i;
        double xmin, xmax;
    };
    std::vector<Seg> segs;
    for (std::size_t r = 0; r < rings.size(); ++r) {
        const auto& p = rings[r].pts;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const Point& a = p[i];
            const Point& b = p[(i + 1) % p.size()];
            segs.push_back({a, b, r, i, std::min(a.x, b.x), std::max(a.x, b.x)});
        }
    }
    std::sort(segs.begin(), segs.end(), [](const Seg& s, const Seg& t) { return s.xmin < t.xmin; });
    for (std::size_t i = 0; i < segs.size(); ++i) {
        for (std::size_t j = i + 1; j < segs.size() && segs[j].xmin <= segs[i].xmax; ++j) {
            const Seg& s = segs[i];
            const Seg& t = segs[j];
            if (s.ring == t.ring) {
                const std::size_t n = rings[s.ring].pts.size();
                if ((s.i + 1) % n == t.i || (t.i + 1) % n == s.i) continue;
            }
            if (segments_cross(s.a, s.b, t.a, t.b))
                throw Error(op, "the exemplar's outlines cross each other near (" + std::to_string(s.a.x) +
                                    ", " + std::to_string(s.a.y) + "); give polygons with holes");
        }
    }
}

}  // namespace

Exemplar make_exemplar(const Curves& c, double band_height, const std::string& op) {
    Exemplar ex;
    BBox box;
    for (const Curve& cv : c.curves) {
        if (!cv.closed) continue;
        std::vector<Point> pts;
        for (const Point& p : cv.points) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error(op, "the exemplar has a point that is not finite");
            if (pts.empty() || p != pts.back()) pts.push_back(p);
        }
        while (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
        if (pts.size() < 3 || std::abs(signed_area(pts)) == 0) continue;
        for (const Point& p : pts) box.add(p);
        ex.rings.push_back({std::move(pts), false});
    }
    if (ex.rings.empty())
        throw Error(op, "the exemplar" + (c.origin.empty() ? std::string() : " '" + c.origin + "'") +
                            " has no closed curve with an area (it must be polygons with holes)");
    if (box.width() <= 0 || box.height() <= 0) throw Error(op, "the exemplar is flat");
    check_simple(ex.rings, op);
    // Nesting depth by even-odd: rings at odd depth are holes.
    for (std::size_t i = 0; i < ex.rings.size(); ++i) {
        int depth = 0;
        for (std::size_t j = 0; j < ex.rings.size(); ++j)
            if (j != i && inside_ring(ex.rings[j].pts, ex.rings[i].pts[0])) ++depth;
        ex.rings[i].hole = depth % 2 == 1;
    }
    const double s = band_height / box.height();
    const Point c0{box.xmin, box.center().y};
    for (Ring& r : ex.rings) {
        for (Point& p : r.pts) p = (p - c0) * s;
        const bool ccw = signed_area(r.pts) > 0;
        if (ccw == r.hole) std::reverse(r.pts.begin(), r.pts.end());
    }
    ex.width = box.width() * s;
    ex.height = band_height;
    return ex;
}

std::vector<std::pair<double, double>> portals_at(const Exemplar& ex, double c) {
    std::vector<double> ys;
    for (const Ring& r : ex.rings) {
        const auto& p = r.pts;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const Point& a = p[i];
            const Point& b = p[(i + 1) % p.size()];
            if ((a.x - c) * (b.x - c) < 0) ys.push_back(a.y + (b.y - a.y) * (c - a.x) / (b.x - a.x));
        }
    }
    std::sort(ys.begin(), ys.end());
    std::vector<std::pair<double, double>> out;
    for (std::size_t i = 0; i + 1 < ys.size(); i += 2) out.push_back({ys[i], ys[i + 1]});
    return out;
}

namespace {

// Moves a cut off the exemplar's vertices, so that every ring crosses it transversally.
double off_vertices(const Exemplar& ex, double c) {
    const double step = 1e-6 * ex.width;
    for (int tries = 0; tries < 100; ++tries) {
        bool hit = false;
        for (const Ring& r : ex.rings)
            for (const Point& p : r.pts)
                if (std::abs(p.x - c) < 0.5 * step) hit = true;
        if (!hit) return c;
        c += step;
    }
    return c;
}

}  // namespace

// x of the vertices where a column of the exemplar starts, ends, splits or merges: the local
// extrema of x along the rings (runs of equal x count once per side change).
std::vector<double> topology_events(const Exemplar& ex) {
    std::vector<double> ev;
    for (const Ring& r : ex.rings) {
        const auto& p = r.pts;
        const std::size_t n = p.size();
        for (std::size_t i = 0; i < n; ++i) {
            const double x = p[i].x;
            double prev = x, next = x;
            for (std::size_t s = 1; s < n && prev == x; ++s) prev = p[(i + n - s) % n].x;
            for (std::size_t s = 1; s < n && next == x; ++s) next = p[(i + s) % n].x;
            if ((prev > x && next > x) || (prev < x && next < x)) ev.push_back(x);
        }
    }
    std::sort(ev.begin(), ev.end());
    return ev;
}

namespace {

// The shortest decimal strictly between lo and hi (0 <= lo < hi), the closest to their middle
// among those of that length: a grouping a user can type and get the same groups.
double round_between(double lo, double hi) {
    const double mid = 0.5 * (lo + hi);
    for (double step = 0.1; step > 1e-12; step /= 10) {
        double best = -1;
        for (double k = std::floor(lo / step) + 1; k * step < hi; ++k) {
            const double v = k * step;
            if (v > lo && (best < 0 || std::abs(v - mid) < std::abs(best - mid))) best = v;
        }
        if (best > 0) return best;
    }
    return mid;
}

}  // namespace

std::vector<double> automatic_groupings(const Exemplar& ex) {
    std::vector<double> out{kSeedGrouping};
    const std::vector<double> ev = topology_events(ex);
    // The gaps between successive events, as fractions of W, that the seed's grouping does
    // not split, largest first; gaps under kFinestGrouping stay grouped (noise, 5.2.2).
    std::vector<double> gaps;
    for (std::size_t i = 1; i < ev.size(); ++i) gaps.push_back((ev[i] - ev[i - 1]) / ex.width);
    std::sort(gaps.begin(), gaps.end(), std::greater<>());
    std::vector<double> distinct;
    for (double g : gaps)
        if (distinct.empty() || g < distinct.back() * (1 - 1e-9)) distinct.push_back(g);
    // Each grouping between two successive distinct gaps splits one more of them.
    std::vector<double> finer;
    for (std::size_t k = 0; k < distinct.size(); ++k) {
        const double g = distinct[k];
        if (g > kSeedGrouping) continue;
        if (g <= kFinestGrouping) break;
        const double below = k + 1 < distinct.size() ? distinct[k + 1] : 0.0;
        finer.push_back(round_between(below, g));
    }
    // At most kMaxGroupings tries in all, spread evenly over the finer ones (first and last kept).
    const std::size_t room = kMaxGroupings - 1;
    if (finer.size() > room) {
        std::vector<double> kept;
        for (std::size_t i = 0; i < room; ++i) kept.push_back(finer[i * (finer.size() - 1) / (room - 1)]);
        finer = kept;
    }
    out.insert(out.end(), finer.begin(), finer.end());
    return out;
}

std::vector<double> cut_positions(const Exemplar& ex, const SynthesisOptions& o, double grouping) {
    std::vector<double> cuts;
    const double W = ex.width;
    if (o.slicing == Slicing::Uniform) {
        for (int i = 1; i <= o.slicing_lines; ++i) cuts.push_back(W * i / (o.slicing_lines + 1));
    } else {
        const std::vector<double> ev = topology_events(ex);
        std::vector<double> centres;
        std::size_t i = 0;
        while (i < ev.size()) {
            std::size_t j = i + 1;
            double sum = ev[i];
            while (j < ev.size() && ev[j] - ev[j - 1] <= grouping * W) sum += ev[j++];
            centres.push_back(sum / double(j - i));
            i = j;
        }
        for (std::size_t k = 0; k + 1 < centres.size(); ++k) cuts.push_back(0.5 * (centres[k] + centres[k + 1]));
    }
    std::vector<double> kept;
    for (double c : cuts) {
        c = off_vertices(ex, c);
        if (c <= 0 || c >= W || (!kept.empty() && c <= kept.back())) continue;
        if (o.thin_portal > 0) {
            bool thin = false;
            for (const auto& [lo, hi] : portals_at(ex, c))
                if (hi - lo < o.thin_portal) thin = true;
            if (thin) continue;
        }
        kept.push_back(c);
    }
    return kept;
}

namespace {

struct Crossing {
    std::size_t edge;
    double t;
    int side;
    Point at;
    bool entering;
};

Piece cut_piece(const Exemplar& ex, double a, double b) {
    Piece pc;
    pc.a = a;
    pc.b = b;
    for (const Ring& r : ex.rings) {
        const auto& p = r.pts;
        const std::size_t n = p.size();
        std::vector<Crossing> xs;
        for (std::size_t i = 0; i < n; ++i) {
            const Point& u = p[i];
            const Point& v = p[(i + 1) % n];
            for (int side : {kLeft, kRight}) {
                const double c = side == kLeft ? a : b;
                if ((u.x - c) * (v.x - c) < 0) {
                    const double t = (c - u.x) / (v.x - u.x);
                    const bool entering = side == kLeft ? v.x > u.x : v.x < u.x;
                    xs.push_back({i, t, side, {c, u.y + t * (v.y - u.y)}, entering});
                }
            }
        }
        std::sort(xs.begin(), xs.end(), [](const Crossing& s, const Crossing& t) {
            return s.edge < t.edge || (s.edge == t.edge && s.t < t.t);
        });
        if (xs.empty()) {
            if (p[0].x >= a && p[0].x <= b) {
                Chain ch;
                ch.pts = p;
                pc.chains.push_back(std::move(ch));
                if (r.hole) ++pc.desc.holes;
                else ++pc.desc.closed;
            }
            continue;
        }
        for (std::size_t j = 0; j < xs.size(); ++j) {
            const Crossing& s = xs[j];
            if (!s.entering) continue;
            const Crossing& e = xs[(j + 1) % xs.size()];
            Chain ch;
            ch.pts.push_back(s.at);
            std::size_t count = (e.edge + n - s.edge) % n;
            if (count == 0 && !(j + 1 < xs.size())) count = n;  // all crossings on one edge
            for (std::size_t k = 0; k < count; ++k) ch.pts.push_back(p[(s.edge + 1 + k) % n]);
            ch.pts.push_back(e.at);
            ch.start_side = s.side;
            ch.end_side = e.side;
            pc.chains.push_back(std::move(ch));
        }
    }
    // Number the end points of each side bottom to top.
    for (int side : {kLeft, kRight}) {
        std::vector<std::pair<double, std::pair<std::size_t, bool>>> ends;  // y, (chain, is_start)
        for (std::size_t c = 0; c < pc.chains.size(); ++c) {
            const Chain& ch = pc.chains[c];
            if (ch.start_side == side) ends.push_back({ch.pts.front().y, {c, true}});
            if (ch.end_side == side) ends.push_back({ch.pts.back().y, {c, false}});
        }
        std::sort(ends.begin(), ends.end());
        auto& ys = side == kLeft ? pc.yl : pc.yr;
        auto& gs = side == kLeft ? pc.gl : pc.gr;
        for (std::size_t k = 0; k < ends.size(); ++k) {
            Chain& ch = pc.chains[ends[k].second.first];
            const bool start = ends[k].second.second;
            // With the inside on the left, a ring leaves a left cut at the bottom of each
            // portal and a right cut at its top.
            const bool expect_start = (side == kLeft) == (k % 2 == 0);
            if (start != expect_start) throw Error("SynthesizeAlongCurve", "internal: portal orientation");
            const auto& q = ch.pts;
            Point g = start ? q[1] - q[0] : q[q.size() - 1] - q[q.size() - 2];
            const double len = norm(g);
            g = len > 0 ? g / len : Point{side == kLeft ? 1.0 : -1.0, 0.0};
            if (start) ch.start_k = int(k);
            else ch.end_k = int(k);
            ys.push_back(ends[k].first);
            gs.push_back(g);
        }
    }
    // Components: walk each boundary cycle (chain, then up a right portal or down a left one,
    // then the chain leaving there).
    const int nc = int(pc.chains.size());
    Dsu dsu(nc);
    std::vector<int> leaving_l(pc.yl.size(), -1), leaving_r(pc.yr.size(), -1);
    for (int c = 0; c < nc; ++c) {
        const Chain& ch = pc.chains[c];
        if (ch.start_side == kLeft) leaving_l[ch.start_k] = c;
        if (ch.start_side == kRight) leaving_r[ch.start_k] = c;
    }
    for (int c = 0; c < nc; ++c) {
        const Chain& ch = pc.chains[c];
        if (ch.end_side == kLeft) dsu.unite(c, leaving_l[ch.end_k - 1]);
        if (ch.end_side == kRight) dsu.unite(c, leaving_r[ch.end_k + 1]);
    }
    std::vector<int> id_of(nc, -1);
    int next = 0;
    auto id = [&](int chain) {
        int& v = id_of[dsu.find(chain)];
        if (v < 0) v = next++;
        return std::uint8_t(v);
    };
    for (std::size_t k = 0; k < pc.yl.size(); k += 2) pc.desc.left.push_back(id(leaving_l[k]));
    for (std::size_t k = 1; k < pc.yr.size(); k += 2) pc.desc.right.push_back(id(leaving_r[k]));
    if (next > 250) throw Error("SynthesizeAlongCurve", "a piece has more than 250 components; slice the exemplar more coarsely");
    return pc;
}

}  // namespace

std::vector<Piece> make_pieces(const Exemplar& ex, const std::vector<double>& cuts) {
    // The outer sides lie a little outside the exemplar, so that an end of the exemplar that
    // is cut straight (a rail's end) keeps a gap to the piece placed next to it across a seam
    // without portals, instead of touching it.
    const double margin = 0.01 * ex.width;
    std::vector<double> xs{-margin};
    xs.insert(xs.end(), cuts.begin(), cuts.end());
    xs.push_back(ex.width + margin);
    std::vector<Piece> pieces;
    for (std::size_t i = 0; i + 1 < xs.size(); ++i) pieces.push_back(cut_piece(ex, xs[i], xs[i + 1]));
    return pieces;
}

std::vector<std::vector<Join>> join_table(const std::vector<Piece>& pieces, double band_height, double alpha) {
    const std::size_t n = pieces.size();
    std::vector<std::vector<Join>> t(n, std::vector<Join>(n));
    // Positions are compared in tenths of the band height, so that both terms are of the
    // same order for a visible mismatch.
    const double unit = 0.1 * band_height;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < n; ++j) {
            const auto& yr = pieces[i].yr;
            const auto& yl = pieces[j].yl;
            if (yr.size() != yl.size()) continue;
            Join& jn = t[i][j];
            jn.valid = true;
            if (yr.empty()) continue;
            const double m = double(yr.size());
            double tau = 0;
            for (std::size_t k = 0; k < yr.size(); ++k) tau += yr[k] - yl[k];
            tau /= m;
            double dm = 0, dt = 0;
            for (std::size_t k = 0; k < yr.size(); ++k) {
                const double r = (yl[k] + tau - yr[k]) / unit;
                dm += r * r;
                dt += std::abs(1.0 - dot(pieces[i].gr[k], pieces[j].gl[k]));
            }
            jn.tau = tau;
            jn.cost = alpha * dm / m + (1 - alpha) * dt;
        }
    }
    return t;
}

}  // namespace tex::synth
