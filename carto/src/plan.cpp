#include "carto/plan.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "carto/error.hpp"
#include "carto/output.hpp"

namespace carto {
namespace {

// A crest band higher than this is a typo for a scale or a unit (it would cover the faces).
constexpr double kMaxCrestHeightMm = 50;

std::string extension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    for (auto& ch : e) ch = char(std::tolower((unsigned char)ch));
    return e;
}

// The output's format from its extension; nullopt for an unknown one.
std::optional<OutputFormat> format_of(const std::string& path) {
    const std::string e = extension(path);
    if (e == ".gpkg") return OutputFormat::GeoPackage;
    if (e == ".svg") return OutputFormat::Svg;
    if (e == ".png") return OutputFormat::Png;
    if (e == ".pdf") return OutputFormat::Pdf;
    if (e == ".mbtiles" || (!path.empty() && path.back() == '/')) return OutputFormat::VectorTiles;
    return std::nullopt;
}

// The crest band (ground units) when the run draws crest ornaments: --crest-height, else the
// style's crest_band, else kDefaultCrestHeightMm.
std::optional<double> crest_band(const Options& o, const StyleInfo& info, const ParamValues& params) {
    if (!o.crest_ornament && !info.crest_ornament) return std::nullopt;
    if (o.crest_height_mm) return *o.crest_height_mm * o.scale / 1000;
    if (info.crest_ornament) return params.at("crest_band");
    return kDefaultCrestHeightMm * o.scale / 1000;
}

}  // namespace

void check_files(const Options& o) {
    std::vector<FileArg> outputs;
    for (const auto& out : o.outputs) outputs.push_back({"-o", out});
    const std::string partition = o.partition.path == "auto" || o.partition.path == "none" ? "" : o.partition.path;
    const std::string crest =
        o.crest_ornament && *o.crest_ornament != kDefaultCrest ? *o.crest_ornament : std::string();
    check_outputs({{"--dem", o.dem}, {"--partition", partition}, {"--slope", o.slope}, {"--roughness", o.roughness},
                   {"--script", o.style_file}, {"--crest-ornament", crest}, {"--mask", o.mask}},
                  outputs, o.overwrite);
}

Plan make_plan(const Options& o, PlanFor use) {
    Plan plan;
    plan.options = o;
    if (!(o.scale > 0) || !std::isfinite(o.scale))
        throw Error(Code::Usage, "--scale: " + std::to_string(o.scale) + " is not a positive number");
    if (!o.mask.empty() && o.partition.path != "auto")
        throw Error(Code::Usage, "--mask '" + o.mask + "': a mask only restricts --partition auto (the rock of a "
                                 "partition file is its faces)");
    plan.style = o.custom_style ? *o.custom_style : builtin_style(o.style.empty() ? default_style() : o.style);
    const ParamValues own = resolve_params(plan.style.info, o.params, o.scale);
    if (plan.terrain_style()) {
        // A terrain style's parameters are its own; its faces are hatched with the default
        // rock style at its default values.
        plan.rock = find_style(default_style());
        plan.rock_params = resolve_params(plan.rock, {}, o.scale);
        plan.terrain_params = own;
    } else {
        plan.rock = plan.style.info;
        plan.rock_params = own;
    }
    if (use == PlanFor::Run) {
        if (o.dem.empty()) throw Error(Code::Usage, "--dem is required");
        if (o.partition.path.empty()) throw Error(Code::Usage, "--partition is required");
        if (o.outputs.empty()) throw Error(Code::Usage, "-o is required (.gpkg, .svg, .png, .pdf, .mbtiles or DIR/)");
    }
    if (!(o.partition.snap > 0)) throw Error(Code::Usage, "--snap must be positive");
    if (!(o.relief_radius > 0) || !std::isfinite(o.relief_radius))
        throw Error(Code::Usage, "--relief-radius: " + std::to_string(o.relief_radius) + " is not a positive number");
    // First: an output onto an input is refused as such, whatever its format.
    check_files(o);
    for (const auto& out : o.outputs) {
        const std::optional<OutputFormat> f = format_of(out);
        if (!f) throw Error(Code::Usage, "-o '" + out + "': unknown format (use .gpkg, .svg, .png, .pdf, "
                                                   ".mbtiles or DIR/ for a folder of vector tiles)");
        plan.outputs.push_back({out, *f});
    }
    const auto has = [&](OutputFormat f) {
        return std::any_of(plan.outputs.begin(), plan.outputs.end(), [&](const Output& out) { return out.format == f; });
    };
    if (!o.page.empty()) {
        if (use == PlanFor::Run && !has(OutputFormat::Pdf)) throw Error(Code::Usage, "--page needs a .pdf output");
        plan.page = parse_page(o.page);
    }
    if (!o.zoom.empty() && use == PlanFor::Run && !has(OutputFormat::VectorTiles))
        throw Error(Code::Usage, "--zoom needs a vector-tile output (.mbtiles or DIR/)");
    plan.zoom = parse_zoom_range(o.zoom.empty() ? kDefaultZoom : o.zoom);
    if (o.png_pixels < 16 || o.png_pixels > 20000) throw Error(Code::Usage, "--png-size must be in 16..20000");
    if (o.crest_height_mm) {
        if (!o.crest_ornament) throw Error(Code::Usage, "--crest-height needs --crest-ornament");
        if (!(*o.crest_height_mm > 0) || *o.crest_height_mm > kMaxCrestHeightMm) {
            std::ostringstream m;
            m << "--crest-height: " << *o.crest_height_mm << " mm is not in (0, " << kMaxCrestHeightMm << "]";
            throw Error(Code::Usage, m.str());
        }
    }
    // The exemplar is read (and tried) now: a bad one is refused before any work. A style
    // that draws crests without --crest-ornament uses the project's exemplar.
    if (o.crest_ornament)
        plan.crest_exemplar = std::make_shared<const CrestExemplar>(load_crest_exemplar(*o.crest_ornament));
    plan.crest_band = crest_band(o, plan.style.info, own);
    if (plan.crest_band && !plan.crest_exemplar)
        plan.crest_exemplar = std::make_shared<const CrestExemplar>(load_crest_exemplar(kDefaultCrest));
    if (o.partition.path == "none" && !plan.terrain_style())
        throw Error(Code::Usage, "--partition none: style '" + plan.style.info.name +
                                     "' hatches rock faces and needs a partition (a file or auto)");
    if (o.threads > kMaxThreads)
        throw Error(Code::Usage, "--threads: " + std::to_string(o.threads) + " is more than " +
                                     std::to_string(kMaxThreads));
    plan.field_smoothing = kFieldSmoothingMm * o.scale / 1000.0;
    return plan;
}

}  // namespace carto
