// Crest ornaments: every ridge line of the partition drawn as a band pattern synthesised
// from an exemplar (seed 002, tex::SynthesizeAlongCurve), one connected piece per ridge.
//
// The exemplar is either the project's own (a spine with barbs on both sides, see
// default_crest_svg) or a user's SVG of polygons with holes. The band is centred on the
// ridge and as high as the option says in millimetres on paper at the map scale. Each ridge
// draws from its own key (the run's seed and the ridge's points), so a ridge's ornament does
// not depend on the other ridges, on their order or on the number of threads.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "carto/partition.hpp"
#include "libtex/curves.hpp"
#include "libtex/synthesis.hpp"

namespace carto {

// The value of --crest-ornament that selects the project's exemplar.
inline constexpr const char* kDefaultCrest = "default";
// --crest-height when it is not given (mm on paper).
inline constexpr double kDefaultCrestHeightMm = 2.0;

// One ridge's ornament: closed rings in the working CRS, outer rings counter-clockwise and
// holes clockwise (the synthesis asks for one connected component per ridge).
struct CrestOrnament {
    std::size_t ridge = 0;  // index of the ridge in Partition::lines (of the run that drew it)
    std::int64_t id = 0;    // ridge_key of the ridge: written as ridge_id, the same in every run
    std::vector<std::vector<Point>> rings;
};

// A ridge line's identifier, from its points alone (not from its place in the partition, which
// differs between a whole run and a tile's window): non-negative, the same wherever the line
// is read.
std::int64_t ridge_key(const std::vector<Point>& line);

// The point that places a ridge line in a window or a tile: the smaller of its two end points
// (a point on the line, so a window that holds it reads the line).
Point ridge_anchor(const std::vector<Point>& line);

// How far beyond a ridge line's box another ridge line may change its ornament: ends are cut
// back where ridges meet, which they do within a small share of the band. A tile reads the
// partition that far around the ridges it owns.
double crest_context(double band_height);

struct CrestResult {
    std::vector<CrestOrnament> ornaments;  // in the order of Partition::lines
    std::vector<std::string> notes;        // ridges skipped and why
};

// The project's crest exemplar as SVG text.
const std::string& default_crest_svg();

// An exemplar and how it is synthesised (one component, holes free; the slicing that suits it).
struct CrestExemplar {
    tex::Curves shapes;
    tex::SynthesisOptions synthesis;
};

// The exemplar --crest-ornament names: kDefaultCrest or the path of an SVG file. Throws
// carto::Error naming the option: InputMissing when the file is missing or is not SVG,
// BadLayer when it holds no polygon or cannot make one connected band.
CrestExemplar load_crest_exemplar(const std::string& spec);

// The ornaments of the ridge lines of `p` (those whose ridge_anchor lies in `window`,
// half-open, when one is given), in a band `band_height` high (ground units),
// in parallel. A ridge shorter than the band height is skipped, and so is a ridge along
// which no pattern can be laid even once smoothed (it turns too tightly for the band);
// notes count both.
CrestResult draw_crests(const Partition& p, const CrestExemplar& exemplar, double band_height, std::uint64_t seed,
                        const std::optional<tex::BBox>& window = std::nullopt);

}  // namespace carto
