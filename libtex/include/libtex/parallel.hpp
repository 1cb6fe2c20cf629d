// Threads used to evaluate independent cells and regions.
//
// Work items are independent and their results are stored by index, so the output does
// not depend on the number of threads. Nested calls (a mapper that evaluates a sub-scale
// arrangement) run serially inside the worker that called them.
#pragma once

#include <cstddef>
#include <functional>

namespace tex {

// Number of worker threads (0 = all hardware threads). Default: all.
void SetThreads(unsigned n);
unsigned GetThreads();

// Runs body(i) for i in [0, n), possibly in parallel; rethrows the first exception (the
// one of the smallest index) after all workers stop.
void parallel_for(std::size_t n, const std::function<void(std::size_t)>& body);

}  // namespace tex
