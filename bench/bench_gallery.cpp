// Times every gallery example (load elements, evaluate on the 2000 x 2000 window, write
// the SVG text) with one and two threads, and compares the medians with the times the
// thesis publishes in its Appendix A. With --python-times (written by
// bench/gallery_python_times.py), the report also gives the Python twins' medians.
//
// With --detail K (4 by default; 1: none), each example is timed once more with its
// SVG elements K times finer (gallery::element), on one thread.
//
//   bench_gallery [--runs N] [--markdown FILE] [--only NAME[,NAME...]] [--python-times FILE] [--detail K]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "gallery.hpp"

namespace {

double run_once(const gallery::Example& e) {
    const auto t0 = std::chrono::steady_clock::now();
    const tex::Arrangement a = e.build(gallery::default_elements_dir());
    const std::string svg =
        tex::ToSVG(a(tex::Region::rectangle(0, 0, gallery::kSize, gallery::kSize)), gallery::kSize);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (svg.size() < 100) std::abort();  // keep the work observable
    return s;
}

double median_time(const gallery::Example& e, unsigned threads, int runs) {
    tex::SetThreads(threads);
    run_once(e);  // warm-up (page faults, label table)
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) t.push_back(run_once(e));
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

std::string fmt(double v, const char* f) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 7;
    int detail = 4;
    std::string markdown, only, python_times;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--markdown" && i + 1 < argc) markdown = argv[++i];
        else if (a == "--only" && i + 1 < argc) only = argv[++i];
        else if (a == "--python-times" && i + 1 < argc) python_times = argv[++i];
        else if (a == "--detail" && i + 1 < argc) detail = std::max(1, std::atoi(argv[++i]));
        else {
            std::cerr << "usage: bench_gallery [--runs N] [--markdown FILE] [--only NAMES] [--python-times FILE] [--detail K]\n";
            return 2;
        }
    }
    std::map<std::string, std::pair<double, double>> py;
    if (!python_times.empty()) {
        std::ifstream in(python_times);
        if (!in) {
            std::cerr << "bench_gallery: cannot read " << python_times << "\n";
            return 2;
        }
        std::string name;
        double t1, t2;
        while (in >> name >> t1 >> t2) py[name] = {t1, t2};
    }
    std::ostringstream md;
    md << "| example | published (thesis) | C++ 1 thread | C++ 2 threads | speed-up, C++ 1 thread | C++ 2 threads";
    if (detail > 1)
        md << " | C++ 1 thread, elements " << detail << "x finer | speed-up | time / time at detail 1";
    if (!py.empty()) md << " | Python 1 thread | Python 2 threads | speed-up, Python 1 thread | Python 2 threads";
    md << " |\n|---|---:|---:|---:|---:|---:" << (detail > 1 ? "|---:|---:|---:" : "")
       << (py.empty() ? "" : "|---:|---:|---:|---:") << "|\n";
    std::printf("%-10s %10s %12s %12s %10s %10s\n", "example", "published", "1 thread", "2 threads", "x (1t)", "x (2t)");
    for (const auto& e : gallery::examples()) {
        if (!only.empty() && ("," + only + ",").find("," + e.name + ",") == std::string::npos) continue;
        const double t1 = median_time(e, 1, runs);
        const double t2 = median_time(e, 2, runs);
        double td = 0;
        if (detail > 1) {
            gallery::SetElementDetail(detail);
            td = median_time(e, 1, runs);
            gallery::SetElementDetail(1);
        }
        const bool known = e.published_seconds > 0, published = e.published_seconds >= 0;
        const double pub = known ? e.published_seconds : 1.0;  // "< 1 sec" in the thesis
        const std::string pub_s = !published ? std::string("n/a") : known ? fmt(pub, "%.0f s") : std::string("< 1 s");
        const std::string r1 = !published ? std::string("-") : (known ? "" : "> ") + fmt(pub / t1, "%.0f");
        const std::string r2 = !published ? std::string("-") : (known ? "" : "> ") + fmt(pub / t2, "%.0f");
        std::printf("%-10s %10s %10.1f ms %10.1f ms %10s %10s\n", e.name.c_str(), pub_s.c_str(), t1 * 1e3, t2 * 1e3,
                    r1.c_str(), r2.c_str());
        md << "| " << e.title << " | " << pub_s << " | " << fmt(t1 * 1e3, "%.1f ms") << " | "
           << fmt(t2 * 1e3, "%.1f ms") << " | " << r1 << " | " << r2;
        if (detail > 1) {
            const std::string rd = !published ? std::string("-") : (known ? "" : "> ") + fmt(pub / td, "%.0f");
            md << " | " << fmt(td * 1e3, "%.1f ms") << " | " << rd << " | " << fmt(td / t1, "%.2f");
            std::printf("%-10s %10s %10.1f ms (elements %dx finer) %10s  %.2fx the detail-1 time\n", "", "", td * 1e3,
                        detail, rd.c_str(), td / t1);
        }
        if (!py.empty()) {
            const auto it = py.find(e.name);
            if (it == py.end()) {
                md << " | - | - | - | -";
            } else {
                const auto [p1, p2] = it->second;
                auto ratio = [&](double t) {
                    return !published ? std::string("-") : (known ? "" : "> ") + fmt(pub / t, "%.0f");
                };
                md << " | " << fmt(p1 * 1e3, "%.1f ms") << " | " << fmt(p2 * 1e3, "%.1f ms") << " | " << ratio(p1)
                   << " | " << ratio(p2);
            }
        }
        md << " |\n";
    }
    if (!markdown.empty()) {
        std::ofstream out(markdown);
        out << "<!-- written by `cmake --build build --target bench` (bench_gallery and "
               "bench/gallery_python_times.py); medians of "
            << runs << " runs after one warm-up; " << std::thread::hardware_concurrency() << " hardware threads -->\n"
            << "# The Appendix A gallery against the thesis's published times\n\n"
            << "Each example is built, evaluated on the 2000 x 2000 window and written as SVG text; the "
               "speed-up is the thesis's Appendix A time over our median (the thesis gives \"< 1 sec\" for "
               "some: their ratio is a lower bound). The Python column runs the twin script of "
               "bindings/examples/gallery.py in one interpreter (same bytes as C++).";
    if (detail > 1)
        out << " The finer elements are the same SVG elements with " << detail
            << " times their points (gallery::element: each smooth stretch along its Catmull-Rom cubic, "
               "straight ones straight): a merge's cost should follow its curves and crossings, not its points.";
    out << "\n\n"
            << md.str();
        std::cout << "report written to " << markdown << "\n";
    }
    return 0;
}
