// rockhatch: rock hatching from a DEM and a labelled partition (thesis Chapter 5).
//
// main only parses the command line (carto/cli.hpp), installs a progress bar and maps
// errors to exit codes; the work is carto::run, which Python and QGIS call too. With
// --script the command hands over to the Python module, which runs the same carto::run
// with the script's style.
#include <cmath>
#include <cstdio>
#include <new>
#include <cerrno>
#include <cstring>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "carto/cli.hpp"
#include "carto/error.hpp"
#include "carto/pipeline.hpp"
#include "carto/progress.hpp"
#include "carto/update.hpp"

#ifdef RH_WITH_JEMALLOC
// The command's own allocator settings, read by jemalloc as the process starts (MALLOC_CONF in
// the environment still overrides them): huge pages for its extents (a drawing churns through
// a few hundred megabytes of small curves: a tenth of the run went to page faults and TLB
// misses) and one arena per CPU (the extents of more arenas than cores, each on huge pages,
// would raise the peak memory for nothing). See docs/engine.md.
extern "C" {
extern const char* malloc_conf;
const char* malloc_conf = "thp:always,percpu_arena:percpu";
}
#endif

namespace {

using carto::Code;
using carto::Error;

// The folder holding this program's own Python package: the installed one beside the program
// (RH_PYTHON_INSTALLED, relative to the program's folder), else the build's; "" if neither.
std::string python_package_dir() {
    std::vector<std::string> candidates;
#ifdef RH_PYTHON_INSTALLED
    char exe[4096];
    const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        std::string dir(exe, std::size_t(n));
        dir = dir.substr(0, dir.rfind('/'));
        candidates.push_back(dir + "/" RH_PYTHON_INSTALLED);
    }
#endif
#ifdef RH_PYTHON_DIR
    candidates.push_back(RH_PYTHON_DIR);
#endif
    for (const auto& c : candidates)
        if (access((c + "/rockhatch/__init__.py").c_str(), R_OK) == 0) return c;
    return "";
}

// Runs `python3 -m rockhatch` with the same arguments (the Python module parses them with
// the same option table; `tiles` is its tiled run). This program's package folder comes
// first on PYTHONPATH.
int run_script(char** argv) {
    const char* env = std::getenv("RH_PYTHON");
    const std::string python = env && *env ? env : "/usr/bin/python3";
    const std::string own = python_package_dir();
    if (!own.empty()) {
        const char* old = std::getenv("PYTHONPATH");
        const std::string path = own + (old && *old ? std::string(":") + old : "");
        setenv("PYTHONPATH", path.c_str(), 1);
    }
    std::vector<char*> args = {const_cast<char*>(python.c_str()), const_cast<char*>("-m"),
                               const_cast<char*>("rockhatch")};
    for (char** a = argv + 1; *a; ++a) args.push_back(*a);
    args.push_back(nullptr);
    execv(python.c_str(), args.data());
    std::fprintf(stderr, "rockhatch: --script and tiles need Python and the rockhatch module: cannot run %s (%s)\n",
                 python.c_str(), std::strerror(errno));
    return 1;
}

}  // namespace

int partition_main(int argc, char** argv);  // apps/partition_cmd.cpp

int main(int argc, char** argv) {
    if (argc > 1 && std::string(argv[1]) == "partition") return partition_main(argc - 1, argv + 1);
    // A tiled run is Python's (rockhatch.tiles, on Dask distributed): `python3 -m rockhatch tiles ...`.
    if (argc > 1 && std::string(argv[1]) == "tiles") return run_script(argv);
    // The web map page over vector tiles (rockhatch.serve): `python3 -m rockhatch serve DIR`.
    if (argc > 1 && std::string(argv[1]) == "serve") return run_script(argv);
    // Redraws the faces whose inputs changed (carto/update.hpp): the run's options and its own.
    const bool update = argc > 1 && std::string(argv[1]) == "update";
    const char* prog = update ? "rockhatch update" : "rockhatch";
    carto::ProgressBar bar(false);
    try {
        const std::vector<std::string> args(argv + 1 + update, argv + argc);
        carto::UpdateCommandLine u;
        if (update) u = carto::parse_update_command_line(args);
        else u.command = carto::parse_command_line(args);
        const carto::CommandLine& cl = u.command;
        if (cl.help) {
            std::cout << (update ? carto::update_help_text() : carto::help_text());
            return 0;
        }
        if (cl.list_styles) {
            std::cout << carto::styles_text();
            return 0;
        }
        if (!cl.script.empty()) {
            // Before Python starts: never write onto an input (update's outputs exist: they are
            // the files it updates).
            carto::Options checked = cl.options;
            checked.overwrite = checked.overwrite || update;
            carto::check_files(checked);
            return run_script(argv);
        }
        bar = carto::ProgressBar(!cl.quiet);
        const carto::Progress progress = [&](double f, const std::string& stage) { return bar(f, stage); };
        if (update) {
            const carto::UpdateReport r = carto::update(cl.options, {u.reset, u.faces}, progress);
            bar.finish();
            if (!cl.quiet)
                for (const auto& n : r.notes) std::fprintf(stderr, "rockhatch update: note: %s\n", n.c_str());
            std::fprintf(stderr,
                         "rockhatch update: %zu faces, %zu redrawn (%zu new), %zu removed; features: %zu removed, %zu "
                         "written, %zu unchanged; %.2f s\n",
                         r.faces, r.redrawn, r.appeared, r.removed, r.deleted, r.written, r.kept, r.seconds);
            return 0;
        }
        const carto::Stats s = carto::run(cl.options, progress);
        if (!cl.quiet)
            for (const auto& n : s.notes) std::fprintf(stderr, "rockhatch: note: %s\n", n.c_str());
        std::fprintf(stderr, "rockhatch: %zu faces, %zu hatches, %.2f s, working CRS %s\n", s.faces, s.hatches, s.seconds,
                     s.crs.c_str());
        if (s.tiles.tiles)
            std::fprintf(stderr, "rockhatch: %zu vector tiles, %.1f MB, largest %.0f kB (%d/%d/%d)\n", s.tiles.tiles,
                         s.tiles.bytes / 1e6, s.tiles.largest / 1e3, s.tiles.largest_z, s.tiles.largest_x,
                         s.tiles.largest_y);
        return 0;
    } catch (const carto::Error& e) {
        bar.finish();
        std::fprintf(stderr, "%s: %s\n", prog, e.what());
        return e.exit_code();
    } catch (const std::bad_alloc&) {
        bar.finish();
        std::fprintf(stderr, "%s: out of memory: the inputs or options ask for more than this machine holds "
                             "(try a --window, a larger --scale or coarser rasters)\n", prog);
        return 1;
    } catch (const std::exception& e) {
        bar.finish();
        std::fprintf(stderr, "%s: %s\n", prog, e.what());
        return 1;
    }
}
