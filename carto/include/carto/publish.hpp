// Publishing a drawing: a georeferenced PDF for print (GDAL's PDF driver, ISO 32000
// georeferencing, one optional-content layer per family) and Mapbox vector tiles for the
// screen (GDAL's MVT driver, into an MBTiles file or a folder), each zoom level drawn at its
// own map scale.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "carto/output.hpp"

namespace carto {

// ---- PDF ----

// A page in millimetres (portrait: width <= height); the drawing is centred on it, turned
// to landscape when only that fits.
struct PageSize {
    std::string name;  // "A3", or "420x297"
    double width_mm = 0, height_mm = 0;
};

// "A0".."A5" (case-insensitive) or "WxH" in mm; throws Error(Usage) naming --page.
PageSize parse_page(const std::string& text);

// The largest page side a PDF reader is bound to accept (14400 units of 1/72 in).
inline constexpr double kMaxPdfPageMm = 14400 / 72.0 * 25.4;

// The page (mm) of a PDF of the drawing framed by `frame` at 1:scale: the frame, or `page`
// upright or turned, whichever holds it. Throws Error(Usage) when none does; `path` names
// the output in the message.
struct PageLayout {
    double width_mm, height_mm;
};
PageLayout page_layout(const tex::BBox& frame, double scale, const std::optional<PageSize>& page,
                       const std::string& path);

// Writes the drawing as a georeferenced PDF at true scale (1:d.scale): black strokes of each
// family's width on paper with round caps and joins, filled crest ornaments and terrain
// elements, one optional-content layer per family (named as the GeoPackage's layers,
// without "hatch_"), the page fitted to the drawing's frame or `page` with the frame
// centred. The page, its georeferencing (ISO 32000) and layers are GDAL's PDF driver's
// (a composition file); each layer's paths are a content stream carto writes. Atomic;
// throws Error(Usage) when the frame does not fit the page.
void write_pdf(const Drawing& d, const std::string& path, const std::optional<PageSize>& page = std::nullopt);

// The PDF line width (in PDF units, 1/72 in) that draws `width_mm` on paper.
inline double pdf_line_width(double width_mm) { return width_mm * 72.0 / 25.4; }

// ---- vector tiles ----

struct ZoomRange {
    int min = 12, max = 16;
};
// "Z" or "Z1-Z2" within 0..22; throws Error(Usage) naming --zoom.
ZoomRange parse_zoom_range(const std::string& text);

// The size on screen of a web map pixel, in mm: OGC's standardised rendering pixel, with
// which zoom 13 is 1:68,247 at the equator.
inline constexpr double kWebPixelMm = 0.28;

// The map scale of zoom `z` of the web's Mercator tiles at latitude `latitude_deg`: the
// ground a screen pixel covers there over kWebPixelMm (at 45.9 degrees, z13 is 1:47,500 and
// z16 1:5,900).
double zoom_scale(int z, double latitude_deg);

// The latitude (degrees, WGS 84) of the centre of a DEM, the latitude at which its zoom
// levels' scales are taken.
double dem_latitude(const std::string& dem);

// One zoom level's drawing: a hatch GeoPackage (write_gpkg, merge_gpkg) drawn at
// zoom_scale(zoom).
struct ZoomDrawing {
    int zoom;
    std::string gpkg;
};

struct TileStats {
    std::size_t tiles = 0;
    std::size_t bytes = 0;    // of all the tiles (compressed, as stored)
    std::size_t largest = 0;  // the largest tile's bytes
    int largest_z = 0, largest_x = 0, largest_y = 0;  // where it is (XYZ scheme)
    std::size_t features = 0;  // features written, over all zoom levels
};

// Writes the zoom levels' drawings as Mapbox vector tiles: into an MBTiles file (path ending
// in .mbtiles) or a folder of z/x/y.pbf tiles (any other path), one tile layer per family
// (fill, ridge, ..., crest) whose features are, at zoom z, those of the drawing of zoom z
// (fields face_id and width_mm). Web Mercator; the MVT limit of 500 kB per tile. Atomic:
// a temporary name renamed at the end. Counts the tiles of an MBTiles output (a folder's are
// not counted: 0).
TileStats write_vector_tiles(const std::vector<ZoomDrawing>& zooms, const std::string& path,
                             const std::string& name = "rockhatch",
                             const std::function<bool(double)>& keep_going = {});

// The tiles of an MBTiles file as write_vector_tiles counts them.
TileStats mbtiles_stats(const std::string& path);

}  // namespace carto
