// The nodes (i cell, j cell) of the global lattice over a region's box, and a field's values
// on them: what the lattice operators (IsoLines, Creases) trace their lines on.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "libtex/error.hpp"
#include "libtex/fields.hpp"
#include "libtex/parallel.hpp"

namespace tex::detail {

struct LatticeWindow {
    // The squares meeting the box: nodes i0..i1 x j0..j1.
    long long i0 = 0, i1 = 0, j0 = 0, j1 = 0;
    // Values on those nodes and `ring` more around them.
    long long ring = 0, nx = 0, ny = 0;
    std::vector<double> values;

    LatticeWindow(const Field& f, const BBox& box, double cell, long long ring_nodes, const char* who)
        : i0((long long)std::floor(box.xmin / cell)),
          i1((long long)std::floor(box.xmax / cell) + 1),
          j0((long long)std::floor(box.ymin / cell)),
          j1((long long)std::floor(box.ymax / cell) + 1),
          ring(ring_nodes),
          nx(i1 - i0 + 1 + 2 * ring_nodes),
          ny(j1 - j0 + 1 + 2 * ring_nodes) {
        if (nx * ny > 50'000'000) throw Error(who, "too many lattice nodes for the region (cell too small)");
        values.resize(std::size_t(nx * ny));
        // Rows of nodes apart (each value is the field's at its node alone): a face drawn last
        // shares them with the threads that have run out of faces.
        parallel_for(std::size_t(ny), [&](std::size_t row) {
            const long long j = (long long)row;
            for (long long i = 0; i < nx; ++i)
                values[std::size_t(j * nx + i)] = f(Point{double(i0 - ring + i) * cell, double(j0 - ring + j) * cell});
        });
    }
    double at(long long i, long long j) const {
        return values[std::size_t((j - j0 + ring) * nx + (i - i0 + ring))];
    }
};

}  // namespace tex::detail
