// Arrangement: a function from a region to curves (thesis 3.1, "functional programming").
//
// Every operator returns one. Nothing is computed when an operator is applied: the chain of
// operators is evaluated when the arrangement is called on a region, and a planar map is
// induced only by the operators that need topology (mapping operators and masks).
#pragma once

#include <functional>
#include <memory>

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

    // Evaluates the arrangement on a region.
    Curves operator()(const Region& r) const;
    // Evaluates the arrangement on a face of another planar map (sub-scale arrangements).
    Curves operator()(const Face& f) const;
    // Evaluates and induces the planar map of the result.
    MapPtr induce(const Region& r) const;

private:
    std::shared_ptr<const Fn> fn_;
    std::shared_ptr<const MapFn> map_;  // null: induce from the curves
};

// An arrangement that returns fixed curves, whatever the region.
Arrangement Constant(Curves c);

}  // namespace tex
