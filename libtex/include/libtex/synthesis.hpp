// Topology-constrained synthesis of vector patterns along curves (seed 002: Zhou, Jiang and
// Lefebvre, "Topology-constrained synthesis of vector patterns", 2014, sections 3 to 6).
//
// An exemplar (closed polygons with holes, e.g. from an SVG) is cut by vertical lines into
// pieces; a dynamic programme chooses a sequence of pieces whose joined topology has exactly
// the requested number of connected components and holes; the pieces are then placed,
// stitched and bent into a band along a curve. The result is a set of closed curves (outer
// contours counter-clockwise, holes clockwise), which any mapper can return.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "libtex/curves.hpp"

namespace tex {

enum class Slicing {
    Uniform,   // `slicing_lines` equally spaced cuts (seed 002, 5.1)
    Topology,  // cuts halfway between groups of topological events along U (5.2)
};

struct SynthesisOptions {
    // Connected components of the result; std::nullopt leaves it free.
    std::optional<int> components = 1;
    // Holes of the result, counted in the plane (a pattern that goes all the way round a
    // closed curve encloses the curve's inside: that is one hole); std::nullopt: free.
    std::optional<int> holes;
    // For a closed curve: the pattern must go all the way round (a ring, Fig. 6 of the
    // seed). Refused for an open curve.
    bool closed_pattern = false;
    // Weight beta of the autocorrelation penalty (3.7); 0 switches it off.
    double autocorrelation = 0.0;
    Slicing slicing = Slicing::Topology;
    // Number of cuts t of the uniform slicing (t + 1 pieces).
    int slicing_lines = 8;
    // Topological events closer than this fraction of the exemplar's width form one group
    // (5.2.2). Unset (the default): chosen from the exemplar. The seed's 0.2 is tried first
    // and kept when some sequence of its pieces meets the request. Else finer groupings,
    // each just below one more of the gaps between the exemplar's successive events (largest
    // gap first, none under 0.005), until one does; SynthesisReport::event_grouping says which.
    std::optional<double> event_grouping;
    // A cut whose narrowest portal is thinner than this (in output units, the exemplar being
    // scaled to the band height) is dropped (5.2.1); 0 keeps every cut.
    double thin_portal = 0.0;
    // Weight of the portal-position term against the tangent term (3.6.1).
    double alpha = 0.8;
    // Length target: the chosen sequence's natural length is within this fraction of the
    // curve's length (widened up to `max_length_deviation` when no sequence reaches it); the
    // pattern is then stretched to the exact length.
    double length_tolerance = 0.05;
    double max_length_deviation = 0.25;
    // Seeded variation: each join cost gets a random share of this fraction of the mean join
    // cost, keyed by its position in the sequence, so different seeds give different
    // patterns of the same topology; 0 gives the plain optimum.
    double randomness = 0.1;
    // Seed of that variation; unset: keyed by the curve's geometry and the global seed
    // (GetSeed), so a mapper calling the operator on every edge gets a different pattern per
    // edge, the same on every run and at any thread count.
    std::optional<std::uint64_t> seed;
};

// What one synthesis did (for the benchmark and the tests).
struct SynthesisReport {
    int pieces_in_exemplar = 0;
    double event_grouping = 0;  // the grouping the pieces were cut with (topology slicing; else 0)
    int groupings_tried = 1;    // slicings solved to get there (more than 1: the automatic choice went finer)
    int pieces_in_result = 0;
    int components = 0;  // as the descriptors say (the tests count them again on the output)
    int holes = 0;
    bool closed_pattern = false;
    double natural_length = 0;   // summed piece widths before the stretch to the curve length
    double target_length = 0;
    double dp_seconds = 0;
    std::size_t dp_entries = 0;     // entries created in the DP table
    std::size_t dp_bytes = 0;       // peak bytes held by the DP table (entries and keys)
    std::size_t candidates = 0;     // complete sequences meeting the constraints ("correct paths")
};

// Synthesizes a pattern from `exemplar` (its closed curves: polygons with holes, nesting by
// even-odd; open curves are ignored) in a band of height `band_height` centred on `curve`
// (one open or closed polyline). The exemplar is scaled so that its height is the band
// height; its x axis runs along the curve, its y axis to the curve's left. Throws tex::Error
// naming SynthesizeAlongCurve on bad input, when no sequence of pieces meets the
// constraints, and when the curve turns too tightly for the band (the pattern would fold).
Curves SynthesizeAlongCurve(const Curves& exemplar, const Curves& curve, double band_height,
                            const SynthesisOptions& options = {}, SynthesisReport* report = nullptr);

// The method applied twice (seed 002, 6.2): a strip of height `row_height` along the
// rectangle's width, then that strip turned a quarter turn and used as the exemplar along
// the height. The result fills [0, width] x [0, height]; the component and hole constraints
// hold for the final pattern. Throws tex::Error naming SynthesizeInRectangle.
Curves SynthesizeInRectangle(const Curves& exemplar, double width, double height,
                             double row_height, const SynthesisOptions& options = {});

}  // namespace tex
