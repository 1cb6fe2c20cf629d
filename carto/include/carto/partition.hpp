// The partition of rock areas (seed section 5.4): faces to hatch separately, whose borders
// are labelled ridge, valley (thalweg), cliff (the top edge of a cliff band) or other, with an
// optional hatching orientation and density per face.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "libtex/region.hpp"

class GDALDataset;

namespace carto {

using tex::Point;

enum class LineKind { Other = 0, Ridge = 1, Valley = 2, Cliff = 3 };
const char* kind_name(LineKind k);

// One segment of a face's boundary rings with its label and the face across it (-1: none).
struct BoundarySegment {
    Point a, b;
    LineKind kind = LineKind::Other;
    int neighbor = -1;
};

struct RockFace {
    std::int64_t id = 0;     // feature id (or the id attribute)
    tex::Region region;      // in the working CRS
    std::vector<BoundarySegment> boundary;
    std::optional<double> orientation;  // hatch direction, math angle in radians (axial)
    std::optional<double> density;      // 0 (sparse, light) .. 1 (dense, dark)
    // A point inside the face as it was read, before its borders were snapped to its
    // neighbours': it depends on this face alone, so the tile that owns the face (the one
    // whose box holds it) is the same whatever else a run reads (face_anchor).
    std::optional<Point> anchor;
};

// The face's anchor, or a point inside it for a face built without one.
Point face_anchor(const RockFace& f);
// Whether a point lies in a half-open box [xmin, xmax) x [ymin, ymax): every point of the
// plane lies in exactly one tile of a grid of such boxes.
bool owns(const tex::BBox& tile, const Point& p);

struct LabelledLine {
    std::vector<Point> points;
    LineKind kind;
};

struct Partition {
    std::vector<RockFace> faces;
    std::vector<LabelledLine> lines;  // ridge and valley lines in the working CRS
    std::string crs_wkt;
    std::vector<std::string> notes;   // what was repaired or derived, for the log
    // Scree areas given by the user (PartitionOptions::scree_layer), in the working CRS;
    // empty: the scree style derives them from the faces and the slope.
    std::vector<tex::Region> scree;
    tex::BBox bounds() const;
};

struct PartitionOptions {
    std::string path;                     // OGR dataset (GeoPackage, shapefile, ...)
    std::string faces_layer;              // "" = the first polygon layer
    std::string lines_layer;              // "" = the first line layer (attribute labels)
    // ridge / valley / cliff / other. Without a line layer that has it, a line layer with OSM's
    // `natural` tag (a field, or `other_tags` as GDAL's OSM driver writes it) labels the lines:
    // ridge and arete ridges, cliff cliffs, valley valleys; other values are not labels.
    std::string label_field = "kind";
    std::string id_field;                 // "" = feature ids
    // Face attributes. "" = the field named "orientation" / "density" when the layer has one;
    // a name given here must exist (a misspelt name is an error, not a silent default).
    std::string orientation_field;        // degrees, azimuth of the hatches
    std::string orientation_layer;        // line layer, one line per face ("" = look for one)
    std::string density_field;            // 0..1
    std::string density_layer;            // point or polygon layer with a density field
    std::string scree_layer;              // polygon layer of the scree areas (the scree style); "" = none
    bool repair = true;                   // repair invalid polygons (else refuse them)
    double snap = 0.5;                    // ground units: border snapping and line matching tolerance
    // Read only the features that meet this box (working CRS): a tile's neighbourhood. A
    // box holding no face gives an empty partition instead of an error.
    std::optional<tex::BBox> filter;
    // The faces and lines as the file holds them (reprojected, repaired): borders neither
    // snapped nor labelled (RockFace::boundary left empty). What update's fingerprints digest
    // (carto/update.hpp): snapping is local, so a face's drawing depends on its neighbourhood
    // as digitised.
    bool as_digitised = false;
};

// Reads the partition and reprojects it to the working CRS. Lines come either from a line
// layer with a label attribute, or from layers named after their kind ("ridges",
// "valleys", "thalwegs"...). Throws carto::Error naming the dataset, layer or field.
Partition load_partition(const PartitionOptions& opt, const std::string& working_wkt);
// The same from a dataset already open (any OGR driver, an in-memory one included); opt.path
// names it in messages only.
Partition load_partition(GDALDataset& ds, const PartitionOptions& opt, const std::string& working_wkt);

// Makes the shared borders of neighbouring faces identical when they lie within `snap` of
// each other, whatever their vertices: vertices move onto other faces' vertices, then onto
// other faces' segments (which gain them as vertices), until stable, so that two neighbours
// run through the same points along their common border. A face never snaps onto itself.
// Faces left without area are dropped (noted in p.notes); faces that do not move stay
// bit-identical. Call it before label_boundaries, which matches neighbours on identical
// segments.
void snap_borders(Partition& p, double snap);

// Labels the boundary segments of every face from the lines, and finds the face across
// each segment: the segment of another face with the same ends (shared by load_partition and
// by tools building partitions in memory).
void label_boundaries(Partition& p, double snap);

// A point inside a face (tex::InteriorPoint of its region): where a style reads the face's
// orientation and density.
inline Point interior_point(const tex::Region& r) { return tex::InteriorPoint(r); }
inline Point interior_point(const RockFace& f) { return tex::InteriorPoint(f.region); }

}  // namespace carto
