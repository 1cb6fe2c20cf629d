#include "libtex/parallel.hpp"

#include "libtex/fields.hpp"
#include "libtex/random.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tex {
namespace {

std::atomic<unsigned> g_threads{0};
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

namespace {

// The work of one parallel_for: items handed out by an atomic counter; the first error (of
// the smallest index) kept.
struct Job {
    std::size_t n;
    const std::function<void(std::size_t)>* item;
    std::atomic<std::size_t> next{0};
    unsigned helpers = 0;  // threads other than the caller in it (guarded by the team's mutex)
    std::mutex error_mutex;
    std::size_t error_index;
    std::exception_ptr error;

    Job(std::size_t count, const std::function<void(std::size_t)>& f) : n(count), item(&f), error_index(count) {}
    // Runs items until none is left.
    void run() {
        for (;;) {
            const std::size_t i = next.fetch_add(1);
            if (i >= n) return;
            try {
                (*item)(i);
            } catch (...) {
                std::lock_guard lock(error_mutex);
                if (i < error_index) {
                    error_index = i;
                    error = std::current_exception();
                }
                next.store(n);  // stop handing out work
            }
        }
    }
};

// The threads of an outermost parallel_for. A thread that runs out of the outer items helps
// with the nested calls still running on the others (a face much larger than the rest: its
// cells are shared out) until every outer item is done. Items are keyed by their index, so
// who runs them does not change their results.
struct Team {
    std::mutex mutex;
    std::condition_variable wake;
    std::vector<Job*> open;     // nested jobs that take helpers
    unsigned running;           // threads still on outer items
    std::atomic<unsigned> idle{0};

    explicit Team(unsigned threads) : running(threads) {}

    // An outer thread whose items are done: helps until no outer item runs any more.
    void help() {
        std::unique_lock lock(mutex);
        --running;
        wake.notify_all();
        for (;;) {
            Job* job = nullptr;
            for (Job* j : open)
                if (j->next.load() < j->n) {
                    job = j;
                    break;
                }
            if (job) {
                ++job->helpers;
                lock.unlock();
                job->run();
                lock.lock();
                --job->helpers;
                wake.notify_all();
                continue;
            }
            if (running == 0) break;
            idle.fetch_add(1);
            wake.wait(lock);
            idle.fetch_sub(1);
        }
    }

    // A nested call on one of the team's threads, shared with the idle ones.
    void share(Job& job) {
        {
            std::lock_guard lock(mutex);
            open.push_back(&job);
        }
        wake.notify_all();
        job.run();
        std::unique_lock lock(mutex);
        open.erase(std::find(open.begin(), open.end(), &job));
        wake.wait(lock, [&] { return job.helpers == 0; });
    }
};

thread_local Team* t_team = nullptr;

}  // namespace

void parallel_for(std::size_t n, const std::function<void(std::size_t)>& body) {
    // Each item runs under random streams derived from the caller's and its index, and in
    // the caller's field window, whatever thread runs it.
    const detail::StreamState parent = detail::capture_stream_state();
    const detail::WindowState window = detail::capture_window();
    const std::function<void(std::size_t)> item = [&](std::size_t i) {
        detail::ItemScope scope(parent, i);
        const detail::WindowState saved = detail::capture_window();
        detail::restore_window(window);
        struct Restore {
            const detail::WindowState& w;
            ~Restore() { detail::restore_window(w); }
        } restore{saved};
        body(i);
    };
    if (Team* team = t_team) {
        // Nested: in this thread, shared with the team's idle threads if there are any.
        if (n >= 2 && team->idle.load() > 0) {
            Job job(n, item);
            team->share(job);
            if (job.error) std::rethrow_exception(job.error);
        } else {
            for (std::size_t i = 0; i < n; ++i) item(i);
        }
        return;
    }
    const unsigned threads = unsigned(std::min<std::size_t>(GetThreads(), n));
    if (threads <= 1) {
        for (std::size_t i = 0; i < n; ++i) item(i);
        return;
    }
    Job job(n, item);
    Team team(threads);
    auto work = [&] {
        t_team = &team;
        job.run();
        team.help();
        t_team = nullptr;
    };
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& th : pool) th.join();
    if (job.error) std::rethrow_exception(job.error);
}

}  // namespace tex
