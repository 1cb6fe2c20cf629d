#include "libtex/arrangement.hpp"

namespace tex {

Arrangement::Arrangement() : Arrangement(Fn([](const Region&) { return Curves{}; })) {}

Arrangement::Arrangement(Fn fn) : fn_(std::make_shared<const Fn>(std::move(fn))) {}

Arrangement::Arrangement(Fn fn, MapFn map)
    : fn_(std::make_shared<const Fn>(std::move(fn))), map_(std::make_shared<const MapFn>(std::move(map))) {}

Arrangement::Arrangement(Fn fn, MapFn map, EdgesFn edges)
    : fn_(std::make_shared<const Fn>(std::move(fn))),
      map_(std::make_shared<const MapFn>(std::move(map))),
      edges_(std::make_shared<const EdgesFn>(std::move(edges))) {}

std::optional<std::vector<LocalEdge>> Arrangement::local_edges(const Region& r, std::optional<LabelId> only) const {
    if (edges_) return (*edges_)(r, only);
    return std::nullopt;
}

Curves Arrangement::operator()(const Region& r) const { return (*fn_)(r); }

Curves Arrangement::operator()(const Face& f) const { return (*fn_)(ToRegion(f)); }

MapPtr Arrangement::induce(const Region& r) const {
    if (map_) return (*map_)(r);
    return PlanarMap::induce((*fn_)(r));
}

Arrangement Constant(Curves c) {
    auto shared = std::make_shared<const Curves>(std::move(c));
    return Arrangement([shared](const Region&) { return *shared; });
}

}  // namespace tex
