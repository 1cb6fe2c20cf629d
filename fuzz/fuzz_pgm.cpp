// libFuzzer target: the PGM reader of the discrete operators (tex::disc::ParsePGM, the bytes
// behind ReadPGM), then what a program does with the image: its frame and the field read
// at a few points. The only expected failure is tex::Error (a malformed or truncated file);
// anything else (a crash, a sanitizer report, another exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "libtex/discrete.hpp"
#include "libtex/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        const tex::GridSamples g = tex::disc::ParsePGM(bytes, "fuzz.pgm");
        const tex::Region frame = tex::disc::Image(g);
        const tex::Field f = tex::GridField(g);
        (void)f(frame.bbox().center());
        (void)f(tex::Point{frame.bbox().xmin, frame.bbox().ymax});
    } catch (const tex::Error&) {
    }
    return 0;
}
