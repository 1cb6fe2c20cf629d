// Internal: the double nearest an exact number of CGAL's exact-constructions kernel, as a
// function of its exact value only (planar_map.cpp rounds the vertices of its exact
// arrangements so; merge.cpp rounds the crossings it computes without one alike).
#pragma once

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <gmpxx.h>

#include <cmath>
#include <utility>

namespace tex::detail {

using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;

// CGAL::to_double returns the middle of the current interval approximation when it is
// narrow enough, and that interval depends on the history of the number (whether a
// predicate has already forced its exact value), which differs between builds: a Debug
// build with sanitizers rounded some cut points of the gallery's exact crops to other
// doubles than the Release build, and drew other faces. Ties go to the lower double.
inline double exact_double(const ExactKernel::FT& x) {
    const auto& a = x.approx();
    if (a.inf() == a.sup()) return a.inf();  // a double input coordinate: already exact
    const auto& e = CGAL::exact(x);
    const std::pair<double, double> b = CGAL::to_interval(e);  // the two doubles around e
    if (b.first == b.second) return b.first;
    // The nearer of the two (ties to the lower one); CGAL::to_double of a rational truncates.
    const int c = CGAL::compare(e - b.first, b.second - e);
    return c == CGAL::LARGER ? b.second : b.first;
}

// The same for a GMP rational (the kernel's exact type), for exact values computed without
// the kernel's lazy numbers: the nearest double, ties to the lower one.
inline double exact_double(const mpq_class& e) {
    const double d = e.get_d();  // truncated towards zero: one of the two doubles around e
    if (mpq_class(d) == e) return d;
    const double lo = cmp(e, d) > 0 ? d : std::nextafter(d, -INFINITY);
    const double hi = std::nextafter(lo, INFINITY);
    const int c = cmp(mpq_class(e - lo), mpq_class(hi - e));
    return c > 0 ? hi : lo;
}

}  // namespace tex::detail
