// bench_synthesis: SynthesizeAlongCurve in the style of Table 1 of seed 002 (Zhou, Jiang and
// Lefebvre 2014): pieces in the exemplar and in the result, DP time, DP table size, against
// the paper's published DP times at the same piece counts.
//
//   bench_synthesis [--runs N] [--markdown FILE] [--elements DIR]
//   bench_synthesis --defaults [--runs N] [--markdown FILE] [--elements DIR]
//
// --defaults: the options' defaults (one component, holes free, topology slicing) on the five
// exemplars of scripts/synth_exemplars.py and the project's three, along a wave of length
// 1500 under a band of 40: the seed's event grouping 0.2 (the default before the automatic
// choice) against the automatic choice.
//
// The exemplar (synth_vine.svg) is cut uniformly into as many pieces as the paper's row has,
// and the curve is made as long as that row's result (pieces x piece width), open or closed
// (the rows the paper marks as cyclic). Every row asks for one component and uses the
// autocorrelation penalty, as the paper's rows do.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "libtex/tex.hpp"

namespace {

struct Row {
    const char* model;
    bool cyclic;
    int pieces_in;
    int pieces_out;
    double paper_dp;  // seconds
    double paper_mb;
};

// Table 1 of the seed.
const std::vector<Row> kRows = {
    {"Figure 13 (1)", false, 11, 56, 0.13, 62},      {"Figure 13 (2)", false, 14, 74, 1.3, 67.3},
    {"Figure 13 (3)", false, 14, 109, 9.9, 101.5},   {"Figure 13 (4)", false, 13, 65, 2.2, 70.5},
    {"Figure 13 (5)", false, 15, 70, 1.2, 64.9},     {"Figure 13 (6)", false, 10, 75, 0.78, 61},
    {"Figure 1 (left), cyclic", true, 20, 147, 62.1, 230},
    {"Chair side (circle), cyclic", true, 18, 190, 143, 453},
    {"Chair foot", false, 12, 130, 8.3, 73.9},       {"Chair back (axis 1)", false, 15, 64, 0.007, 88.7},
    {"Chair back (axis 2)", false, 14, 102, 5.9, 295.8},
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;
}

// One call of SynthesizeAlongCurve, `runs` times: a cell of the --defaults table.
struct Try {
    bool ok = false;
    std::string error;
    tex::SynthesisReport rep;
    double seconds = 0;
};

Try attempt(const tex::Curves& ex, const tex::Curves& curve, double band, const tex::SynthesisOptions& o, int runs) {
    Try t;
    std::vector<double> times;
    for (int k = 0; k < runs; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        try {
            tex::SynthesizeAlongCurve(ex, curve, band, o, &t.rep);
            t.ok = true;
        } catch (const tex::Error& e) {
            t.error = e.what();
        }
        times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    t.seconds = median(times);
    return t;
}

int defaults_table(int runs, const std::string& markdown, const std::string& elements) {
    const std::vector<std::pair<const char*, const char*>> exemplars = {
        {"synth_rungs", "ladder, nine evenly spaced rungs (8 holes)"},
        {"synth_bar_beads", "beads on a bar, up and down"},
        {"synth_rings", "chain of nine overlapping rings (9 holes)"},
        {"synth_truss", "zig-zag between two rails (13 triangular holes)"},
        {"synth_dots", "loose dots above a bar, beads under it (6 components)"},
        {"synth_ladder", "project's ladder (4 holes)"},
        {"synth_beads", "project's beads (holes, loose diamonds)"},
        {"synth_vine", "project's vine"},
    };
    std::vector<tex::Point> p;
    for (int i = 0; i <= 150; ++i) p.push_back({1500.0 * i / 150, 60 * std::sin(3 * tex::pi * i / 150)});
    const tex::Curves curve = tex::Polyline(p);
    std::ostringstream md;
    md << "<!-- written by `build/bench/bench_synthesis --defaults`; medians of " << runs << " runs -->\n"
       << "| exemplar | seed's 0.2 W (old default) | automatic (new default) | grouping chosen (slicings tried) "
          "| pieces in exemplar / result | time old / new |\n"
       << "|---|---|---|---|---|---:|\n";
    for (const auto& [name, what] : exemplars) {
        const tex::Curves ex = tex::ImportSVG(elements + "/" + name + ".svg");
        tex::SynthesisOptions seed;
        seed.event_grouping = 0.2;
        const Try old = attempt(ex, curve, 40, seed, runs);
        const Try now = attempt(ex, curve, 40, tex::SynthesisOptions{}, runs);
        auto cell = [](const Try& t) {
            if (!t.ok) {
                const std::string e = t.error.substr(t.error.find(": ") + 2);
                return "error: " + e.substr(0, e.find(" within")) + " ...";
            }
            char c[128];
            std::snprintf(c, sizeof c, "%d component(s), %d hole(s)", t.rep.components, t.rep.holes);
            return std::string(c);
        };
        char line[1024];
        std::snprintf(line, sizeof line, "| `%s`: %s | %s | %s | %g (%d) | %d / %d | %.1f / %.1f ms |\n", name, what,
                      cell(old).c_str(), cell(now).c_str(), now.rep.event_grouping, now.rep.groupings_tried,
                      now.rep.pieces_in_exemplar, now.rep.pieces_in_result, old.seconds * 1e3, now.seconds * 1e3);
        std::cout << line;
        md << line;
    }
    if (!markdown.empty()) std::ofstream(markdown) << md.str();
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 5;
    bool defaults = false;
    std::string markdown, elements = RH_SYNTH_ELEMENTS;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--defaults") defaults = true;
        else if (a == "--runs" && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
        else if (a == "--markdown" && i + 1 < argc) markdown = argv[++i];
        else if (a == "--elements" && i + 1 < argc) elements = argv[++i];
        else {
            std::cerr << "usage: bench_synthesis [--defaults] [--runs N] [--markdown FILE] [--elements DIR]\n";
            return 2;
        }
    }
    if (defaults) return defaults_table(runs, markdown, elements);
    const tex::Curves vine = tex::ImportSVG(elements + "/synth_vine.svg");
    const double band = 40;
    const double width = tex::BBoxWidth(vine) * band / tex::BBoxHeight(vine);
    std::ostringstream md;
    md << "<!-- written by `build/bench/bench_synthesis --markdown docs/benchmarks-synthesis.md`; medians of " << runs
       << " runs; one thread (the DP is serial) -->\n"
       << "| row of Table 1 | cyclic | pieces in exemplar | pieces in result (paper) | pieces in result (ours) "
          "| correct paths | DP entries | DP table | paper DP | our DP (median) | speed-up | whole call (median) |\n"
       << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    std::printf("%-30s %6s %4s %5s %5s %8s %10s %9s %9s %9s %8s\n", "row", "cyclic", "in", "paper", "ours", "paths",
                "entries", "table MB", "paper s", "DP s", "speedup");
    for (const Row& r : kRows) {
        tex::SynthesisOptions o;
        o.slicing = tex::Slicing::Uniform;
        o.slicing_lines = r.pieces_in - 1;
        o.components = 1;
        o.autocorrelation = 0.1;
        o.closed_pattern = r.cyclic;
        o.seed = 1;
        // The result's natural length is pieces_out piece widths (the exemplar spans its
        // width plus a 1% margin on each side).
        const double piece = width * 1.02 / r.pieces_in;
        const double L = piece * r.pieces_out;
        tex::Curves curve;
        if (r.cyclic) {
            std::vector<tex::Point> p;
            const double radius = L / (2 * tex::pi);
            for (int i = 0; i < 720; ++i)
                p.push_back({radius * std::cos(2 * tex::pi * i / 720), radius * std::sin(2 * tex::pi * i / 720)});
            curve = tex::Polyline(p, true);
        } else {
            curve = tex::Polyline({{0, 0}, {L, 0}});
        }
        std::vector<double> dp, whole;
        tex::SynthesisReport rep;
        for (int k = 0; k < runs; ++k) {
            const auto t0 = std::chrono::steady_clock::now();
            tex::SynthesizeAlongCurve(vine, curve, band, o, &rep);
            whole.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            dp.push_back(rep.dp_seconds);
        }
        const double d = median(dp), w = median(whole);
        const double mb = double(rep.dp_bytes) / (1024.0 * 1024.0);
        std::printf("%-30s %6s %4d %5d %5d %8zu %10zu %9.2f %9.3f %9.4f %8.0f\n", r.model, r.cyclic ? "yes" : "no",
                    rep.pieces_in_exemplar, r.pieces_out, rep.pieces_in_result, rep.candidates, rep.dp_entries, mb,
                    r.paper_dp, d, r.paper_dp / d);
        char line[512];
        std::snprintf(line, sizeof line, "| %s | %s | %d | %d | %d | %zu | %zu | %.2f MB | %.3g s | %.4f s | %.0fx | %.4f s |\n",
                      r.model, r.cyclic ? "yes" : "no", rep.pieces_in_exemplar, r.pieces_out, rep.pieces_in_result,
                      rep.candidates, rep.dp_entries, mb, r.paper_dp, d, r.paper_dp / d, w);
        md << line;
    }
    md << "\nPeak resident memory of the whole benchmark process: " << std::lround(peak_rss_mb()) << " MB.\n";
    if (!markdown.empty()) std::ofstream(markdown) << md.str();
    return 0;
}
