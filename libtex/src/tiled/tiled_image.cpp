// libtex_image: a raster to a file through OpenImageIO.
#include "libtex/tiled_image.hpp"

#include <OpenImageIO/imageio.h>

#include "libtex/error.hpp"

namespace tex {

void WriteImage(const Raster& r, const std::string& path) {
    if (r.width <= 0 || r.height <= 0 || r.pixels.size() != std::size_t(r.width) * std::size_t(r.height))
        throw Error("WriteImage", "the raster is empty or inconsistent");
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw Error("WriteImage", "'" + path + "': no image format for this name (" + OIIO::geterror() + ")");
    const OIIO::ImageSpec spec(r.width, r.height, 1, OIIO::TypeDesc::UINT8);
    if (!out->open(path, spec)) throw Error("WriteImage", "'" + path + "': " + out->geterror());
    const bool ok = out->write_image(OIIO::TypeDesc::UINT8, r.pixels.data());
    const std::string err = ok ? std::string() : out->geterror();
    out->close();
    if (!ok) throw Error("WriteImage", "'" + path + "': " + err);
}

}  // namespace tex
