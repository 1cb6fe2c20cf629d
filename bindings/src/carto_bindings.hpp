// Private header of the rockhatch.carto bindings: the areas bind_carto registers, one
// function each, and the helpers several areas share (defined in carto_bindings.cpp).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "carto/progress.hpp"
#include "carto/raster.hpp"
#include "carto/terrain.hpp"
#include "common.hpp"

namespace rhpy {

using RasterPtr = std::shared_ptr<carto::Raster>;

// The terrain rasters, each shared with Python (fields built on them keep them alive).
struct PyTerrain {
    RasterPtr elevation, slope, aspect, roughness, hillshade;
};

PyTerrain share(carto::Terrain t);

// A CRS as WKT: 'EPSG:n' (or 'epsg:n') as the WKT of that code, anything else as given.
std::string wkt_of(const std::string& crs);

// Raster.from_array: cells equal to nodata, and non-finite cells, become NaN.
RasterPtr raster_from_array(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                            const std::vector<double>& gt, const std::string& crs, std::optional<double> nodata);

// A Python progress callback (None: none). Called with or without the GIL (inside bindings
// that release it): takes it to keep a reference to the callback.
carto::Progress to_progress(const py::object& cb);

// The areas of rockhatch.carto, in the order bind_carto calls them: a class is registered
// before the functions whose signatures or defaults use it.
void add_raster_bindings(py::module_& m);         // carto_bindings.cpp
void add_control_field_bindings(py::module_& m);  // carto_bindings.cpp
void add_partition_bindings(py::module_& m);      // carto_partition_bindings.cpp
void add_hatch_bindings(py::module_& m);          // carto_style_bindings.cpp
void add_style_bindings(py::module_& m);          // carto_style_bindings.cpp
void add_pipeline_bindings(py::module_& m);       // carto_pipeline_bindings.cpp
void add_output_bindings(py::module_& m);         // carto_pipeline_bindings.cpp
void add_tile_bindings(py::module_& m);           // carto_pipeline_bindings.cpp
void add_extraction_bindings(py::module_& m);     // carto_partition_bindings.cpp
void add_cli_bindings(py::module_& m);            // carto_cli_bindings.cpp

}  // namespace rhpy
