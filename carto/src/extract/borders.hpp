// The borders between faces: chains of cell edges traced on the face grid, labelled by the
// ridge and thalweg cells they run along, cut below the cell size and generalised at several
// levels (step 4 of carto/extract.hpp).
#pragma once

#include <array>
#include <map>
#include <vector>

#include "carto/partition.hpp"
#include "grid.hpp"

namespace carto::extraction {

// Douglas-Peucker tolerance of the lighter fallback generalisation, in cells.
constexpr double kHalfCell = 0.5;

// Directions between cell corners: E, S, W, N (rows go south).
constexpr int kCx[4] = {1, 0, -1, 0};

constexpr int kCy[4] = {0, 1, 0, -1};

struct Chain {
    std::vector<Point> raw;  // corner coordinates (col, row)
    // The shapes a face may use, from the most generalised to the cell edges themselves
    // (`level` picks one): 0 the generalised chain, 1 the cut steps simplified within half a
    // cell and rounded once, 2 the cut steps themselves (a one-cell staircase becomes its
    // diagonal), 3 the steps cut at the middles of the cell edges (a face of line cells alone
    // would lose its width if both of its borders moved onto the line), 4 the cell edges.
    // Levels 0 to 3 run along a grid axis only where the trace runs straight; level 4 is the
    // last resort. All five end at the same node places (NodePlaces).
    std::array<std::vector<Point>, 5> shapes;
    int right = -1, left = -1;  // faces on either side (-1: outside)
    int first_dir = 0, last_dir = 0;
    long long start = -1, end = -1;  // corner ids (closed chains: start == end)
    bool closed = false;
    int level = 0;
    static constexpr int kLevels = 5;
    const std::vector<Point>& shape() const { return shapes[std::size_t(level)]; }
    LineKind kind = LineKind::Other;
    std::vector<unsigned char>
        edges;  // per cell edge: bit 0 along a ridge cell, bit 1 along a thalweg cell
};

double seg_dist(const Point& p, const Point& a, const Point& b);

void douglas_peucker(const std::vector<Point>& pts, std::size_t a, std::size_t b, double tol,
                     std::vector<char>& keep);

std::vector<Point> simplify(const std::vector<Point>& pts, bool closed, double tol);

// The stair steps of a border chain cut at one point per cell edge (`cuts`: BorderPlaces, the
// edge's middle or a sub-cell position near it), so a one-cell staircase becomes its
// diagonal, between the chain's end nodes `from` and `to` (NodePlaces). Every chain through a
// node ends at the same point, so the chains of neighbouring faces still meet and the faces
// still tile the rock exactly: both faces of a border use the same chain. A closed chain
// without a node is the loop of its cut points.
std::vector<Point> cut_steps(const std::vector<Point>& cuts, bool closed, const Point& from,
                             const Point& to);

// Where a border crosses each cell edge, below the cell size (issue 16: borders traced at
// sub-cell precision, not along the grid's axes):
//  - a ridge or thalweg border lies on its line, through the line cell beside the edge: a
//    ridge through the cell's centre; a thalweg on its floor, moved across from the centre to
//    the low point of a parabola through the smoothed heights of the cell and its two
//    neighbours across the edge (sub-pixel peak fitting). Not ridges: a border that wraps
//    around a crest cell would then turn more tightly than the crest ornaments' band can
//    follow (51 of Chamonix.tif's 599 ridges lost their ornament), and ridge precision on
//    the sample did not gain;
//  - the rock outline lies where the slope (the small window's where the edge follows the
//    terrain, else the averaged one) crosses the rock threshold between the
//    centres of the rock cell and the cell outside, where it does cross it (elsewhere the
//    outline was drawn by the closing or the gap filling, and the edge's middle is kept);
//  - any other border crosses at the edge's middle.
struct BorderPlaces {
    const Grid& g;
    const std::vector<int>& face;
    const std::vector<int>& line_cells;  // 0 none, 1 ridge, 2 thalweg
    const std::vector<float>& slope;     // the slope the mask's edge was drawn with, percent
    const std::vector<float>& z;         // the smoothed DEM
    double min_slope;
    // Where the grid lies in the whole raster's pixel grid (grid.hpp, window_offset): cells are
    // indexed in the grid, the places returned are in the whole raster's grid.
    Point offset{0, 0};
    // The user's mask burnt onto the grid (empty: none): the outline does not move past the
    // middle of an edge towards a cell outside it.
    const std::vector<char>* inside = nullptr;

    // How far a thalweg's floor may move off its cell's centre, and how close the outline may
    // come to a cell's centre, in cells: the points stay near the edge they cut, so borders
    // of narrow faces seldom cross.
    static constexpr double kMaxFloorShiftCells = 0.45;
    static constexpr double kOutlineMarginCells = 0.15;

    Point cut(const Point& a, const Point& b, LineKind kind) const {
        const Point m = (a + b) / 2;
        // The two cells across the unit edge a-b: 0 above (left), 1 below (right).
        const bool horizontal = a.y == b.y;
        const int c0 = int(std::floor(horizontal ? m.x : m.x - 0.5));
        const int r0 = int(std::floor(horizontal ? m.y - 0.5 : m.y));
        const int c1 = horizontal ? c0 : c0 + 1, r1 = horizontal ? r0 + 1 : r0;
        if (kind != LineKind::Other) {
            // Only onto line cells of a face: the rock outline does not move out of the rock.
            auto on = [&](int c, int r) {
                return g.inside(c, r) && line_cells[g.at(c, r)] == int(kind) &&
                       face[g.at(c, r)] >= 0;
            };
            const bool on0 = on(c0, r0), on1 = on(c1, r1);
            if (on0 == on1) return m + offset;
            const int c = on0 ? c0 : c1, r = on0 ? r0 : r1;
            const Point centre{c + offset.x + 0.5, r + offset.y + 0.5};
            if (kind == LineKind::Ridge) return centre;
            // Across the edge: rows for a horizontal edge, columns for a vertical one.
            const int sc = horizontal ? 0 : 1, sr = horizontal ? 1 : 0;
            if (!g.inside(c - sc, r - sr) || !g.inside(c + sc, r + sr)) return centre;
            const double zm = z[g.at(c - sc, r - sr)], z0 = z[g.at(c, r)],
                         zp = z[g.at(c + sc, r + sr)];
            const double curve = zm - 2 * z0 + zp;  // > 0 across a floor
            if (!std::isfinite(curve) || curve <= 0) return centre;
            const double t =
                std::clamp(0.5 * (zm - zp) / curve, -kMaxFloorShiftCells, kMaxFloorShiftCells);
            return centre + Point{sc * t, sr * t};
        }
        const bool in0 = g.inside(c0, r0) && face[g.at(c0, r0)] >= 0,
                   in1 = g.inside(c1, r1) && face[g.at(c1, r1)] >= 0;
        if (in0 == in1 || !g.inside(c0, r0) || !g.inside(c1, r1)) return m + offset;
        const double s_in = slope[g.at(in0 ? c0 : c1, in0 ? r0 : r1)],
                     s_out = slope[g.at(in0 ? c1 : c0, in0 ? r1 : r0)];
        if (!(s_in >= min_slope && s_out < min_slope)) return m + offset;
        if (inside && !inside->empty() && !(*inside)[g.at(in0 ? c1 : c0, in0 ? r1 : r0)]) return m + offset;
        // Fraction of the way from the rock cell's centre to the outside cell's centre.
        const double t = std::clamp((s_in - min_slope) / (s_in - s_out), kOutlineMarginCells,
                                    1 - kOutlineMarginCells);
        const Point p0{c0 + offset.x + 0.5, r0 + offset.y + 0.5}, p1{c1 + offset.x + 0.5, r1 + offset.y + 0.5};
        const Point from = in0 ? p0 : p1, to = in0 ? p1 : p0;
        return from + (to - from) * t;
    }
};

// Where the chains meeting at a node end: the cell corner moved to the mean of the middles of
// the cell edges that meet there (by at most kMaxNodeShiftCells along each axis), so a short
// border between two nodes does not run along a cell edge. The middles, not the chains' cut
// points, so that the place does not depend on the borders' labels (labelling the outline or
// not leaves the inner borders as they are). Every chain through the node ends at this one
// point, whatever its level of generalisation.
class NodePlaces {
public:
    static constexpr double kMaxNodeShiftCells = 0.35;

    void add(long long id, const Point& corner, const Point& edge_middle) {
        Sum& s = sums_[id];
        s.corner = corner;
        s.middles = s.middles + edge_middle;
        ++s.n;
    }
    // The node stays at its corner from now on (a face whose cell edges alone are valid).
    void pin(long long id) { sums_[id].pinned = true; }
    Point place(long long id) const {
        const auto it = sums_.find(id);
        if (it == sums_.end()) return {};
        const Sum& s = it->second;
        const Point d = s.pinned ? Point{0, 0} : s.middles / double(s.n) - s.corner;
        return s.corner + Point{std::clamp(d.x, -kMaxNodeShiftCells, kMaxNodeShiftCells),
                                std::clamp(d.y, -kMaxNodeShiftCells, kMaxNodeShiftCells)};
    }

private:
    struct Sum {
        Point corner, middles{0, 0};
        int n = 0;
        bool pinned = false;
    };
    std::map<long long, Sum> sums_;
};

// The cut chain generalised: simplified within `tol` cells, then rounded by `rounds` passes
// of corner cutting at 1/4 and 3/4 of each segment (each pass stays inside the previous
// polyline's hull; the ends stay).
std::vector<Point> generalise(const std::vector<Point>& cut, bool closed, double tol, int rounds);

// Traces the borders between faces (and between faces and the outside) as chains of cell
// edges between nodes (corners where three or four edges meet).
std::vector<Chain> trace_chains(const Grid& g, const std::vector<int>& face,
                                const std::vector<int>& kind);

// Labels the chains by the line cells they run along, piece by piece: each chain is cut where
// it passes from running along ridge cells to thalweg cells or to neither, pieces shorter than
// `min_run` cell edges taking the label of their longer neighbour (so a border is not chopped
// at every kink of a line). Borders of the rock outline are labelled too when `outline` is set:
// an arête is often the very edge of the steep area.
std::vector<Chain> label_chains(std::vector<Chain> chains, int corner_w, int min_run, bool outline);

}  // namespace carto::extraction
