// Mapping operators: induce the input's planar map, run the mapper on every cell (in
// parallel), concatenate the results in cell order.
#include "libtex/mapping.hpp"

#include "libtex/fields.hpp"
#include "libtex/parallel.hpp"
#include "libtex/random.hpp"

namespace tex {
namespace {

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
    if (t == MapperThreads::Serial) {
        for (std::size_t i = 0; i < ids.size(); ++i) visit(i);
    } else {
        parallel_for(ids.size(), visit);
    }
    Curves out;
    std::size_t total = 0;
    for (const auto& r : results) total += r.curves.size();
    out.curves.reserve(total);
    for (auto& r : results) out.append(std::move(r));
    out.origin.clear();
    return out;
}

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

Arrangement MapToEdges(EdgeMapper m, Arrangement a, MapperThreads t) {
    return Arrangement([m = std::move(m), a = std::move(a), t](const Region& r) {
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
