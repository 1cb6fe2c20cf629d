// Small helpers shared by the libtex tests.
#pragma once

#include <gtest/gtest.h>

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

// Expects two planar maps to be the same, record by record (points, numbering, labels, keys).
inline void expect_same_map(const tex::PlanarMap& a, const tex::PlanarMap& b, const char* what) {
    ASSERT_EQ(a.vertices().size(), b.vertices().size()) << what;
    ASSERT_EQ(a.edges().size(), b.edges().size()) << what;
    ASSERT_EQ(a.faces().size(), b.faces().size()) << what;
    EXPECT_EQ(a.unbounded_face(), b.unbounded_face()) << what;
    for (std::size_t i = 0; i < a.vertices().size(); ++i) {
        const auto &x = a.vertices()[i], &y = b.vertices()[i];
        EXPECT_EQ(x.point, y.point) << what << " vertex " << i;
        EXPECT_EQ(x.labels, y.labels) << what;
        EXPECT_EQ(x.edges, y.edges) << what << " vertex " << i;
        EXPECT_EQ(x.faces, y.faces) << what << " vertex " << i;
        EXPECT_EQ(x.key, y.key) << what;
    }
    for (std::size_t i = 0; i < a.edges().size(); ++i) {
        const auto &x = a.edges()[i], &y = b.edges()[i];
        EXPECT_EQ(x.points, y.points) << what << " edge " << i;
        EXPECT_EQ(std::make_pair(x.source, x.target), std::make_pair(y.source, y.target)) << what;
        EXPECT_EQ(std::make_pair(x.left, x.right), std::make_pair(y.left, y.right)) << what << " edge " << i;
        EXPECT_EQ(x.labels, y.labels) << what;
        EXPECT_EQ(x.left_labels, y.left_labels) << what;
        EXPECT_EQ(x.right_labels, y.right_labels) << what;
        ASSERT_EQ(x.sources.size(), y.sources.size()) << what;
        for (std::size_t k = 0; k < x.sources.size(); ++k) {
            EXPECT_EQ(x.sources[k].curve, y.sources[k].curve) << what;
            EXPECT_EQ(x.sources[k].forward, y.sources[k].forward) << what;
        }
        EXPECT_EQ(x.key, y.key) << what;
    }
    for (std::size_t i = 0; i < a.faces().size(); ++i) {
        const auto &x = a.faces()[i], &y = b.faces()[i];
        EXPECT_EQ(x.unbounded, y.unbounded) << what;
        EXPECT_EQ(x.labels, y.labels) << what << " face " << i;
        ASSERT_EQ(x.cycles.size(), y.cycles.size()) << what << " face " << i;
        for (std::size_t c = 0; c < x.cycles.size(); ++c) {
            ASSERT_EQ(x.cycles[c].size(), y.cycles[c].size()) << what;
            for (std::size_t k = 0; k < x.cycles[c].size(); ++k) {
                EXPECT_EQ(x.cycles[c][k].edge, y.cycles[c][k].edge) << what;
                EXPECT_EQ(x.cycles[c][k].left, y.cycles[c][k].left) << what;
            }
        }
        EXPECT_EQ(x.vertices, y.vertices) << what;
        EXPECT_EQ(x.edges, y.edges) << what;
        EXPECT_EQ(x.key, y.key) << what;
    }
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
