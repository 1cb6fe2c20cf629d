// Tiled planar maps against the planar-map engine on the brick wall of teaser (c), the job
// of the thesis's Table 4.1. One size per process, so that the peak memory it prints is
// this size's: bench_tiled.py runs it over the sizes and writes docs/tiled.md.
//
//   bench_tiled --cells N --engine tiled|planar [--runs R]
//
// prints one line: cells N, bricks drawn, operator seconds, conversion seconds at 1 and 2
// threads (medians of R runs; planar: the whole evaluation, at 2 threads), peak RSS in KiB.
//
//   bench_tiled --engine queries [--runs R]
//
// times FaceLabelsAt on the wall instead: the first query (which builds the point locator),
// then the median over R batches of the time per query of 100,000 random points near the
// origin and 100,000 points a million periods away (it should not depend on where).
//
//   bench_tiled --engine distance [--runs R]
//
// times DistanceToCurves against the linear scan it replaced (DistanceToCurvesByScan) on
// the wall (3 elements per period) and on 24-gons in a grid of 20 x 20 cells per period
// (400 elements, 9,600 segments): the first query (which builds the grid), then the median
// over R batches of the time per query of 2,000 random points, near the origin and a
// million periods away.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "gallery_teasers.hpp"
#include "libtex/tex.hpp"

using namespace tex;
namespace tz = gallery::teasers;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

template <class F>
double median_time(int runs, F&& f) {
    std::vector<double> t;
    for (int k = 0; k < runs; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        t.push_back(seconds_since(t0));
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

long peak_rss_kib() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

// A square window holding about `cells` bricks: the wall has 3 bricks per 400 x 480 period.
Region window_for(double cells) {
    const double side = std::sqrt(cells * 400.0 * 480.0 / 3.0);
    return Region::rectangle(0, 0, side, side);
}

}  // namespace

int main(int argc, char** argv) {
    double cells = 9000;
    int runs = 5;
    std::string engine = "tiled";
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--cells")) cells = std::atof(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--runs")) runs = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--engine")) engine = argv[i + 1];
    }
    const Region w = window_for(cells);
    if (engine == "planar") {
        ThreadsScope threads(2);
        std::size_t n = 0;
        const double t = median_time(runs, [&] { n = tz::shrunk_bricks()(w).curves.size(); });
        std::printf("%.0f %zu - - %.6f %ld\n", cells, n, t, peak_rss_kib());
        return 0;
    }
    if (engine == "queries") {
        const TiledMap wall = MapToFaces(
            tz::shrink_brick, MapToEdges(tz::keep_brick_joints, GridPartition(tz::brick_rows(), tz::brick_columns(), Tiled())));
        auto t0 = std::chrono::steady_clock::now();
        std::size_t sink = wall.FaceLabelsAt({1, 1}).names().size();
        const double first = seconds_since(t0);
        double per_query[2];
        for (int far = 0; far < 2; ++far) {
            const Point base = far ? wall.shift(1000000, -1000000) : Point{0, 0};
            std::vector<Point> pts;
            std::uint64_t h = 12345;
            for (int k = 0; k < 100000; ++k) {
                h = mix64(h + 1);
                const double u = unit_from_hash(h), v = unit_from_hash(mix64(h ^ 0x55));
                pts.push_back(base + Point{u * 4000, v * 4000});
            }
            per_query[far] = median_time(runs, [&] {
                for (const auto& p : pts) sink += wall.FaceLabelsAt(p).names().size();
            }) / double(pts.size());
        }
        std::printf("first query %.6f s; per query near %.3f us, far %.3f us (%zu)\n", first, per_query[0] * 1e6,
                    per_query[1] * 1e6, sink % 2);
        return 0;
    }
    if (engine == "distance") {
        auto polygon = [](const Face& f) {
            std::vector<Point> pts;
            for (int k = 0; k < 24; ++k) pts.push_back(Centroid(f) + Point{std::cos(k * pi / 12), std::sin(k * pi / 12)} * 3.0);
            return Polyline(pts, true);
        };
        std::vector<double> widths;
        for (int k = 0; k < 20; ++k) widths.push_back(8 + k % 3);
        const std::pair<const char*, TiledMap> maps[] = {
            {"wall", MapToFaces(tz::shrink_brick, MapToEdges(tz::keep_brick_joints,
                                                             GridPartition(tz::brick_rows(), tz::brick_columns(), Tiled())))},
            {"24-gons, 20 x 20 per period",
             MapToFaces(polygon, GridPartition(StripesProperties(0, widths), StripesProperties(pi / 2, widths), Tiled()))},
        };
        double sink = 0;
        for (const auto& [name, map] : maps) {
            auto t0 = std::chrono::steady_clock::now();
            sink += map.DistanceToCurves({1, 1});
            const double first = seconds_since(t0);
            double per[2][2];  // [far][indexed]
            for (int far = 0; far < 2; ++far) {
                const Point base = far ? map.shift(1000000, -1000000) : Point{0, 0};
                std::vector<Point> pts;
                std::uint64_t h = 777;
                for (int k = 0; k < 2000; ++k) {
                    h = mix64(h + 1);
                    pts.push_back(base + Point{unit_from_hash(h) * 4000, unit_from_hash(mix64(h ^ 0x55)) * 4000});
                }
                per[far][0] = median_time(runs, [&] {
                    for (const auto& p : pts) sink += map.DistanceToCurvesByScan(p);
                }) / double(pts.size());
                per[far][1] = median_time(runs, [&] {
                    for (const auto& p : pts) sink += map.DistanceToCurves(p);
                }) / double(pts.size());
            }
            std::printf("%s: first query %.6f s; per query near: scan %.3f us, index %.3f us; far: scan %.3f us, index %.3f us (%d)\n",
                        name, first, per[0][0] * 1e6, per[0][1] * 1e6, per[1][0] * 1e6, per[1][1] * 1e6, int(sink) % 2);
        }
        return 0;
    }
    TiledMap wall = GridPartition(tz::brick_rows(), tz::brick_columns(), Tiled(CROP));
    const double op = median_time(runs, [&] {
        wall = MapToFaces(tz::shrink_brick,
                          MapToEdges(tz::keep_brick_joints, GridPartition(tz::brick_rows(), tz::brick_columns(), Tiled(CROP))));
    });
    std::size_t n = 0;
    double conv[2];
    for (unsigned th : {1u, 2u}) {
        ThreadsScope threads(th);
        conv[th - 1] = median_time(runs, [&] { n = wall.Convert(w, CROP).curves.size(); });
    }
    std::printf("%.0f %zu %.6f %.6f %.6f %ld\n", cells, n, op, conv[0], conv[1], peak_rss_kib());
    return 0;
}
