// Deterministic randomness.
//
// Every random value in libtex is a pure function of a key (a cell's geometry, a tile of
// the plane, a site), a stream number n and the global seed, never of a pointer, an
// index or the order in which threads visit cells. The same script and seed therefore
// give the same bytes with any number of threads (ARCHITECTURE.md, "Random").
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "libtex/geometry.hpp"

namespace tex {

// Global seed used by every random operator (default 0). Setting it also restarts the
// numbering of the streams (see below) and the unkeyed Random(min, max) of the calling
// thread, so a script that starts with SetSeed(n) draws the same values every time it runs.
void SetSeed(std::uint64_t seed);
std::uint64_t GetSeed();

// SplitMix64 finaliser: a good 64-bit mixing function.
inline std::uint64_t mix64(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}
inline std::uint64_t hash_combine(std::uint64_t h, std::uint64_t v) { return mix64(h ^ mix64(v)); }
inline std::uint64_t hash_double(std::uint64_t h, double v) {
    if (v == 0.0) v = 0.0;  // -0 and +0 hash alike
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return hash_combine(h, bits);
}
inline std::uint64_t hash_point(std::uint64_t h, const Point& p) {
    return hash_double(hash_double(h, p.x), p.y);
}
// Uniform double in [0, 1) from a 64-bit hash.
inline double unit_from_hash(std::uint64_t h) { return double(h >> 11) * 0x1.0p-53; }

// A small counter-based generator: value i is a pure function of (key, i).
class KeyedRng {
public:
    explicit KeyedRng(std::uint64_t key) : key_(key) {}
    std::uint64_t next_u64() { return mix64(key_ ^ mix64(++counter_)); }
    double uniform() { return unit_from_hash(next_u64()); }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    // Poisson-distributed count with the given mean (inversion; fine for small means,
    // normal approximation above 500).
    std::uint32_t poisson(double mean);

private:
    std::uint64_t key_;
    std::uint64_t counter_ = 0;
};

namespace detail {
// The random state of a thread, captured by parallel_for in the calling thread and derived
// for each work item (ItemScope), whatever thread runs it.
struct StreamState {
    bool active;
    std::uint64_t key, counter, stream_key, stream_count;
    bool has_seed;
    std::uint64_t seed;
    const char* no_random;  // the operator of an open NoRandomScope, or nullptr
};
StreamState capture_stream_state();
void restore_stream_state(const StreamState& s);
class ItemScope {
public:
    ItemScope(const StreamState& parent, std::size_t i);
    ~ItemScope();
    ItemScope(const ItemScope&) = delete;
    ItemScope& operator=(const ItemScope&) = delete;

private:
    StreamState saved_;
};
// While alive on this thread, every seeded random draw (Random on cells, Random(min, max),
// the random partitions: all go through GetSeed) throws tex::Error naming `op`. A regular
// mapper of a tiled map (tiled.hpp) runs in one: a random value would break the period.
class NoRandomScope {
public:
    explicit NoRandomScope(const char* op);
    ~NoRandomScope();
    NoRandomScope(const NoRandomScope&) = delete;
    NoRandomScope& operator=(const NoRandomScope&) = delete;

private:
    const char* saved_;
};
}  // namespace detail

// Scope that binds the unkeyed Random(min, max) of the current thread to a cell key, so
// that a mapper calling Random(min, max) gets the same values whatever thread runs it;
// streams created inside it are numbered under the same key.
class RandomScope {
public:
    explicit RandomScope(std::uint64_t key);
    ~RandomScope();
    RandomScope(const RandomScope&) = delete;
    RandomScope& operator=(const RandomScope&) = delete;

private:
    detail::StreamState saved_;
};

// Scope in which GetSeed() on this thread, and in the work items it starts, is `seed`
// instead of the global seed: a library call (a pipeline run) draws from its own seed
// without changing the process's (SetSeed is global).
class SeedScope {
public:
    explicit SeedScope(std::uint64_t seed);
    ~SeedScope();
    SeedScope(const SeedScope&) = delete;
    SeedScope& operator=(const SeedScope&) = delete;

private:
    detail::StreamState saved_;
};

// Scope at whose end the global seed, and this thread's stream numbering and unkeyed
// Random(min, max), are what they were at its start: a library call that runs a user's
// script (which may call SetSeed) leaves the process's seed as it found it.
class SavedSeed {
public:
    SavedSeed();
    ~SavedSeed();
    SavedSeed(const SavedSeed&) = delete;
    SavedSeed& operator=(const SavedSeed&) = delete;

private:
    std::uint64_t seed_;
    std::uint64_t free_counter_;
    detail::StreamState stream_;
};

// Random value in [min, max): inside a mapper it is keyed by the visited cell and the
// call count in that mapper; outside mappers it is a seeded stream of the calling thread.
double Random(double min, double max);

// ---- Streams ----
//
// Every random operator (UniformPartition, RandomPartition) draws from a stream of its own,
// fixed when the operator is created:
//  - at the top of a script, the n-th random operator created gets stream n (numbered per
//    thread from the last SetSeed or StreamScope), so two identical calls differ and the
//    same script gives the same streams on every run;
//  - inside a mapper, the n-th one created for a cell gets a stream keyed by that cell's
//    geometry, so the result does not depend on which thread visits the cell first;
//  - an explicit seed gives a stream of its own that repeats on purpose (the same seed,
//    the same sites).
// Work items of parallel_for run under a stream keyed by their index, so streams created
// there do not depend on the thread either.

// A fresh stream for an operator being created now.
std::uint64_t NextStream();
// The stream an explicit seed names.
std::uint64_t SeededStream(std::uint64_t seed);

// Scope in which the numbering of streams restarts under `key` (0: as at the start of a
// program); the previous numbering comes back at the end of the scope. Library entry points
// use it so that a call does not change what the next one draws.
class StreamScope {
public:
    explicit StreamScope(std::uint64_t key);
    ~StreamScope();
    StreamScope(const StreamScope&) = delete;
    StreamScope& operator=(const StreamScope&) = delete;

private:
    std::uint64_t saved_key_;
    std::uint64_t saved_count_;
};



}  // namespace tex
