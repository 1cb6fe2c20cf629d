#include "libtex/parallel.hpp"

#include "libtex/fields.hpp"
#include "libtex/random.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tex {
namespace {

std::atomic<unsigned> g_threads{0};
thread_local bool t_in_worker = false;
// A ThreadsScope is open on this thread: its count, not the global one.
thread_local bool t_threads_set = false;
thread_local unsigned t_threads = 0;

}  // namespace

void SetThreads(unsigned n) { g_threads.store(n); }

ThreadsScope::ThreadsScope(unsigned n) : saved_set_(t_threads_set), saved_(t_threads) {
    t_threads_set = true;
    t_threads = n;
}

ThreadsScope::~ThreadsScope() {
    t_threads_set = saved_set_;
    t_threads = saved_;
}

unsigned GetThreads() {
    // glibc answers hardware_concurrency by reading /sys on every call: ask once.
    static const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const unsigned n = t_threads_set ? t_threads : g_threads.load();
    return n == 0 ? hardware : n;
}

void parallel_for(std::size_t n, const std::function<void(std::size_t)>& body) {
    // Each item runs under random streams derived from the caller's and its index, and in
    // the caller's field window, whatever thread runs it.
    const detail::StreamState parent = detail::capture_stream_state();
    const detail::WindowState window = detail::capture_window();
    auto item = [&](std::size_t i) {
        detail::ItemScope scope(parent, i);
        const detail::WindowState saved = detail::capture_window();
        detail::restore_window(window);
        struct Restore {
            const detail::WindowState& w;
            ~Restore() { detail::restore_window(w); }
        } restore{saved};
        body(i);
    };
    // A nested call runs serially in its worker: no need to ask for a thread count.
    const unsigned threads = t_in_worker ? 1u : unsigned(std::min<std::size_t>(GetThreads(), n));
    if (threads <= 1) {
        for (std::size_t i = 0; i < n; ++i) item(i);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::mutex error_mutex;
    std::size_t error_index = n;
    std::exception_ptr error;
    auto work = [&] {
        const bool saved = t_in_worker;
        t_in_worker = true;
        for (;;) {
            const std::size_t i = next.fetch_add(1);
            if (i >= n) break;
            try {
                item(i);
            } catch (...) {
                std::lock_guard lock(error_mutex);
                if (i < error_index) {
                    error_index = i;
                    error = std::current_exception();
                }
                next.store(n);  // stop handing out work
            }
        }
        t_in_worker = saved;
    };
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& th : pool) th.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace tex
