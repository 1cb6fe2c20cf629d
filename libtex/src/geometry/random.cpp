#include "libtex/random.hpp"

#include <atomic>
#include <cmath>
#include <cstring>

#include "libtex/error.hpp"

namespace tex {
namespace {

std::atomic<std::uint64_t> g_seed{0};

struct ThreadStream {
    bool active = false;  // inside a mapper: keyed by the visited cell
    std::uint64_t key = 0;
    std::uint64_t counter = 0;
    std::uint64_t free_counter = 0;  // outside mappers
    std::uint64_t stream_key = 0;    // numbering of the streams of new operators
    std::uint64_t stream_count = 0;
    bool has_seed = false;  // a SeedScope is open: its seed, not the global one
    std::uint64_t seed = 0;
};
thread_local ThreadStream t_stream;

constexpr std::uint64_t kStreamTag = 0x5354524541ULL;

}  // namespace

void SetSeed(std::uint64_t seed) {
    g_seed.store(seed);
    t_stream.free_counter = 0;
    if (!t_stream.active) t_stream.stream_count = 0;
}

std::uint64_t NextStream() {
    return hash_combine(hash_combine(kStreamTag, t_stream.stream_key), ++t_stream.stream_count);
}

std::uint64_t SeededStream(std::uint64_t seed) { return hash_combine(mix64(kStreamTag ^ 0x5345454455ULL), seed); }

StreamScope::StreamScope(std::uint64_t key) : saved_key_(t_stream.stream_key), saved_count_(t_stream.stream_count) {
    t_stream.stream_key = key;
    t_stream.stream_count = 0;
}

StreamScope::~StreamScope() {
    t_stream.stream_key = saved_key_;
    t_stream.stream_count = saved_count_;
}

static thread_local const char* t_no_random = nullptr;

std::uint64_t GetSeed() {
    if (t_no_random)
        throw Error(t_no_random, "a regular mapper of a tiled map drew a random value (it would break the "
                                 "period); draw it in a GhostMap mapper instead");
    return t_stream.has_seed ? t_stream.seed : g_seed.load();
}

namespace detail {
NoRandomScope::NoRandomScope(const char* op) : saved_(t_no_random) { t_no_random = op; }
NoRandomScope::~NoRandomScope() { t_no_random = saved_; }
}  // namespace detail

SeedScope::SeedScope(std::uint64_t seed) : saved_(detail::capture_stream_state()) {
    t_stream.has_seed = true;
    t_stream.seed = seed;
    t_stream.free_counter = 0;
}

SeedScope::~SeedScope() { detail::restore_stream_state(saved_); }

SavedSeed::SavedSeed()
    : seed_(g_seed.load()), free_counter_(t_stream.free_counter), stream_(detail::capture_stream_state()) {}

SavedSeed::~SavedSeed() {
    g_seed.store(seed_);
    t_stream.free_counter = free_counter_;
    detail::restore_stream_state(stream_);
}

std::uint32_t KeyedRng::poisson(double mean) {
    if (mean <= 0) return 0;
    if (mean > 500) {
        // Box-Muller normal approximation.
        const double u1 = std::max(uniform(), 1e-300), u2 = uniform();
        const double z = std::sqrt(-2 * std::log(u1)) * std::cos(2 * pi * u2);
        const double v = std::round(mean + std::sqrt(mean) * z);
        return v < 0 ? 0u : std::uint32_t(v);
    }
    const double limit = std::exp(-mean);
    double p = uniform();
    std::uint32_t k = 0;
    while (p > limit) {
        p *= uniform();
        ++k;
    }
    return k;
}

namespace detail {

StreamState capture_stream_state() {
    return {t_stream.active,   t_stream.key,  t_stream.counter, t_stream.stream_key, t_stream.stream_count,
            t_stream.has_seed, t_stream.seed, t_no_random};
}

void restore_stream_state(const StreamState& s) {
    t_stream.active = s.active;
    t_stream.key = s.key;
    t_stream.counter = s.counter;
    t_stream.stream_key = s.stream_key;
    t_stream.stream_count = s.stream_count;
    t_stream.has_seed = s.has_seed;
    t_stream.seed = s.seed;
    t_no_random = s.no_random;
}

ItemScope::ItemScope(const StreamState& parent, std::size_t i) : saved_(capture_stream_state()) {
    const std::uint64_t base = hash_combine(hash_combine(parent.stream_key ^ 0x504152ULL, parent.stream_count), i);
    t_stream.stream_key = base;
    t_stream.stream_count = 0;
    t_stream.key = parent.active ? hash_combine(hash_combine(parent.key, parent.counter), i) : base;
    t_stream.active = true;
    t_stream.counter = 0;
    t_stream.has_seed = parent.has_seed;
    t_stream.seed = parent.seed;
    t_no_random = parent.no_random;  // whichever thread runs the item
}

ItemScope::~ItemScope() { restore_stream_state(saved_); }

}  // namespace detail

RandomScope::RandomScope(std::uint64_t key) : saved_(detail::capture_stream_state()) {
    t_stream.active = true;
    t_stream.key = key;
    t_stream.counter = 0;
    t_stream.stream_key = hash_combine(key, 0x43454c4cULL);
    t_stream.stream_count = 0;
}

RandomScope::~RandomScope() { detail::restore_stream_state(saved_); }

double Random(double min, double max) {
    std::uint64_t h;
    if (t_stream.active) {
        h = hash_combine(hash_combine(mix64(GetSeed() ^ 0x52414e44ULL), t_stream.key),
                         ++t_stream.counter);
    } else {
        h = hash_combine(mix64(GetSeed() ^ 0x46524545ULL), ++t_stream.free_counter);
    }
    return min + (max - min) * unit_from_hash(h);
}

}  // namespace tex
