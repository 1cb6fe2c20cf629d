// Mapping operators: induce the input's planar map, run the mapper on every cell (in
// parallel), concatenate the results in cell order.
#include "libtex/mapping.hpp"

#include <algorithm>

#include "libtex/fields.hpp"
#include "libtex/parallel.hpp"
#include "libtex/random.hpp"

namespace tex {
namespace {

// Runs visit(i) for every cell i, on the workers or in order; then the results of the cells
// in their order.
template <class Visit>
Curves map_items(std::size_t n, std::vector<Curves>& results, const Visit& visit, MapperThreads t) {
    if (t == MapperThreads::Serial) {
        for (std::size_t i = 0; i < n; ++i) visit(i);
    } else {
        parallel_for(n, visit);
    }
    Curves out;
    std::size_t total = 0;
    for (const auto& r : results) total += r.curves.size();
    out.curves.reserve(total);
    for (auto& r : results) out.append(std::move(r));
    out.origin.clear();
    return out;
}

template <class CellT, class Mapper, class KeyOf>
Curves map_cells(const MapPtr& map, const std::vector<int>& ids, const Mapper& m, KeyOf key_of, MapperThreads t) {
    std::vector<Curves> results(ids.size());
    auto visit = [&](std::size_t i) {
        CellT cell(map, ids[i]);
        RandomScope scope(key_of(ids[i]));
        if (detail::locality_checked()) {
            // Field reads of the mapper are checked against the cell's box.
            FieldWindow window(CellBBox(cell));
            results[i] = m(cell);
        } else {
            results[i] = m(cell);
        }
    };
    return map_items(ids.size(), results, visit, t);
}

// map_cells over the edges of a map for a mapper that reads only its edge, the edges read
// without the map: the same calls, keys and windows, so the same result. The edges go in
// blocks, each appended to one buffer in order.
Curves map_local_edges(std::vector<LocalEdge>& edges, const LocalEdgeFn& f, MapperThreads t) {
    constexpr std::size_t kBlock = 64;
    std::vector<Curves> results((edges.size() + kBlock - 1) / kBlock);
    auto visit = [&](std::size_t b) {
        Curves& out = results[b];
        out.curves.reserve(std::min(kBlock, edges.size() - b * kBlock));
        for (std::size_t i = b * kBlock; i < std::min(edges.size(), (b + 1) * kBlock); ++i) {
            RandomScope scope(edges[i].key);
            if (detail::locality_checked()) {
                FieldWindow window(CellBBox(edges[i]));
                f(edges[i], out);
            } else {
                f(edges[i], out);
            }
        }
    };
    return map_items(results.size(), results, visit, t);
}

// The EdgeMapper of a LocalEdgeFn: MapToEdges knows it by its type.
struct LocalMapper {
    LocalEdgeFn f;
    std::optional<LabelId> only;
    Curves operator()(const Edge& e) const {
        if (only && !record(e).labels.has(*only)) return Nothing();
        LocalEdge local = AsLocalEdge(e);
        Curves out;
        f(local, out);
        return out;
    }
};

std::vector<int> iota_ids(std::size_t n) {
    std::vector<int> ids(n);
    for (std::size_t i = 0; i < n; ++i) ids[i] = int(i);
    return ids;
}

}  // namespace

Arrangement MapToVertices(VertexMapper m, Arrangement a, MapperThreads t) {
    return Arrangement([m = std::move(m), a = std::move(a), t](const Region& r) {
        MapPtr map = a.induce(r);
        return map_cells<Vertex>(map, iota_ids(map->vertices().size()), m,
                                 [&](int i) { return map->vertices()[i].key; }, t);
    });
}

EdgeMapper LocalEdgeMapper(LocalEdgeFn f, std::optional<LabelId> only) { return LocalMapper{std::move(f), only}; }

Arrangement MapToEdges(EdgeMapper m, Arrangement a, MapperThreads t) {
    return Arrangement([m = std::move(m), a = std::move(a), t](const Region& r) {
        if (const LocalMapper* local = m.target<LocalMapper>())
            if (std::optional<std::vector<LocalEdge>> edges = a.local_edges(r, local->only))
                return map_local_edges(*edges, local->f, t);
        MapPtr map = a.induce(r);
        return map_cells<Edge>(map, iota_ids(map->edges().size()), m,
                               [&](int i) { return map->edges()[i].key; }, t);
    });
}

Arrangement MapToFaces(FaceMapper m, Arrangement a, MapperThreads t) {
    return Arrangement([m = std::move(m), a = std::move(a), t](const Region& r) {
        MapPtr map = a.induce(r);
        std::vector<int> ids;
        for (std::size_t i = 0; i < map->faces().size(); ++i)
            if (!map->faces()[i].unbounded) ids.push_back(int(i));
        return map_cells<Face>(map, ids, m, [&](int i) { return map->faces()[i].key; }, t);
    });
}

}  // namespace tex
