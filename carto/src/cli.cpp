// The rockhatch option table, its parser and its help text.
#include "carto/cli.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>

#include "carto/error.hpp"
#include "carto/styles.hpp"

namespace carto {

double parse_double(const std::string& opt, const std::string& v) {
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != 0 || !std::isfinite(d)) throw Error(Code::Usage, opt + ": '" + v + "' is not a number");
    return d;
}

namespace {

struct Option {
    const char* name;   // "--dem"
    const char* arg;    // "PATH", or nullptr for a flag
    const char* help;
    std::function<void(const std::string&)> set;
};

// A decimal integer in [0, max]: larger values are refused, not wrapped around (the
// narrowing of --threads 4294967296 to 0 meant "all cores").
unsigned long long parse_uint(const std::string& opt, const std::string& v,
                              unsigned long long max = std::numeric_limits<unsigned long long>::max()) {
    if (v.empty() || v.find_first_not_of("0123456789") != std::string::npos)
        throw Error(Code::Usage, opt + ": '" + v + "' is not a non-negative integer");
    errno = 0;
    const unsigned long long n = std::strtoull(v.c_str(), nullptr, 10);
    if (errno == ERANGE || n > max)
        throw Error(Code::Usage, opt + ": '" + v + "' is too large (at most " + std::to_string(max) + ")");
    return n;
}

std::vector<Option> options(CommandLine& cl) {
    Options& o = cl.options;
    return {
        {"--dem", "PATH", "DEM raster (any GDAL format and CRS; geographic DEMs are reprojected to UTM)",
         [&](const std::string& v) { o.dem = v; }},
        {"--partition", "PATH", "partition of the rock areas (GeoPackage, shapefile...): faces + labelled lines; auto: extracted "
                                "from the DEM; none: no rock (terrain styles only)",
         [&](const std::string& v) { o.partition.path = v; }},
        {"-o", "PATH", "output: .gpkg (one layer per hatch family), .svg (true scale), .png (preview), .pdf (georeferenced, "
                         "true scale), .mbtiles or DIR/ (vector tiles, see --zoom); repeatable",
         [&](const std::string& v) { o.outputs.push_back(v); }},
        {"--slope", "PATH", "slope raster in percent (default: computed from the DEM)",
         [&](const std::string& v) { o.slope = v; }},
        {"--roughness", "PATH", "roughness raster in 0..1 (default: computed from the DEM)",
         [&](const std::string& v) { o.roughness = v; }},
        {"--style", "NAME", "hatching style (see --list-styles; default: rock, the structure lines with strokes hanging from them and the print tone)",
         [&](const std::string& v) { o.style = v; }},
        {"--script", "PATH", "a Python style script (see styles/); its parameters are set with --param",
         [&](const std::string& v) { cl.script = o.style_file = v; }},
        {"--param", "NAME=VALUE", "set a style parameter (units as listed by --list-styles); repeatable",
         [&](const std::string& v) {
             const auto eq = v.find('=');
             if (eq == std::string::npos || eq == 0) throw Error(Code::Usage, "--param: expected NAME=VALUE, got '" + v + "'");
             o.params[v.substr(0, eq)] = parse_double("--param " + v.substr(0, eq), v.substr(eq + 1));
         }},
        {"--crest-ornament", "default|FILE.svg",
         "draw every ridge line as a band pattern synthesised from an exemplar: the project's (default) or an SVG of "
         "polygons; one connected piece per ridge (GPKG polygon layer / SVG group crest)",
         [&](const std::string& v) { o.crest_ornament = v; }},
        {"--crest-height", "MM", "height of the crest band, mm on paper at the map scale (default 2)",
         [&](const std::string& v) { o.crest_height_mm = parse_double("--crest-height", v); }},
        {"--scale", "N", "map scale denominator; style parameters are millimetres on paper at 1:N (default 10000)",
         [&](const std::string& v) { o.scale = parse_double("--scale", v); }},
        {"--relief-radius", "M",
         "height is the elevation between the lowest and highest ground within M metres (default 1000): editing "
         "the DEM changes the drawing only that far",
         [&](const std::string& v) { o.relief_radius = parse_double("--relief-radius", v); }},
        {"--seed", "N", "random seed (default 0); same inputs and seed give the same bytes",
         [&](const std::string& v) { o.seed = parse_uint("--seed", v); }},
        {"--threads", "N", "worker threads (default 0: all cores); does not change the output",
         [&](const std::string& v) { o.threads = unsigned(parse_uint("--threads", v, std::numeric_limits<unsigned>::max())); }},
        {"--faces-layer", "NAME", "polygon layer of the faces (default: the first polygon layer)",
         [&](const std::string& v) { o.partition.faces_layer = v; }},
        {"--lines-layer", "NAME", "line layer with the ridge / valley labels (default: the first with the label field, "
                                  "else layers named ridges / valleys)",
         [&](const std::string& v) { o.partition.lines_layer = v; }},
        {"--mask", "PATH", "with --partition auto: rock only inside these polygons (an OSM layer: natural=bare_rock)",
         [&](const std::string& v) { o.mask = v; }},
        {"--label-field", "NAME", "label attribute of the lines: ridge, valley (thalweg), cliff or other (default kind)",
         [&](const std::string& v) { o.partition.label_field = v; }},
        {"--id-field", "NAME", "face id attribute (default: feature ids)", [&](const std::string& v) { o.partition.id_field = v; }},
        {"--orientation-field", "NAME", "face attribute: hatch azimuth in degrees (default orientation)",
         [&](const std::string& v) { o.partition.orientation_field = v; }},
        {"--orientation-layer", "NAME", "line layer, one line per face along its hatches (default: a layer named orient*)",
         [&](const std::string& v) { o.partition.orientation_layer = v; }},
        {"--density-field", "NAME", "face attribute: hatch density 0 (light) .. 1 (dark) (default density)",
         [&](const std::string& v) { o.partition.density_field = v; }},
        {"--density-layer", "NAME", "point or polygon layer carrying the density field",
         [&](const std::string& v) { o.partition.density_layer = v; }},
        {"--scree-layer", "NAME", "polygon layer of the scree areas, for --style scree (default: the band below the "
                                  "rock where the slope is moderate)",
         [&](const std::string& v) { o.partition.scree_layer = v; }},
        {"--snap", "UNITS", "tolerance snapping neighbouring borders together and matching them to lines (default 0.5 m)",
         [&](const std::string& v) { o.partition.snap = parse_double("--snap", v); }},
        {"--no-repair", nullptr, "refuse invalid face polygons instead of repairing them",
         [&](const std::string&) { o.partition.repair = false; }},
        {"--window", "XMIN,YMIN,XMAX,YMAX", "hatch only the faces whose anchor (a point inside the face) lies in this box (working CRS)",
         [&](const std::string& v) {
             std::stringstream ss(v);
             std::string part;
             std::vector<double> n;
             while (std::getline(ss, part, ',')) n.push_back(parse_double("--window", part));
             if (n.size() != 4 || !(n[0] < n[2]) || !(n[1] < n[3]))
                 throw Error(Code::Usage, "--window: expected XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX");
             o.window = tex::BBox{n[0], n[1], n[2], n[3]};
         }},
        {"--page", "A0..A5|WxH", "page of a .pdf output, in mm, the drawing centred (default: the drawing's frame)",
         [&](const std::string& v) { o.page = v; }},
        {"--zoom", "Z1-Z2", "zoom levels of a vector-tile output, each drawn at its own scale (default 12-16)",
         [&](const std::string& v) { o.zoom = v; }},
        {"--png-size", "PIXELS", "width of PNG previews (default 1600)",
         [&](const std::string& v) { o.png_pixels = int(parse_uint("--png-size", v, std::numeric_limits<int>::max())); }},
        {"--no-spatial-index", nullptr, "write the GeoPackage without its R-tree (much faster for millions of hatches)",
         [&](const std::string&) { o.spatial_index = false; }},
        {"--overwrite", nullptr, "replace existing outputs", [&](const std::string&) { o.overwrite = true; }},
        {"-q", nullptr, "quiet: no progress bar", [&](const std::string&) { cl.quiet = true; }},
        {"--list-styles", nullptr, "list the styles, their parameters and defaults", [&](const std::string&) { cl.list_styles = true; }},
        {"--help", nullptr, "this help", [&](const std::string&) { cl.help = true; }},
    };
}

}  // namespace

std::string styles_text() {
    std::ostringstream os;
    for (const auto& s : carto::styles()) {
        os << "  " << s.name << (s.terrain ? std::string(" (terrain, around the rock)") : " (Fig. " + s.figure + ")")
           << (s.name == carto::default_style() ? " [default]" : "") << (s.crest_ornament ? " [crest ornaments]" : "")
           << ": " << s.title << "\n";
        os << params_text(s.params);
    }
    return os.str();
}

std::string params_text(const std::vector<StyleParam>& params, int indent) {
    std::ostringstream os;
    for (const auto& p : params) {
        std::ostringstream v;
        v << p.value;
        os << std::string(std::size_t(std::max(indent, 0)), ' ') << p.name << " = " << v.str() << " " << p.unit << "  "
           << p.help << "\n";
    }
    return os.str();
}

std::vector<OptionHelp> option_table() {
    CommandLine dummy;
    std::vector<OptionHelp> out;
    for (const auto& o : options(dummy)) out.push_back({o.name, o.arg ? o.arg : "", o.help});
    return out;
}

std::string exit_codes_text() {
    return "exit codes: 0 ok, 1 failure, 2 usage, 3 missing input, 4 no CRS, 5 no overlap,\n"
           "6 bad layer or attribute, 7 unknown style or parameter, 8 invalid geometry,\n"
           "9 output exists, is an input or cannot be written, 10 cancelled\n";
}

std::string help_text() {
    std::ostringstream out;
    out << "usage: rockhatch --dem DEM.tif --partition faces.gpkg [options] -o hatching.gpkg|.svg|.png\n\n"
                 "Draws rock hatching from a DEM and a partition of the rock areas whose borders are\n"
                 "labelled ridge / valley / other (thesis Chapter 5).\n\noptions:\n";
    for (const auto& o : option_table()) {
        std::string head = o.name + (o.arg.empty() ? std::string() : " " + o.arg);
        out << "  " << head << (head.size() < 26 ? std::string(26 - head.size(), ' ') : "\n" + std::string(28, ' '))
                  << o.help << "\n";
    }
    out << "\nstyles (parameters in mm on paper at the map scale, m on the ground, ratios, or degrees):\n";
    out << styles_text();
    out << "\n" << exit_codes_text();
    return out.str();
}

CommandLine parse_command_line(const std::vector<std::string>& args) {
    CommandLine cl;
    const std::vector<Option> opts = options(cl);
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const Option* match = nullptr;
        std::string value;
        for (const auto& op : opts) {
            if (a == op.name) match = &op;
            else if (op.arg && a.rfind(std::string(op.name) + "=", 0) == 0 && a.size() > 2 && a[1] == '-') {
                match = &op;
                value = a.substr(std::strlen(op.name) + 1);
            }
            if (match) break;
        }
        if (!match) throw Error(Code::Usage, "unknown option '" + a + "' (see --help)");
        if (match->arg && value.empty()) {
            if (i + 1 >= args.size()) throw Error(Code::Usage, std::string(match->name) + " needs a value (" + match->arg + ")");
            value = args[++i];
        }
        match->set(value);
    }
    return cl;
}

std::vector<OptionHelp> update_option_table() {
    return {{"--reset", "", "redraw every face and drop every feature, hand edits included (also accepts a file of "
                            "another program version, CRS or style)"},
            {"--face", "ID", "redraw this face whatever its fingerprint; repeatable"}};
}

std::string update_help_text() {
    std::ostringstream out;
    out << "usage: rockhatch update --dem DEM.tif --partition faces.gpkg [options] -o hatching.gpkg [-o .svg|.png|.pdf]\n\n"
           "Redraws the faces whose inputs changed since the run that wrote hatching.gpkg (the same options):\n"
           "the file keeps a fingerprint of each face's inputs; the features of changed, new and removed faces\n"
           "are replaced in one transaction, every other feature (hand edits included) stays as it is. The\n"
           "SVG, PNG and PDF outputs are drawn again from the updated layers.\n\nupdate's own options:\n";
    for (const auto& o : update_option_table()) {
        const std::string head = o.name + (o.arg.empty() ? std::string() : " " + o.arg);
        out << "  " << head << std::string(head.size() < 26 ? 26 - head.size() : 1, ' ') << o.help << "\n";
    }
    out << "\nand every option of rockhatch (rockhatch --help).\n\n" << exit_codes_text();
    return out.str();
}

UpdateCommandLine parse_update_command_line(const std::vector<std::string>& args) {
    UpdateCommandLine u;
    std::vector<std::string> rest;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--reset") {
            u.reset = true;
        } else if (a == "--face" || a.rfind("--face=", 0) == 0) {
            std::string v;
            if (a == "--face") {
                if (i + 1 >= args.size()) throw Error(Code::Usage, "--face needs a value (ID)");
                v = args[++i];
            } else {
                v = a.substr(7);
            }
            char* end = nullptr;
            errno = 0;
            const long long id = std::strtoll(v.c_str(), &end, 10);
            if (v.empty() || *end != 0 || errno == ERANGE)
                throw Error(Code::Usage, "--face: '" + v + "' is not a face id (an integer)");
            u.faces.push_back(id);
        } else {
            rest.push_back(a);
        }
    }
    u.command = parse_command_line(rest);
    return u;
}

}  // namespace carto
