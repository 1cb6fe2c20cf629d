// Threads used to evaluate independent cells and regions.
//
// Work items are independent and their results are stored by index, so the output does
// not depend on the number of threads, nor on which thread runs an item. A nested call (a
// mapper that evaluates a sub-scale arrangement, the cells of one face among many) runs in
// the worker that made it; the threads of the outermost call that have run out of items
// help with it (one large face drawn after the small ones is shared, not left to one
// thread). A caller waits for its helpers: it must not hold a lock its items take (Python's
// GIL: release it before evaluating).
#pragma once

#include <cstddef>
#include <functional>

namespace tex {

// Number of worker threads (0 = all hardware threads). Default: all.
void SetThreads(unsigned n);
unsigned GetThreads();

// Scope in which GetThreads() on this thread, and so the parallel_for it starts, is `n`
// (0 = all hardware threads) instead of the global setting: a library call (a pipeline run)
// uses its own thread count without changing the process's (SetThreads is global).
class ThreadsScope {
public:
    explicit ThreadsScope(unsigned n);
    ~ThreadsScope();
    ThreadsScope(const ThreadsScope&) = delete;
    ThreadsScope& operator=(const ThreadsScope&) = delete;

private:
    bool saved_set_;
    unsigned saved_;
};

// Runs body(i) for i in [0, n), possibly in parallel; rethrows the first exception (the
// one of the smallest index) after all workers stop.
void parallel_for(std::size_t n, const std::function<void(std::size_t)>& body);

}  // namespace tex
