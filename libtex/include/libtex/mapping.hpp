// Mapping operators (thesis 3.4, table 3.3): apply a mapper to every cell of a planar map.
//
// A mapper is any callable from one cell to curves. It is run on every vertex, edge or
// bounded face of the planar map induced by the input arrangement, possibly on several
// threads; its results are concatenated in the map's cell order, so the output is the
// same whatever the number of threads.
#pragma once

#include <functional>
#include <optional>

#include "libtex/arrangement.hpp"

namespace tex {

using VertexMapper = std::function<Curves(const Vertex&)>;
using EdgeMapper = std::function<Curves(const Edge&)>;
using FaceMapper = std::function<Curves(const Face&)>;

// How a mapping operator runs its mapper: on the worker threads (the default), or one cell
// after the other on the thread that evaluates the arrangement, for a mapper that cannot
// run two calls at once anyway (a Python function holds the interpreter's lock: on several
// threads it would only pass the lock back and forth). The output is the same either way.
enum class MapperThreads { Parallel, Serial };

Arrangement MapToVertices(VertexMapper m, Arrangement a, MapperThreads t = MapperThreads::Parallel);
Arrangement MapToEdges(EdgeMapper m, Arrangement a, MapperThreads t = MapperThreads::Parallel);
// A mapper that reads only its edge (LocalEdge: its curve, labels, key, its vertices' keys,
// and fields at points of it). As an EdgeMapper it runs on AsLocalEdge(e); MapToEdges runs
// it straight on the edges of a partition that knows them without its planar map (the KEEP
// modes of StripesPartition and GridPartition), with the same result, cell for cell.
// With `only`, an edge without that label maps to nothing, f is not called on it, and MapToEdges
// does not read it at all (the partition leaves it out of its edges: half of a grid's edges
// when the mapper draws one family of its lines). f appends the edge's curves to `out`, which
// holds those of the edges before it (f leaves them alone): one buffer for a run of edges,
// not a set of curves per edge. The edge handed to f is a copy of its own, read by nothing
// after the call: f may take its curve (move it into `out`).
using LocalEdgeFn = std::function<void(LocalEdge& e, Curves& out)>;
EdgeMapper LocalEdgeMapper(LocalEdgeFn f, std::optional<LabelId> only = std::nullopt);

// Visits the bounded faces only.
Arrangement MapToFaces(FaceMapper m, Arrangement a, MapperThreads t = MapperThreads::Parallel);

}  // namespace tex
