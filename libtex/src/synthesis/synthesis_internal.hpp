// Internal steps of SynthesizeAlongCurve (seed 002), one file each:
//   pieces.cpp   exemplar rings, slicing (5.1, 5.2), pieces and portals (3.3)
//   solver.cpp   topology descriptors (3.4) and the dynamic programme (3.6, 3.7)
//   synthesis.cpp offsets (4.1), stitching (4.2), contours (4.3), band mapping, the API
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "libtex/synthesis.hpp"

namespace tex::synth {

// A ring of the exemplar, oriented with the inside on its left (outer rings
// counter-clockwise, holes clockwise).
struct Ring {
    std::vector<Point> pts;
    bool hole = false;
};

// The exemplar scaled to the band height: x from 0 to width, y centred on 0.
struct Exemplar {
    std::vector<Ring> rings;
    double width = 0, height = 0;
};
Exemplar make_exemplar(const Curves& c, double band_height, const std::string& op);

// The interior intervals (portals) a vertical line x = c cuts through, bottom to top.
std::vector<std::pair<double, double>> portals_at(const Exemplar& ex, double c);

// Cut positions (strictly inside (0, width), never through a vertex); topology slicing groups
// the events with `grouping` (a fraction of the width; unused by uniform slicing).
std::vector<double> cut_positions(const Exemplar& ex, const SynthesisOptions& o, double grouping);

// x of the exemplar's topological events (5.2), sorted: the vertices where x has a local
// extremum along a ring.
std::vector<double> topology_events(const Exemplar& ex);

// The event grouping of the seed (5.2.2), tried first when the option is unset.
constexpr double kSeedGrouping = 0.2;
// The automatic choice never splits events closer than this fraction of the width.
constexpr double kFinestGrouping = 0.005;
// At most this many groupings are tried (the seed's and finer ones).
constexpr std::size_t kMaxGroupings = 12;
// The groupings tried when the option is unset, coarsest first: the seed's 0.2, then for each
// distinct gap between successive topological events narrower than that (and wider than
// kFinestGrouping), largest first, a round grouping just below it, which splits the exemplar
// there as well. Each gives more pieces than the one before.
std::vector<double> automatic_groupings(const Exemplar& ex);

// Union-find over small integer sets (components of pieces and of partial patterns).
struct Dsu {
    std::vector<int> parent;
    explicit Dsu(int n) : parent(std::size_t(n)) {
        for (int i = 0; i < n; ++i) parent[std::size_t(i)] = i;
    }
    int find(int x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    bool unite(int a, int b) {
        a = find(a);
        b = find(b);
        if (a == b) return false;
        parent[std::max(a, b)] = std::min(a, b);
        return true;
    }
};

enum Side : int { kLeft = 0, kRight = 1, kNone = -1 };

// A part of a ring inside a piece: from a portal end point to another, or a whole ring.
struct Chain {
    std::vector<Point> pts;
    int start_side = kNone, start_k = -1;
    int end_side = kNone, end_k = -1;
    bool whole() const { return start_side == kNone; }
};

// Topology descriptor (3.4): a component id per portal on each side, closed components and
// holes. Ids are canonical (numbered by first appearance, left side first).
struct Descriptor {
    std::vector<std::uint8_t> left, right;
    int closed = 0, holes = 0;
};

struct Piece {
    double a = 0, b = 0;  // x range in the exemplar
    std::vector<Chain> chains;
    // Portal end points bottom to top (two per portal) and the travel direction of the ring
    // through each (unit vectors).
    std::vector<double> yl, yr;
    std::vector<Point> gl, gr;
    Descriptor desc;
    double width() const { return b - a; }
};
std::vector<Piece> make_pieces(const Exemplar& ex, const std::vector<double>& cuts);

// Cost and best vertical alignment of piece j after piece i (3.6.1); valid when the
// numbers of portal end points agree.
struct Join {
    bool valid = false;
    double cost = 0;
    double tau = 0;
};
std::vector<std::vector<Join>> join_table(const std::vector<Piece>& pieces, double band_height,
                                          double alpha);

struct SolveInput {
    const std::vector<Piece>* pieces;
    const std::vector<std::vector<Join>>* joins;
    double length = 0, band_height = 0;
    bool cyclic = false;
    SynthesisOptions options;
    std::uint64_t key = 0;  // keys the seeded variation
};
struct Solution {
    std::vector<int> sequence;
    double length = 0;
    int components = 0, holes = 0;
    bool closed_pattern = false;
};
// The cheapest sequence meeting the constraints, or nothing when none does (other errors
// throw tex::Error naming `op`).
std::optional<Solution> solve(const SolveInput& in, SynthesisReport& report, const std::string& op);
// "no sequence of the exemplar's <pieces> gives <the request> within <d>% of the
// curve's length <L>", the start of the error when solve finds nothing.
std::string no_sequence(const SolveInput& in, const std::string& pieces);

// Joins descriptor d (a partial pattern) with piece p on its right (the merge rule of 3.4).
Descriptor join(const Descriptor& d, const Descriptor& p);
// Closes a cyclic pattern: joins its right side to its left side. Returns the final
// counts and whether some component goes all the way round.
struct Closure {
    int components = 0, holes = 0;
    bool winds = false;
};
Closure close_cycle(const Descriptor& d);

}  // namespace tex::synth
