// Text for XML attributes and elements (internal to carto): the SVG writer's and the PDF
// composition's.
#pragma once

#include <string>

namespace carto {

inline std::string xml_escape(const std::string& in) {
    std::string out;
    for (char c : in) {
        if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '&') out += "&amp;";
        else if (c == '"') out += "&quot;";
        else out += c;
    }
    return out;
}

}  // namespace carto
