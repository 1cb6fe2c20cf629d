// libFuzzer target: SVG import (tex::ParseSVG, the text behind tex::ImportSVG), then what
// is done with imported curves: the SVG export and the region a frame bounds. The only
// expected failure is tex::Error (a file that does not parse, holds no curve or bounds no
// region); anything else (a crash, a sanitizer report, another exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "libtex/error.hpp"
#include "libtex/svg.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const tex::Curves c = tex::ParseSVG(text, "fuzz.svg");
        (void)tex::ToSVG(c, 100.0);
        (void)tex::FrameRegion(c);
    } catch (const tex::Error&) {
    }
    return 0;
}
