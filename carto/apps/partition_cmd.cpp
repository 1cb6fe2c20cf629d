// `rockhatch partition`: the partition of the rock areas from a bare DEM (carto::extract_partition),
// written as the GeoPackage `rockhatch --partition` reads.
#include <cmath>
#include <cstdio>
#include <new>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "carto/cli.hpp"
#include "carto/error.hpp"
#include "carto/extract.hpp"
#include "carto/output.hpp"
#include "carto/progress.hpp"

namespace {

using carto::Code;
using carto::Error;

const char* kUsage =
    "usage: rockhatch partition --dem DEM.tif -o faces.gpkg [options]\n\n"
    "Extracts the partition of the rock areas from the DEM alone: the rock mask (steep and\n"
    "rough terrain), ridges and thalwegs (flow accumulation on the inverted and on the plain\n"
    "DEM), the faces between them with borders labelled ridge / valley / other, and each face's\n"
    "mean fall line and shade (1 - mean hillshade) as attributes fall_line and shade. The output\n"
    "is read unchanged by `rockhatch --dem DEM.tif --partition faces.gpkg -o out.svg`, which\n"
    "hatches it as `--partition auto` does (strokes follow the terrain).\n\n"
    "options:\n"
    "  --dem PATH              DEM raster (any GDAL format and CRS; geographic DEMs are reprojected to UTM)\n"
    "  -o PATH                 output GeoPackage: layers faces, lines (their labelled borders), mask,\n"
    "                          network (all traced ridges and thalwegs in the rock)\n"
    "  --mask PATH             polygon layer: rock only inside its polygons\n"
    "  --min-slope PCT         rock where the slope (mean over ~25 m) reaches PCT percent (default 70, 35 deg)\n"
    "  --min-roughness R       ... and the vector ruggedness (same mean) reaches R (default 0.001)\n"
    "  --min-area MM2          rock specks, enclosed gaps and faces smaller than MM2 square millimetres\n"
    "                          on paper at the map scale are dropped, filled or merged (default 16)\n"
    "  --scale N               map scale denominator (default 10000)\n"
    "  --thalweg-area M2       contributing area that starts a thalweg, m2 (default 6000, at least 50 cells)\n"
    "  --ridge-area M2         contributing area on the inverted DEM that starts a ridge, m2 (default 20000, at least "
    "100 cells)\n"
    "  --max-fill M            depressions and summits up to M metres deep/high are flowed across (default 30)\n"
    "  --smooth M              smoothing of the DEM before flow routing, metres (default 10, 0: none)\n"
    "  --converge K            a line starts where the contributing area is at least K times the mean\n"
    "                          of the cells beside it across the flow (default 1.2; 1: no test)\n"
    "  --no-ridge-extension    do not prolong ridge feet down their crest to a thalweg\n"
    "  --no-outline-labels     label the rock outline 'other' everywhere (default: ridge / valley where\n"
    "                          it runs along a traced ridge or thalweg)\n"
    "  --smooth-edge           leave the rock's edge where the 25 m means put it (default: within\n"
    "                          their reach, the slope over about 10 m moves it onto the breaks of slope)\n"
    "  --simplify CELLS        border generalisation tolerance in DEM cells (default 0.8; borders are\n"
    "                          cut through the middle of cell edges or the ridge / thalweg cells\n"
    "                          they run along, simplified within CELLS, then rounded)\n"
    "  --fixed-controls        write the fall line and shade as orientation and density, the attributes\n"
    "                          rockhatch reads as given: each face is hatched in one direction\n"
    "  --png PATH              also write a preview: hillshade, faces, ridges red, thalwegs blue\n"
    "  --png-size PIXELS       preview width (default 1600)\n"
    "  --overwrite             replace existing outputs\n"
    "  -q                      quiet: no progress\n"
    "  --help                  this help\n\n"
    "exit codes: 0 ok, 1 failure, 2 usage, 3 missing input, 4 no CRS, 6 bad layer or no rock,\n"
    "9 output exists, is an input or cannot be written, 10 cancelled\n";

}  // namespace

const char* partition_usage() { return kUsage; }

int partition_main(int argc, char** argv) {
    carto::ExtractOptions o;
    std::string out, png;
    int png_size = 1600;
    bool overwrite = false, quiet = false, fixed_controls = false;
    carto::ProgressBar bar(false);
    try {
        for (int i = 1; i < argc; ++i) {
            std::string a = argv[i], v;
            const auto eq = a.find('=');
            const bool inline_value = a.rfind("--", 0) == 0 && eq != std::string::npos;
            if (inline_value) {
                v = a.substr(eq + 1);
                a = a.substr(0, eq);
            }
            auto value = [&]() -> std::string {
                if (inline_value) return v;
                if (i + 1 >= argc) throw Error(Code::Usage, a + " needs a value");
                return argv[++i];
            };
            double png_width = png_size;
            // The command's own numbers, paths and flags; the extraction's tuning options come
            // from carto's table (shared with `rockhatch tiles --partition auto`).
            const std::pair<const char*, double*> numbers[] = {{"--scale", &o.scale}, {"--png-size", &png_width}};
            const std::pair<const char*, std::string*> paths[] = {{"--dem", &o.dem}, {"-o", &out}, {"--png", &png}};
            const std::pair<const char*, std::function<void()>> flags[] = {
                {"--overwrite", [&] { overwrite = true; }},
                {"-q", [&] { quiet = true; }},
                {"--fixed-controls", [&] { fixed_controls = true; }}};
            if (a == "--help" || a == "-h") {
                std::cout << kUsage;
                return 0;
            }
            bool known = false;
            for (const auto& e : carto::extract_option_names())
                if (a == e.name) known = carto::set_extract_option(o, a, e.takes_value ? value() : std::string());
            for (const auto& [name, target] : numbers)
                if (a == name) *target = carto::parse_double(a, value()), known = true;
            for (const auto& [name, target] : paths)
                if (a == name) *target = value(), known = true;
            for (const auto& [name, set] : flags)
                if (a == name) set(), known = true;
            if (!known) throw Error(Code::Usage, "unknown option '" + a + "' (see --help)");
            png_size = int(png_width);
        }
        if (o.dem.empty()) throw Error(Code::Usage, "--dem is required");
        if (out.empty()) throw Error(Code::Usage, "-o is required (a .gpkg file)");
        // First: an output onto an input is refused as such, whatever its format.
        carto::check_extract_files(o, out, png, overwrite);
        if (std::filesystem::path(out).extension() != ".gpkg")
            throw Error(Code::Usage, "-o '" + out + "': the partition is written as a GeoPackage (.gpkg)");
        if (png_size < 16 || png_size > 20000) throw Error(Code::Usage, "--png-size must be in 16..20000");
        if (!png.empty() && std::filesystem::path(png).extension() != ".png")
            throw Error(Code::Usage, "--png '" + png + "': not a .png file");
        bar = carto::ProgressBar(!quiet, "rockhatch partition: ");
        const carto::ExtractResult r = carto::extract_partition(o, std::ref(bar));
        bar.finish();
        carto::write_partition_gpkg(r.partition, out, overwrite, &r.network, fixed_controls);
        if (!png.empty()) carto::write_partition_png(r, png, png_size);
        if (!quiet)
            for (const auto& n : r.notes) std::fprintf(stderr, "rockhatch partition: note: %s\n", n.c_str());
        std::size_t ridges = 0, valleys = 0;
        for (const auto& l : r.partition.lines) {
            ridges += l.kind == carto::LineKind::Ridge;
            valleys += l.kind == carto::LineKind::Valley;
        }
        std::fprintf(stderr, "rockhatch partition: %zu faces, %zu ridge and %zu valley lines, working CRS %s\n",
                     r.partition.faces.size(), ridges, valleys, carto::crs_name(r.partition.crs_wkt).c_str());
        return 0;
    } catch (const Error& e) {
        bar.finish();
        std::fprintf(stderr, "rockhatch partition: %s\n", e.what());
        return e.exit_code();
    } catch (const std::bad_alloc&) {
        bar.finish();
        std::fprintf(stderr, "rockhatch partition: out of memory: --dem is too large for this machine (crop or coarsen it)\n");
        return 1;
    } catch (const std::exception& e) {
        bar.finish();
        std::fprintf(stderr, "rockhatch partition: %s\n", e.what());
        return 1;
    }
}
