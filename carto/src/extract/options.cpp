// The extraction's tuning options as the command line spells them (carto/extract.hpp): one
// table for `rockhatch partition` and for `rockhatch tiles --partition auto`.
#include <functional>
#include <string>
#include <vector>

#include "carto/cli.hpp"
#include "carto/extract.hpp"

namespace carto {
namespace {

struct Setter {
    ExtractOptionName name;
    std::function<void(ExtractOptions&, const std::string&)> set;
};

// A number option writing the member `field`.
Setter number(const char* name, double ExtractOptions::*field) {
    return {{name, true}, [name, field](ExtractOptions& o, const std::string& v) { o.*field = parse_double(name, v); }};
}

const std::vector<Setter>& setters() {
    static const std::vector<Setter> table = {
        {{"--mask", true}, [](ExtractOptions& o, const std::string& v) { o.mask = v; }},
        number("--min-slope", &ExtractOptions::min_slope),
        number("--min-roughness", &ExtractOptions::min_roughness),
        number("--min-area", &ExtractOptions::min_area_mm2),
        number("--thalweg-area", &ExtractOptions::thalweg_area),
        number("--ridge-area", &ExtractOptions::ridge_area),
        number("--max-fill", &ExtractOptions::max_fill),
        number("--smooth", &ExtractOptions::smooth),
        number("--converge", &ExtractOptions::converge),
        number("--simplify", &ExtractOptions::simplify),
        {{"--no-ridge-extension", false}, [](ExtractOptions& o, const std::string&) { o.extend_ridges = false; }},
        {{"--no-outline-labels", false}, [](ExtractOptions& o, const std::string&) { o.label_outline = false; }},
        {{"--smooth-edge", false}, [](ExtractOptions& o, const std::string&) { o.terrain_edge = false; }},
    };
    return table;
}

}  // namespace

const std::vector<ExtractOptionName>& extract_option_names() {
    static const std::vector<ExtractOptionName> names = [] {
        std::vector<ExtractOptionName> out;
        for (const Setter& s : setters()) out.push_back(s.name);
        return out;
    }();
    return names;
}

bool set_extract_option(ExtractOptions& o, const std::string& name, const std::string& value) {
    for (const Setter& s : setters())
        if (s.name.name == name) {
            s.set(o, value);
            return true;
        }
    return false;
}

}  // namespace carto
