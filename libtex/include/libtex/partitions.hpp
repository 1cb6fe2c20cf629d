// Partitioning operators (thesis 3.3, table 3.2).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "libtex/arrangement.hpp"

namespace tex {

// Behaviour at the border of the region (thesis Fig. 3.4).
enum class Border {
    CROP,               // cut the partition along the region boundary
    CROP_ADD_BOUNDARY,  // cut it and add the region outline
    KEEP_INSIDE,        // keep only the cells strictly inside the region
    KEEP_OUTSIDE,       // keep every cell that meets the region
};
inline constexpr Border CROP = Border::CROP;
inline constexpr Border CROP_ADD_BOUNDARY = Border::CROP_ADD_BOUNDARY;
inline constexpr Border KEEP_INSIDE = Border::KEEP_INSIDE;
inline constexpr Border KEEP_OUTSIDE = Border::KEEP_OUTSIDE;
const char* border_name(Border b);

// Parallel lines at angle `angle` (radians, direction (cos a, sin a)); successive lines are
// separated by the widths of the cycle, repeated periodically. Line 0 passes through the
// origin, so a stripes partition is anchored to the plane, not to the region.
struct Stripes {
    double angle = 0.0;
    std::vector<double> widths;
    std::vector<std::string> edge_labels;  // cycle of labels of the lines
    std::vector<std::string> face_labels;  // cycle of labels of the bands between lines
};

Stripes StripesProperties(double angle, std::vector<double> widths);
template <class... W>
Stripes StripesProperties(double angle, double w1, W... ws) {
    return StripesProperties(angle, std::vector<double>{w1, double(ws)...});
}
// Sets the label cycles of p (in place, as in the thesis's scripts) and returns p.
Stripes& SetEdgeLabels(Stripes& p, std::vector<std::string> labels);
Stripes& SetFaceLabels(Stripes& p, std::vector<std::string> labels);

// Density (sites per unit area) and weighted random labels of an irregular partition.
struct WeightedLabel {
    std::string label;
    double weight;  // probability that a cell carries this label
};
struct Irregular {
    double density = 0.0;
    std::vector<WeightedLabel> vertex_labels, edge_labels, face_labels;
};

Irregular IrregularProperties(double density);
// Each cell receives at most one label of the list, label i with probability w_i; the
// weights are probabilities in [0, 1] with a sum of at most 1 (the rest: no label).
Irregular& SetWeightedVertexLabels(Irregular& p, std::vector<WeightedLabel> labels);
Irregular& SetWeightedEdgeLabels(Irregular& p, std::vector<WeightedLabel> labels);
Irregular& SetWeightedFaceLabels(Irregular& p, std::vector<WeightedLabel> labels);

// Parallel stripes cropped to the region, with its outline (the bands are infinite, so the
// outline is what closes them into faces). With a border mode other than CROP_ADD_BOUNDARY (the partition of the region, the default):
// CROP gives the stripe boundaries cut to the region alone, KEEP_* whole stripes.
Arrangement StripesPartition(const Stripes& p, Border b = Border::CROP_ADD_BOUNDARY);
// Cells between two families of stripes.
Arrangement GridPartition(const Stripes& s1, const Stripes& s2, Border b);
// Voronoi diagram of Poisson-disk sites (density sites per unit area). Sites are a
// function of the plane, the seed and the partition's stream, not of the region: two
// regions sharing a border agree on it. Each call draws from its own stream (random.hpp,
// "Streams"); an explicit `seed` repeats one on purpose.
Arrangement UniformPartition(const Irregular& p, Border b, std::optional<std::uint64_t> seed = std::nullopt);
// Voronoi diagram of Poisson (uniform random) sites, also anchored to the plane.
Arrangement RandomPartition(const Irregular& p, Border b, std::optional<std::uint64_t> seed = std::nullopt);

// The sites the two irregular partitions of a stream use inside a box (for tests and tools).
std::vector<Point> PoissonDiskSites(double density, const BBox& box, std::uint64_t stream = 0);
std::vector<Point> PoissonSites(double density, const BBox& box, std::uint64_t stream = 0);
// Minimum distance between Poisson-disk sites for a density.
double PoissonDiskRadius(double density);

namespace detail {
// While alive on this thread, every family of lines that StripesPartition or GridPartition
// lays over a region is recorded: its unit normal and the distance across which its widths
// and label cycles repeat. Such lines are anchored to the plane, so a tiled map's mapper
// (tiled.hpp) runs in a probe to learn whether the partitions it builds inside a cell
// repeat with the lattice (thesis 4.2.2 assumes mappers commute with the periods).
class StripesProbe {
public:
    struct Family {
        Point normal;
        double period = 0;
    };
    StripesProbe();
    ~StripesProbe();
    StripesProbe(const StripesProbe&) = delete;
    StripesProbe& operator=(const StripesProbe&) = delete;
    const std::vector<Family>& families() const { return families_; }
    // Records a family in this thread's innermost probe, if there is one.
    static void record(const Point& normal, double period);

private:
    std::vector<Family> families_;
    StripesProbe* saved_;
};
}  // namespace detail

}  // namespace tex
