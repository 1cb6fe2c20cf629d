// Aretes: the noisy fill of (a), with no ridge emphasis of its own, and every ridge line
// drawn as a crest ornament (issue 14): the style-table form of --crest-ornament, for sharp
// aretes on a schematic or tourist map.
#include "builtins.hpp"

namespace carto::blocks {

Builtin aretes() {
    Builtin b = noisy();
    b.info.name = "aretes";
    b.info.figure = "after 5.4a";
    b.info.title = "noisy hatching with a crest ornament along every ridge (aretes of a schematic map)";
    b.info.params.push_back({"crest_band", 2.0, "mm", "height of the crest ornament band centred on each ridge"});
    b.info.crest_ornament = true;
    return b;
}

}  // namespace carto::blocks
