// Topology descriptors (seed 002, 3.4) and the topology solver (3.6, 3.7).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "libtex/error.hpp"
#include "libtex/random.hpp"
#include "synthesis_internal.hpp"

namespace tex::synth {
namespace {

int count_ids(const Descriptor& d) {
    int n = 0;
    for (auto v : d.left) n = std::max(n, int(v) + 1);
    for (auto v : d.right) n = std::max(n, int(v) + 1);
    return n;
}

}  // namespace

void join_into(const Descriptor& d, const Descriptor& p, Descriptor& out) {
    // Ids are bytes, so at most 256 per side: the union-find lives on the stack (this runs
    // for every extension the programme tries).
    const int nd = count_ids(d), np = count_ids(p), n = nd + np;
    int parent[512], canon[512];
    char open[512];
    for (int v = 0; v < n; ++v) {
        parent[v] = v;
        canon[v] = -1;
        open[v] = 0;
    }
    auto find = [&](int x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    out.closed = d.closed + p.closed;
    out.holes = d.holes + p.holes;
    // Each shared portal either merges two components or closes a loop around a hole.
    for (std::size_t k = 0; k < d.right.size(); ++k) {
        const int a = find(d.right[k]), b = find(nd + p.left[k]);
        if (a == b) ++out.holes;
        else parent[std::max(a, b)] = std::min(a, b);
    }
    int next = 0;
    auto relabel = [&](int node) {
        const int r = find(node);
        open[r] = 1;
        if (canon[r] < 0) canon[r] = next++;
        return std::uint8_t(canon[r]);
    };
    out.left.clear();
    out.right.clear();
    for (auto v : d.left) out.left.push_back(relabel(v));
    for (auto v : p.right) out.right.push_back(relabel(nd + v));
    // Components left without any open portal are finished.
    for (int v = 0; v < n; ++v)
        if (find(v) == v && !open[v]) ++out.closed;
    if (next > 256)
        throw Error("SynthesizeAlongCurve", "a partial pattern has more than 256 open components; slice the exemplar more coarsely");
}

Descriptor join(const Descriptor& d, const Descriptor& p) {
    Descriptor out;
    join_into(d, p, out);
    return out;
}

Closure close_cycle(const Descriptor& d) {
    const int n = count_ids(d);
    // Union-find with potentials: crossing the seam from the right side to the left side
    // moves one turn forward; a loop whose turns do not add up to zero goes round the curve.
    std::vector<int> parent(n), pot(n, 0);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) {
        int off = 0;
        while (parent[x] != x) {
            off += pot[x];
            x = parent[x];
        }
        return std::pair<int, int>{x, off};
    };
    Closure c;
    c.holes = d.holes;
    int roots = n;
    for (std::size_t k = 0; k < d.right.size(); ++k) {
        const auto [ru, pu] = find(d.right[k]);
        const auto [rv, pv] = find(d.left[k]);
        if (ru == rv) {
            ++c.holes;
            if (pv - pu != 1) c.winds = true;
        } else {
            parent[rv] = ru;
            pot[rv] = pu + 1 - pv;
            --roots;
        }
    }
    c.components = d.closed + roots;
    return c;
}

namespace {

struct Entry {
    double cost = 0;   // joins (with variation) plus beta * autocorrelation
    double joins = 0;  // joins only
    double length = 0;
    double offset = 0;
    int piece = 0, first = 0, parent = -1;
    Descriptor desc;
    std::vector<float> lags;          // autocorrelation sums per lag (3.7), when beta > 0
    float max_lag = 0;                // the largest of them
    std::vector<std::uint16_t> seq;   // the pieces so far, when beta > 0
};

struct Candidate {
    int layer, index;
    double cost, length;
    Closure closure;
};

// What backtracking needs of an entry once its layer has been expanded.
struct Back {
    int piece, parent;
};

// The key of an entry in its layer: last piece, first piece (cycles), and the descriptor;
// a counter the request leaves free is left out, so entries differing only there compete.
void key_of(std::string& k, int piece, int first, const Descriptor& d, bool cyclic, bool components_free,
            bool holes_free) {
    k.clear();
    auto put = [&](int v) {
        k.push_back(char(v & 0xff));
        k.push_back(char((v >> 8) & 0xff));
    };
    put(piece);
    if (cyclic) put(first);
    if (!components_free) put(d.closed);
    if (!holes_free) put(d.holes);
    put(int(d.left.size()));
    k.append(d.left.begin(), d.left.end());
    k.append(d.right.begin(), d.right.end());
}

std::size_t bytes_of(const Entry& e) {
    return sizeof(Entry) + e.desc.left.capacity() + e.desc.right.capacity() + e.lags.capacity() * sizeof(float) +
           e.seq.capacity() * sizeof(std::uint16_t);
}

class Solver {
public:
    Solver(const SolveInput& in, SynthesisReport& report) : in_(in), report_(report), P_(*in.pieces), J_(*in.joins) {
        double sum = 0;
        int n = 0;
        for (const auto& row : J_)
            for (const Join& j : row)
                if (j.valid) {
                    sum += j.cost;
                    ++n;
                }
        mean_join_ = n > 0 && sum > 0 ? sum / n : 1.0;
        // exp(-|i - j| / sigma), sigma = 0.5 (3.7), by index distance.
        for (std::size_t d = 0; d < P_.size(); ++d) similarity_.push_back(float(std::exp(-double(d) / 0.5)));
        for (std::size_t i = 0; i < P_.size(); ++i)
            for (std::size_t j = 0; j < P_.size(); ++j)
                similarity_to_.push_back(similarity_[i > j ? i - j : j - i]);
        for (std::size_t i = 0; i < P_.size(); ++i) {
            succ_.emplace_back();
            for (std::size_t j = 0; j < P_.size(); ++j)
                if (J_[i][j].valid) succ_.back().push_back(int(j));
        }
    }

    // Runs the programme with lengths up to `cap`; fills candidates_.
    void run(double cap) {
        back_.clear();
        candidates_.clear();
        const auto& o = in_.options;
        std::vector<Entry> first;
        std::unordered_map<std::string, int> index;
        for (std::size_t p = 0; p < P_.size(); ++p) {
            if (!in_.cyclic && !P_[p].desc.left.empty()) continue;
            Entry e;
            e.piece = e.first = int(p);
            e.length = P_[p].width();
            e.desc = P_[p].desc;
            if (!in_.cyclic) e.desc.left.clear();
            if (o.autocorrelation > 0) e.seq = {std::uint16_t(p)};
            if (e.length > cap || pruned(e.desc)) continue;
            insert(first, index, std::move(e));
        }
        std::vector<Entry> cur = std::move(first);
        std::size_t bytes = 0;
        for (std::size_t k = 0; !cur.empty(); ++k) {
            // Only the frontier keeps descriptors; earlier layers keep their back pointers.
            back_.emplace_back();
            for (const Entry& e : cur) back_.back().push_back({e.piece, e.parent});
            bytes += back_.back().size() * sizeof(Back);
            collect(k, cur);
            std::vector<Entry> next;
            index.clear();
            // Scratch of one extension: nothing is allocated unless it beats what its key holds.
            Descriptor desc;
            std::vector<float> lags;
            std::string key;
            for (std::size_t ei = 0; ei < cur.size(); ++ei) {
                const Entry& e = cur[ei];
                for (int j : succ_[e.piece]) {
                    const Join& jn = J_[e.piece][j];
                    const double length = e.length + P_[j].width();
                    if (length > cap) continue;
                    const double offset = e.offset + jn.tau;
                    if (std::abs(offset) > 0.5 * in_.band_height) continue;  // band bound (3.6.2)
                    join_into(e.desc, P_[j].desc, desc);
                    if (pruned(desc)) continue;
                    const double joins = e.joins + jn.cost + variation(k, e.piece, j);
                    key_into(key, j, e.first, desc);
                    const auto it = index.find(key);
                    // The penalty is never negative: the joins alone may already lose.
                    Entry* held = it != index.end() ? &next[std::size_t(it->second)] : nullptr;
                    // Lags only grow when a piece is appended, so the penalty is at least
                    // beta x the largest lag so far: a lower bound that may already lose.
                    if (held && !(joins + o.autocorrelation * double(e.max_lag) < held->cost)) continue;
                    double cost = joins;
                    float max_lag = 0;
                    if (o.autocorrelation > 0) {
                        max_lag = lags_after(e, j, lags);
                        cost += o.autocorrelation * double(max_lag);
                    }
                    if (held && !(cost < held->cost)) continue;
                    if (!held) {
                        index.emplace(key, int(next.size()));
                        held = &next.emplace_back();
                    }
                    // A replaced entry's vectors are reused (assign keeps their capacity).
                    Entry& n = *held;
                    n.length = length;
                    n.offset = offset;
                    n.desc.left.assign(desc.left.begin(), desc.left.end());
                    n.desc.right.assign(desc.right.begin(), desc.right.end());
                    n.desc.closed = desc.closed;
                    n.desc.holes = desc.holes;
                    n.piece = j;
                    n.first = e.first;
                    n.parent = int(ei);
                    n.joins = joins;
                    n.cost = cost;
                    if (o.autocorrelation > 0) {
                        n.lags.assign(lags.begin(), lags.end());
                        n.max_lag = max_lag;
                        n.seq.reserve(e.seq.size() + 1);
                        n.seq.assign(e.seq.begin(), e.seq.end());
                        n.seq.push_back(std::uint16_t(j));
                    }
                }
            }
            std::size_t frontier = 0;
            for (const Entry& e : cur) frontier += bytes_of(e);
            for (const Entry& e : next) frontier += bytes_of(e) + 48 + e.desc.left.size() + e.desc.right.size();
            report_.dp_bytes = std::max(report_.dp_bytes, bytes + frontier);
            report_.dp_entries += next.size();
            cur = std::move(next);
            if (back_.size() > 200000)
                throw Error(op_, "the pieces are too narrow for the curve's length (more than 200000 in a row)");
        }
    }

    std::vector<int> backtrack(const Candidate& c) const {
        std::vector<int> seq;
        for (int k = c.layer, i = c.index; k >= 0 && i >= 0; --k) {
            seq.push_back(back_[k][i].piece);
            i = back_[k][i].parent;
        }
        std::reverse(seq.begin(), seq.end());
        return seq;
    }

    const std::vector<Candidate>& candidates() const { return candidates_; }
    std::string op_;

private:
    bool pruned(const Descriptor& d) const {
        const auto& o = in_.options;
        const bool open = !d.left.empty() || !d.right.empty();
        if (o.components && d.closed + (open ? 1 : 0) > *o.components) return true;
        if (o.holes && d.holes > *o.holes) return true;
        return false;
    }

    double variation(std::size_t k, int i, int j) const {
        const double r = in_.options.randomness;
        if (r <= 0) return 0.0;
        std::uint64_t h = hash_combine(in_.key, k);
        h = hash_combine(h, std::uint64_t(i) * 1000003u + std::uint64_t(j));
        return r * mean_join_ * unit_from_hash(h);
    }

    // Autocorrelation sums after appending piece j to entry (k, ei): for each lag, the pairs
    // of pieces that far apart, weighted by how close their indices are (sigma = 0.5).
    // Returns the largest sum.
    float lags_after(const Entry& e, int j, std::vector<float>& lags) const {
        // One lag more than the entry has (e.lags holds lags 1 .. K - 1 of its K pieces).
        const std::size_t K = e.seq.size();
        lags.resize(K);
        const float* sim = &similarity_to_[std::size_t(j) * P_.size()];  // by piece index
        const std::uint16_t* last = e.seq.data() + K - 1;               // lag 1: the last piece
        float top = 0.f;
        for (std::size_t lag = 1; lag < K; ++lag) {
            const float v = e.lags[lag - 1] + sim[*(last - (lag - 1))];
            lags[lag - 1] = v;
            top = std::max(top, v);
        }
        lags[K - 1] = 0.f + sim[e.seq[0]];
        return std::max(top, lags[K - 1]);
    }

    void key_into(std::string& key, int piece, int first, const Descriptor& d) const {
        const auto& o = in_.options;
        key_of(key, piece, first, d, in_.cyclic, !o.components, !o.holes);
    }

    void insert(std::vector<Entry>& layer, std::unordered_map<std::string, int>& index, Entry&& e) {
        std::string key;
        key_into(key, e.piece, e.first, e.desc);
        auto [it, fresh] = index.emplace(key, int(layer.size()));
        if (fresh) layer.push_back(std::move(e));
        else if (e.cost < layer[it->second].cost) layer[it->second] = std::move(e);
    }

    // Complete patterns of layer k meeting the constraints.
    void collect(std::size_t k, const std::vector<Entry>& layer) {
        const auto& o = in_.options;
        for (std::size_t i = 0; i < layer.size(); ++i) {
            const Entry& e = layer[i];
            Closure cl;
            double cost = e.cost;
            double length = e.length;
            if (!in_.cyclic) {
                if (!e.desc.right.empty()) continue;
                cl.components = e.desc.closed;
                cl.holes = e.desc.holes;
            } else {
                const Join& jn = J_[e.piece][e.first];
                if (!jn.valid) continue;
                // The wrap-around join must also keep the band: the offsets of a cycle add up.
                if (std::abs(e.offset + jn.tau) > 0.5 * in_.band_height) continue;
                Descriptor d = e.desc;
                d.left = e.desc.left;
                cl = close_cycle(d);
                cost += jn.cost + variation(k, e.piece, e.first);
                if (o.closed_pattern && !cl.winds) continue;
            }
            if (o.components && cl.components != *o.components) continue;
            if (o.holes && cl.holes != *o.holes) continue;
            if (cl.components == 0) continue;
            candidates_.push_back({int(k), int(i), cost, length, cl});
        }
    }

    const SolveInput& in_;
    SynthesisReport& report_;
    const std::vector<Piece>& P_;
    const std::vector<std::vector<Join>>& J_;
    std::vector<std::vector<int>> succ_;
    std::vector<float> similarity_;
    std::vector<float> similarity_to_;  // [j * pieces + i]: similarity of pieces i and j
    double mean_join_ = 1;
    std::vector<std::vector<Back>> back_;
    std::vector<Candidate> candidates_;
};

std::string describe(const SynthesisOptions& o, bool cyclic) {
    std::string s;
    s += o.components ? std::to_string(*o.components) + " component(s)" : "any number of components";
    s += o.holes ? ", " + std::to_string(*o.holes) + " hole(s)" : "";
    if (cyclic && o.closed_pattern) s += ", going all the way round";
    return s;
}

}  // namespace

std::string no_sequence(const SolveInput& in, const std::string& pieces) {
    const auto& o = in.options;
    return "no sequence of the exemplar's " + pieces + " gives " + describe(o, in.cyclic) + " within " +
           std::to_string(int(std::lround(o.max_length_deviation * 100))) + "% of the curve's length " +
           std::to_string(in.length);
}

std::optional<Solution> solve(const SolveInput& in, SynthesisReport& report, const std::string& op) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto& o = in.options;
    const double L = in.length;
    Solver solver(in, report);
    solver.op_ = op;
    const Candidate* best = nullptr;
    // First within the tolerance; when nothing complete reaches it, the widest allowed
    // deviation, and the closest lengths there (3.6.3).
    for (double tol : {o.length_tolerance, std::max(o.length_tolerance, o.max_length_deviation)}) {
        solver.run(L * (1 + tol));
        const auto& cs = solver.candidates();
        double eps = tol * L;
        bool any = false;
        for (const Candidate& c : cs)
            if (std::abs(c.length - L) <= eps) any = true;
        if (!any) {
            if (tol == o.length_tolerance && o.max_length_deviation > o.length_tolerance) continue;
            double closest = std::numeric_limits<double>::infinity();
            for (const Candidate& c : cs) closest = std::min(closest, std::abs(c.length - L));
            if (closest > o.max_length_deviation * L) continue;
            eps = closest * (1 + 1e-12) + 1e-12 * L;
        }
        for (const Candidate& c : cs) {
            if (std::abs(c.length - L) > eps) continue;
            if (!best || c.cost < best->cost) best = &c;
        }
        std::size_t n = 0;
        for (const Candidate& c : cs)
            if (std::abs(c.length - L) <= eps) ++n;
        report.candidates = n;
        if (best) break;
    }
    report.dp_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!best) return std::nullopt;
    Solution s;
    s.sequence = solver.backtrack(*best);
    s.length = best->length;
    s.components = best->closure.components;
    s.holes = best->closure.holes;
    s.closed_pattern = best->closure.winds;
    return s;
}

}  // namespace tex::synth
