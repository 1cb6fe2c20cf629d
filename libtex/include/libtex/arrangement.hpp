// Arrangement: a function from a region to curves (thesis 3.1, "functional programming").
//
// Every operator returns one. Nothing is computed when an operator is applied: the chain of
// operators is evaluated when the arrangement is called on a region, and a planar map is
// induced only by the operators that need topology (mapping operators and masks).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "libtex/cells.hpp"
#include "libtex/curves.hpp"
#include "libtex/planar_map.hpp"
#include "libtex/region.hpp"

namespace tex {

class Arrangement {
public:
    using Fn = std::function<Curves(const Region&)>;
    using MapFn = std::function<MapPtr(const Region&)>;

    // The empty arrangement.
    Arrangement();
    explicit Arrangement(Fn fn);
    // An arrangement that knows a quicker way to its planar map than inducing it from its
    // curves (a partition that keeps whole cells: its cell complex already is the map).
    // `map(r)` must give exactly PlanarMap::induce(fn(r)), record for record.
    Arrangement(Fn fn, MapFn map);
    // The edges of that map, as LocalEdges in the map's edge order, when the arrangement
    // knows them without the map (none: it does not, this time); a mapper that reads only
    // its edge then runs without the map (MapToEdges of a LocalEdgeMapper). `edges(r)` must
    // give exactly the edges of map(r), in order, curve for curve and key for key; with
    // `only`, exactly those whose curve has that label.
    using EdgesFn = std::function<std::optional<std::vector<LocalEdge>>(const Region&, std::optional<LabelId> only)>;
    Arrangement(Fn fn, MapFn map, EdgesFn edges);

    // Evaluates the arrangement on a region.
    Curves operator()(const Region& r) const;
    // Evaluates the arrangement on a face of another planar map (sub-scale arrangements).
    Curves operator()(const Face& f) const;
    // Evaluates and induces the planar map of the result.
    MapPtr induce(const Region& r) const;
    // The edges of induce(r) without inducing it, when the arrangement knows them (with
    // `only`, those with that label).
    std::optional<std::vector<LocalEdge>> local_edges(const Region& r, std::optional<LabelId> only = std::nullopt) const;

private:
    std::shared_ptr<const Fn> fn_;
    std::shared_ptr<const MapFn> map_;  // null: induce from the curves
    std::shared_ptr<const EdgesFn> edges_;  // null: read the edges of the map
};

// An arrangement that returns fixed curves, whatever the region.
Arrangement Constant(Curves c);

}  // namespace tex
