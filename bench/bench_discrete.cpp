// bench_discrete: greedy distribution (seed 004, Fig. 1a's program) of 100,000 hatches,
// in a plain domain and in a grey image read as a density; then a dart throwing run far
// past saturation (the scree program's regime: most darts refused for their spacing), in
// microseconds per dart. Prints the median of --runs.
//
//   bench_discrete [--runs N] [--count N] [--darts N]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "libtex/discrete.hpp"
#include "libtex/random.hpp"

namespace {

using namespace tex::disc;

// The side of the square domain: 100,000 hatches of 24 x 3 cover about a third of it.
constexpr double kSide = 6000;
// Tries allowed per hatch wanted before the run gives up (it never should here).
constexpr long long kTriesPerHatch = 20;

// A 600 x 600 grey image over the domain (10 units a pixel): light in the middle, dark at
// the border, read as the density of the pins.
tex::GridSamples grey_image() {
    tex::GridSamples g;
    g.width = g.height = 600;
    g.transform = {0, kSide / 600, 0, kSide, 0, -kSide / 600};
    auto v = std::make_shared<std::vector<float>>(600 * 600);
    for (int r = 0; r < 600; ++r)
        for (int c = 0; c < 600; ++c)
            (*v)[std::size_t(r) * 600 + c] =
                float(0.3 + 0.7 * std::hypot(r - 300.0, c - 300.0) / 425.0);
    g.values = v;
    return g;
}

struct Run {
    double seconds;
    long long thrown;
    std::size_t kept;
};

Run once(long long count, bool image) {
    tex::StreamScope fresh(0);
    const auto t0 = std::chrono::steady_clock::now();
    RegionSet hatches;
    auto tries = std::make_shared<long long>(0);
    const Condition loop = [&hatches, tries, count] {
        return (long long)hatches.size() < count && (*tries)++ < kTriesPerHatch * count;
    };
    const tex::Region frame = Image(kSide, kSide);
    const Pinning pins =
        image ? RandomPinning(frame, tex::GridField(grey_image())) : RandomPinning(frame);
    const long long thrown = greedy_distribution(hatches, loop, pins, Translation(BuiltinHatch()),
                                                 Not(Overlap(hatches)));
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return {s, thrown, hatches.size()};
}

// Past saturation: hexagonal dots of diameter 1 at least 1 apart, thrown into a 400 x 400
// square, `darts` darts (about 25 per dot kept, as the scree program throws on Chamonix).
Run saturated(long long darts) {
    tex::StreamScope fresh(0);
    const auto t0 = std::chrono::steady_clock::now();
    RegionSet dots;
    const long long thrown =
        greedy_distribution(dots, CountUpTo(darts), RandomPinning(Image(400, 400)),
                            Translation(BuiltinCircle(0.5, 6)), Not(MinimalDistance(dots, 1.0)));
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return {s, thrown, dots.size()};
}

template <class F>
Run median_of(int runs, F f) {
    std::vector<Run> rs;
    for (int r = 0; r < runs; ++r) rs.push_back(f());
    std::sort(rs.begin(), rs.end(), [](const Run& a, const Run& b) { return a.seconds < b.seconds; });
    return rs[rs.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 5;
    long long count = 100000, darts = 1000000;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--runs")
            runs = std::max(1, std::atoi(argv[i + 1]));
        else if (a == "--count")
            count = std::max(1LL, std::atoll(argv[i + 1]));
        else if (a == "--darts")
            darts = std::max(1LL, std::atoll(argv[i + 1]));
        else {
            std::fprintf(stderr, "usage: bench_discrete [--runs N] [--count N] [--darts N]\n");
            return 2;
        }
    }
    std::printf("| domain | hatches kept | darts thrown | median s (%d runs) | min s | max s |\n",
                runs);
    std::printf("|---|---|---|---|---|---|\n");
    for (const bool image : {false, true}) {
        std::vector<Run> rs;
        for (int r = 0; r < runs; ++r) rs.push_back(once(count, image));
        std::sort(rs.begin(), rs.end(),
                  [](const Run& a, const Run& b) { return a.seconds < b.seconds; });
        const Run& m = rs[rs.size() / 2];
        std::printf("| %s | %zu | %lld | %.2f | %.2f | %.2f |\n",
                    image ? "6000 x 6000, grey image as density" : "6000 x 6000, uniform", m.kept,
                    m.thrown, m.seconds, rs.front().seconds, rs.back().seconds);
    }
    const Run m = median_of(runs, [darts] { return saturated(darts); });
    std::printf("\n| past saturation (400 x 400, dots 1 apart) | dots kept | darts thrown | median s | us per dart |\n");
    std::printf("|---|---|---|---|---|\n");
    std::printf("| MinimalDistance against the kept dots | %zu | %lld | %.2f | %.2f |\n", m.kept, m.thrown,
                m.seconds, 1e6 * m.seconds / double(m.thrown));
    return 0;
}
