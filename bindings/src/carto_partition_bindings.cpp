// rockhatch.carto, the partition of the rock areas: reading one (faces, labelled lines,
// the region a style draws a face in), and extracting one from the DEM alone (rockhatch
// partition), whole or by tiles.
#include "carto/control_fields.hpp"
#include "carto/extract.hpp"
#include "carto/partition.hpp"
#include "carto/styles.hpp"
#include "carto/tiles.hpp"
#include "carto_bindings.hpp"

namespace rhpy {

using namespace carto;

// Partitions as rockhatch reads them: faces, their borders and labelled lines.
void add_partition_bindings(py::module_& m) {
    py::enum_<LineKind>(m, "LineKind")
        .value("OTHER", LineKind::Other)
        .value("RIDGE", LineKind::Ridge)
        .value("VALLEY", LineKind::Valley)
        .value("CLIFF", LineKind::Cliff);
    py::class_<BoundarySegment>(m, "BoundarySegment", "A segment of a face's border, its label and the face across it")
        .def_readonly("a", &BoundarySegment::a)
        .def_readonly("b", &BoundarySegment::b)
        .def_readonly("kind", &BoundarySegment::kind)
        .def_readonly("neighbor", &BoundarySegment::neighbor, "index of the face across (-1: none)");
    py::class_<RockFace>(m, "RockFace", "A face of the partition of rock areas")
        .def_readonly("id", &RockFace::id)
        .def_readonly("region", &RockFace::region)
        .def_readonly("boundary", &RockFace::boundary)
        .def_readonly("orientation", &RockFace::orientation, "hatch direction (radians) or None")
        .def_readonly("density", &RockFace::density, "0..1 or None");
    py::class_<LabelledLine>(m, "LabelledLine")
        .def_readonly("points", &LabelledLine::points)
        .def_readonly("kind", &LabelledLine::kind);
    py::class_<Partition>(m, "Partition", "Faces to hatch separately and their labelled ridge / valley lines")
        .def_readonly("faces", &Partition::faces)
        .def_readonly("lines", &Partition::lines)
        .def_readonly("crs", &Partition::crs_wkt)
        .def_readonly("notes", &Partition::notes)
        .def("bounds", &Partition::bounds);
    py::class_<PartitionOptions>(m, "PartitionOptions", "Where the partition's faces, labels and attributes are")
        .def(py::init<>())
        .def_readwrite("path", &PartitionOptions::path)
        .def_readwrite("faces_layer", &PartitionOptions::faces_layer)
        .def_readwrite("lines_layer", &PartitionOptions::lines_layer)
        .def_readwrite("label_field", &PartitionOptions::label_field)
        .def_readwrite("id_field", &PartitionOptions::id_field)
        .def_readwrite("orientation_field", &PartitionOptions::orientation_field)
        .def_readwrite("orientation_layer", &PartitionOptions::orientation_layer)
        .def_readwrite("density_field", &PartitionOptions::density_field)
        .def_readwrite("density_layer", &PartitionOptions::density_layer)
        .def_readwrite("scree_layer", &PartitionOptions::scree_layer)
        .def_readwrite("repair", &PartitionOptions::repair)
        .def_readwrite("snap", &PartitionOptions::snap)
        .def_readwrite("filter", &PartitionOptions::filter, "read only the features meeting this box (working CRS)");
    m.def(
        "load_partition",
        [](const PartitionOptions& o, const std::string& crs) { return load_partition(o, wkt_of(crs)); },
        py::arg("options"), py::arg("working_crs"), py::call_guard<py::gil_scoped_release>(),
        "reads and reprojects a partition to the working CRS (WKT or 'EPSG:n')");
    m.def(
        "face_field",
        [](const Partition& p, std::vector<double> values) {
            if (values.size() != p.faces.size())
                throw py::value_error("face_field: " + std::to_string(values.size()) + " values for " +
                                      std::to_string(p.faces.size()) + " faces");
            return face_field(p, std::move(values));
        },
        py::arg("partition"), py::arg("values"), "value i on face i, NaN outside the faces");
    m.def("interior_point", py::overload_cast<const tex::Region&>(&interior_point), py::arg("region"));

    m.def("face_region", &face_region, py::arg("partition"), py::arg("face"),
          "the region a style draws face i in: its rings, its border as edges labelled ridge / valley / other "
          "(and owned where this face draws what lies on a shared border)");
}

// The partition from the DEM alone (rockhatch partition), whole or by tiles.
void add_extraction_bindings(py::module_& m) {
    py::class_<ExtractOptions>(m, "ExtractOptions", "Options of rockhatch partition (see its --help for units)")
        .def(py::init<>())
        .def_readwrite("dem", &ExtractOptions::dem)
        .def_property(
            "raster", [](const ExtractOptions& o) { return o.raster ? std::make_shared<Raster>(*o.raster) : nullptr; },
            [](ExtractOptions& o, const RasterPtr& r) {
                if (r) o.raster = *r;
                else o.raster.reset();
            },
            "an in-memory DEM used instead of the dem path")
        .def_readwrite("mask", &ExtractOptions::mask)
        .def_readwrite("min_slope", &ExtractOptions::min_slope, "percent")
        .def_readwrite("min_roughness", &ExtractOptions::min_roughness, "vector ruggedness 0..1")
        .def_readwrite("min_area_mm2", &ExtractOptions::min_area_mm2, "mm2 on paper at the scale")
        .def_readwrite("scale", &ExtractOptions::scale)
        .def_readwrite("thalweg_area", &ExtractOptions::thalweg_area, "m2")
        .def_readwrite("ridge_area", &ExtractOptions::ridge_area, "m2")
        .def_readwrite("smooth", &ExtractOptions::smooth, "m")
        .def_readwrite("converge", &ExtractOptions::converge)
        .def_readwrite("extend_ridges", &ExtractOptions::extend_ridges)
        .def_readwrite("max_fill", &ExtractOptions::max_fill, "m")
        .def_readwrite("simplify", &ExtractOptions::simplify, "cells")
        .def_readwrite("label_outline", &ExtractOptions::label_outline,
                       "label the rock outline ridge / valley where it runs along a line")
        .def_readwrite("terrain_edge", &ExtractOptions::terrain_edge,
                       "the rock's edge on the breaks of slope (False: where the 25 m means put it)")
        .def_readwrite("what", &ExtractOptions::what);
    py::class_<ExtractResult>(m, "ExtractResult", "An extracted partition, its rock mask and terrain")
        .def_readonly("partition", &ExtractResult::partition)
        .def_property_readonly("terrain", [](const ExtractResult& r) { return share(r.terrain); })
        .def_property_readonly("rock", [](const ExtractResult& r) { return std::make_shared<Raster>(r.rock); },
                               "1 rock, 0 not, NaN NoData, on the working grid")
        .def_property_readonly("faces", [](const ExtractResult& r) { return std::make_shared<Raster>(r.faces); },
                               "face index per cell (-1 outside)")
        .def_readonly("network", &ExtractResult::network, "all traced ridges and thalwegs in the rock")
        .def_readonly("notes", &ExtractResult::notes);
    m.def(
        "extract_option_names",
        [] {
            std::vector<std::pair<std::string, bool>> out;
            for (const auto& e : extract_option_names()) out.emplace_back(e.name, e.takes_value);
            return out;
        },
        "(name, takes a value) of the extraction's tuning options, as rockhatch partition spells them");
    m.def("check_extract_options", &check_extract_options, py::arg("options"),
          "the ranges of the tuning options (RockhatchError, code 2); extract_partition checks them first");
    m.def("set_extract_option", &set_extract_option, py::arg("options"), py::arg("name"), py::arg("value") = "",
          "sets one tuning option from its command-line value; False when `name` is not one");
    m.def(
        "extract_partition",
        [](const ExtractOptions& o, const py::object& cb) { return extract_partition(o, to_progress(cb)); },
        py::arg("options"), py::arg("progress") = py::none(), py::call_guard<py::gil_scoped_release>(),
        "the partition of the rock areas from the DEM alone (rockhatch partition)");
    m.def(
        "write_partition_gpkg",
        [](const Partition& p, const std::string& path, bool overwrite, const std::vector<LabelledLine>* network,
           bool fixed_controls) { write_partition_gpkg(p, path, overwrite, network, fixed_controls); },
        py::arg("partition"), py::arg("path"), py::arg("overwrite") = false, py::arg("network") = nullptr,
        py::arg("fixed_controls") = false, py::call_guard<py::gil_scoped_release>(),
        "layers faces, lines, mask (and network), as rockhatch reads them; the faces' fall line and shade as "
        "attributes fall_line and shade (derived: hatching follows the terrain), or, with fixed_controls, as "
        "orientation and density (read as given: one direction per face)");
    py::class_<ExtractTileReport>(m, "ExtractTileReport", "What one tile of a tiled extraction read and kept")
        .def_readonly("faces", &ExtractTileReport::faces)
        .def_readonly("lines", &ExtractTileReport::lines)
        .def_readonly("dem_cells", &ExtractTileReport::dem_cells)
        .def_readonly("rounds", &ExtractTileReport::rounds)
        .def_readonly("seconds", &ExtractTileReport::seconds);
    m.def("extract_tile", &extract_tile, py::arg("options"), py::arg("tile"), py::arg("halo"), py::arg("out"),
          py::call_guard<py::gil_scoped_release>(),
          "the faces of the partition whose anchor lies in the tile, extracted from the DEM window under the tile "
          "plus halo (ground units; larger where an owned face reaches the halo), written to out");
    py::class_<PartitionMerge>(m, "PartitionMerge", "What merge_partition_tiles wrote, and where its tiles disagree")
        .def_readonly("faces", &PartitionMerge::faces, "face polygons written")
        .def_readonly("overlaps", &PartitionMerge::overlaps,
                      "pairs of faces from different tiles that overlap (the tiles placed a face differently)")
        .def_readonly("overlap_area", &PartitionMerge::overlap_area, "their common area, ground units squared")
        .def_readonly("area", &PartitionMerge::area, "the area of all faces");
    m.def("merge_partition_tiles", &merge_partition_tiles, py::arg("parts"), py::arg("out"),
          py::arg("overwrite") = false, py::call_guard<py::gil_scoped_release>(),
          "one partition GeoPackage from the tiles of a tiled extraction; returns a PartitionMerge");
    m.def("check_extract_files", &check_extract_files, py::arg("options"), py::arg("output"), py::arg("png") = "",
          py::arg("overwrite") = false, "the outputs of partition_from_dem against its inputs (check_outputs)");
    m.def("write_partition_png", &write_partition_png, py::arg("result"), py::arg("path"), py::arg("pixels") = 1600,
          py::call_guard<py::gil_scoped_release>());
}

}  // namespace rhpy
