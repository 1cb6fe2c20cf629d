// Mapping operators (thesis 3.4, table 3.3): apply a mapper to every cell of a planar map.
//
// A mapper is any callable from one cell to curves. It is run on every vertex, edge or
// bounded face of the planar map induced by the input arrangement, possibly on several
// threads; its results are concatenated in the map's cell order, so the output is the
// same whatever the number of threads.
#pragma once

#include <functional>

#include "libtex/arrangement.hpp"

namespace tex {

using VertexMapper = std::function<Curves(const Vertex&)>;
using EdgeMapper = std::function<Curves(const Edge&)>;
using FaceMapper = std::function<Curves(const Face&)>;

Arrangement MapToVertices(VertexMapper m, Arrangement a);
Arrangement MapToEdges(EdgeMapper m, Arrangement a);
// Visits the bounded faces only.
Arrangement MapToFaces(FaceMapper m, Arrangement a);

}  // namespace tex
