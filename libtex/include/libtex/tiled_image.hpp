// Writing a raster (tiled.hpp's Rasterize) to an image file through OpenImageIO: any format
// it writes (PNG, TIFF, EXR...), chosen by the file name's extension. In the optional
// library libtex_image, so that libtex and the programs that write no image do not load
// OpenImageIO.
#pragma once

#include <string>

#include "libtex/tiled.hpp"

namespace tex {

// Throws tex::Error naming the file when OpenImageIO cannot create or write it.
void WriteImage(const Raster& r, const std::string& path);

}  // namespace tex
