// Small helpers shared by the libtex tests.
#pragma once

#include <cmath>
#include <string>

#include "libtex/tex.hpp"

namespace th {

inline double length(const tex::Curves& c) {
    double l = 0;
    for (const auto& cv : c.curves) {
        const std::size_t n = cv.points.size();
        const std::size_t segs = cv.closed ? n : n - 1;
        for (std::size_t i = 0; i < segs && n > 1; ++i) l += tex::distance(cv.points[i], cv.points[(i + 1) % n]);
    }
    return l;
}

inline std::size_t bounded_faces(const tex::PlanarMap& m) {
    std::size_t n = 0;
    for (const auto& f : m.faces()) n += !f.unbounded;
    return n;
}

// Area of a bounded face (holes subtracted).
inline double face_area(const tex::PlanarMap& m, int f) {
    double a = 0;
    for (std::size_t k = 0; k < m.faces()[f].cycles.size(); ++k) a += tex::signed_area(m.cycle_points(f, k));
    return a;
}

// Expects a tex::Error whose message contains every fragment.
#define EXPECT_TEX_ERROR(stmt, frag1, frag2)                                              \
    do {                                                                                  \
        try {                                                                             \
            stmt;                                                                         \
            ADD_FAILURE() << "no tex::Error thrown by " #stmt;                           \
        } catch (const tex::Error& e) {                                                   \
            EXPECT_NE(std::string(e.what()).find(frag1), std::string::npos) << e.what(); \
            EXPECT_NE(std::string(e.what()).find(frag2), std::string::npos) << e.what(); \
        }                                                                                 \
    } while (0)

}  // namespace th
