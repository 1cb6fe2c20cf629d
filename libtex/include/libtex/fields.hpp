// Control fields, controlled arrangements and controlled mappers (thesis 5.3).
//
// A field gives a value at every point of the plane, NaN where it has none (outside its
// domain, or NoData). Fields are values: cheap to copy, immutable, safe to read from any
// thread. They know nothing of GIS: a raster is a sampled grid with an affine transform.
//
// Local control: a controlled mapper should read its fields only near the cell it visits.
// A LocalityCheck, while alive, compares every read with the window of the reading thread
// (the bounding box of the cell being mapped, or a FieldWindow the caller opens) and counts
// the reads that land farther than its margin outside it.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "libtex/arrangement.hpp"
#include "libtex/cells.hpp"
#include "libtex/error.hpp"
#include "libtex/geometry.hpp"
#include "libtex/region.hpp"

namespace tex {

namespace detail {
// Number of live LocalityChecks: the only thing a field read looks at when there is none.
extern std::atomic<int> g_locality_checks;
void locality_read(const Point& p);
}  // namespace detail

// What a field computes; subclass it for a new kind of field.
class FieldImpl {
public:
    virtual ~FieldImpl() = default;
    virtual double eval(const Point& p) const = 0;
    // Where the field may have values (nullopt: anywhere).
    virtual std::optional<BBox> domain() const { return std::nullopt; }
    // A short name of the kind of field ("constant", "grid", "faces", ...), for messages.
    virtual const char* kind() const { return "function"; }
};

class Field {
public:
    using Fn = std::function<double(const Point&)>;

    // NaN everywhere.
    Field();
    // A constant.
    Field(double v);  // NOLINT: implicit on purpose
    // Any callable double(const Point&).
    template <class F,
              std::enable_if_t<!std::is_same_v<std::decay_t<F>, Field> && !std::is_arithmetic_v<std::decay_t<F>> &&
                                   std::is_invocable_r_v<double, const std::decay_t<F>&, const Point&>,
                               int> = 0>
    Field(F&& f)  // NOLINT: implicit, so that lambdas are fields
        : Field(from_function(Fn(std::forward<F>(f)))) {}
    explicit Field(std::shared_ptr<const FieldImpl> impl);

    double operator()(const Point& p) const {
        if (detail::g_locality_checks.load(std::memory_order_relaxed) != 0) detail::locality_read(p);
        return impl_->eval(p);
    }
    double operator()(double x, double y) const { return (*this)(Point{x, y}); }
    std::optional<BBox> domain() const { return impl_->domain(); }
    bool has_value(const Point& p) const;
    const char* kind() const { return impl_->kind(); }
    // The implementation (compositions read it without counting a second read).
    const std::shared_ptr<const FieldImpl>& impl() const { return impl_; }

private:
    static Field from_function(Fn fn);
    std::shared_ptr<const FieldImpl> impl_;
};

// ---- Builders ----

Field ConstantField(double v);
// fn inside `domain` (the whole plane when none), NaN outside.
Field FunctionField(Field::Fn fn, std::optional<BBox> domain = std::nullopt);

// A sampled grid. transform is GDAL's: x = t0 + col*t1 + row*t2, y = t3 + col*t4 + row*t5,
// (col, row) in pixel units, (0.5, 0.5) the centre of the first cell. values: row-major,
// NaN = NoData.
struct GridSamples {
    int width = 0, height = 0;
    std::array<double, 6> transform{0, 1, 0, 0, 0, -1};
    std::shared_ptr<const std::vector<float>> values;
};
// Bilinear interpolation over the four cell centres around p; NoData neighbours are left
// out and the weights renormalised; NaN outside the grid; when no neighbour has weight,
// the value of the cell containing p. A rotated transform is inverted.
double sample_grid(const float* values, int width, int height, const std::array<double, 6>& t, const Point& p);
// Value of the cell containing p (NaN outside).
double nearest_grid(const float* values, int width, int height, const std::array<double, 6>& t, const Point& p);
// Pixel position (col, row) of a world point.
inline Point grid_pixel(const std::array<double, 6>& t, const Point& p) {
    if (t[2] == 0 && t[4] == 0) return {(p.x - t[0]) / t[1], (p.y - t[3]) / t[5]};
    const double det = t[1] * t[5] - t[2] * t[4];
    const double dx = p.x - t[0], dy = p.y - t[3];
    return {(t[5] * dx - t[2] * dy) / det, (t[1] * dy - t[4] * dx) / det};
}
// sample_grid and nearest_grid at a pixel position (col, row; 0.5 = a cell centre): for a
// window of a larger grid, whose callers compute the position in the larger grid and
// subtract the window's integer offset (exact), so a window samples the same bits as the
// whole grid. Every field reading of a raster comes here: the common case (four cells
// inside the grid, none NaN) is inline, the rest (borders, NoData) in sample_grid_edge.
double sample_grid_edge(const float* values, int width, int height, const Point& pixel);
inline double sample_grid_pixel(const float* values, int width, int height, const Point& p) {
    const double fx = p.x - 0.5, fy = p.y - 0.5;
    if (!(p.x >= 0 && p.y >= 0 && p.x <= width && p.y <= height)) return std::numeric_limits<double>::quiet_NaN();
    // floor(fx) and floor(fy) (fx, fy >= -0.5 and within int here): the truncation, one less
    // below it.
    int x0 = int(fx), y0 = int(fy);
    x0 -= fx < x0;
    y0 -= fy < y0;
    if (x0 >= 0 && y0 >= 0 && x0 + 1 < width && y0 + 1 < height) {
        const double tx = fx - x0, ty = fy - y0;
        const float* row = values + std::size_t(y0) * width + x0;
        const float v00 = row[0], v10 = row[1], v01 = row[width], v11 = row[width + 1];
        if (!(v00 != v00 || v10 != v10 || v01 != v01 || v11 != v11)) {
            // sample_grid_edge's weighted mean in the same operations and order: the same bits.
            const double w00 = (1 - tx) * (1 - ty), w10 = tx * (1 - ty), w01 = (1 - tx) * ty, w11 = tx * ty;
            double sum = 0, wsum = 0;
            sum += w00 * v00;
            wsum += w00;
            sum += w10 * v10;
            wsum += w10;
            sum += w01 * v01;
            wsum += w01;
            sum += w11 * v11;
            wsum += w11;
            if (wsum > 1e-12) return sum / wsum;
        }
    }
    return sample_grid_edge(values, width, height, p);
}
double nearest_grid_pixel(const float* values, int width, int height, const Point& pixel);
// The grid as a field (sample_grid). Throws tex::Error naming GridField on a bad grid.
Field GridField(GridSamples g);

// Face-wise constant over a planar map: values[face id] on each bounded face, NaN in the
// unbounded one. A point on an edge takes the value of its adjacent face of smallest id.
Field FaceField(MapPtr map, std::vector<double> values);
// Face-wise constant over disjoint regions: values[i] inside regions[i] (borders included;
// the smallest index wins on a shared border), NaN outside all.
Field RegionField(std::vector<Region> regions, std::vector<double> values);

// ---- Compositions (NaN in, NaN out) ----

// fn of the value (fn is not called on NaN).
Field Apply(Field f, std::function<double(double)> fn);
// fn of both values (not called when either is NaN).
Field Combine(Field f, Field g, std::function<double(double, double)> fn);
Field operator+(const Field& a, const Field& b);
Field operator-(const Field& a, const Field& b);
Field operator*(const Field& a, const Field& b);
Field operator/(const Field& a, const Field& b);
Field operator-(const Field& a);
Field Clamp(Field f, double lo, double hi);
// std::pow(value, exponent) (a tone curve, a gamma).
Field Pow(Field f, double exponent);
// f inside the box (or region, borders included), NaN outside.
Field Restrict(Field f, const BBox& box);
Field Restrict(Field f, Region region);
// f where it has a value, else g.
Field Fallback(Field f, Field g);
// Smooth noise of the plane in [-1, 1]: values drawn at the nodes of a square lattice
// `wavelength` apart on the plane's axes (keyed by the node and the seed at the call, so any
// region or tile reads the same noise), interpolated between them with a smoothstep. Throws
// tex::Error naming Noise for a wavelength that is not positive.
Field Noise(double wavelength);

// ---- Vector fields ----

class VectorFieldImpl {
public:
    virtual ~VectorFieldImpl() = default;
    virtual Point eval(const Point& p) const = 0;
};

// A vector at every point; NaN components where there is none.
class VectorField {
public:
    using Fn = std::function<Point(const Point&)>;

    // NaN everywhere.
    VectorField();
    explicit VectorField(Fn fn);
    VectorField(Field x, Field y);
    explicit VectorField(const Point& constant);
    explicit VectorField(std::shared_ptr<const VectorFieldImpl> impl);

    Point operator()(const Point& p) const {
        if (detail::g_locality_checks.load(std::memory_order_relaxed) != 0) detail::locality_read(p);
        return impl_->eval(p);
    }
    const std::shared_ptr<const VectorFieldImpl>& impl() const { return impl_; }

private:
    std::shared_ptr<const VectorFieldImpl> impl_;
};

// Direction of the vectors (atan2(y, x), radians).
Field Angle(VectorField v);
// Length of the vectors.
Field Norm(VectorField v);
// Central differences with step h.
VectorField Gradient(Field f, double h);

// Each open curve of `a` turned about its middle (half-way between its two ends) so that
// its end-to-end direction follows the axial angle `angle` (radians) read there; of the two
// senses of that axis the one nearer the curve's own is kept. Closed curves, curves shorter
// than 1e-12 and curves whose middle reads NaN are left as they are. A control field read
// once per curve (thesis 5.3.2): strokes laid out by any partition bend with the field.
Arrangement AlignToField(Arrangement a, Field angle);

// The level set f = level as curves, by marching squares on the lattice of the points
// (i cell, j cell) of the plane: a global lattice, so the lines in a region are those of the
// plane whatever region they are drawn in (the same in a tile as in the whole). Each line
// runs with the values above `level` on its left; a lattice square with a NaN corner gives
// none, and a saddle is decided by the mean of its corners. Evaluated on a region: the
// lines through the squares meeting its bounding box, not cut to it (crop them). Throws
// tex::Error naming IsoLines for a cell that is not positive or a level that is not finite.
Arrangement IsoLines(Field f, double level, double cell);

// The crease lines of a surface f (height ridges): where it is highest (Ridge) or lowest
// (Valley) across its sharpest bend, the derivative along the Hessian's eigenvector of the
// most negative (positive) eigenvalue vanishing, that eigenvalue the stronger of the two and
// at least min_bend in magnitude (1 / length: the change of slope per unit across the line).
// The gradient and Hessian are central differences over the nodes of the lattice
// (i cell, j cell) of the plane, the lines traced across its squares: a global lattice, so a
// region draws the lines of the plane wherever it lies. Lines are open or closed polylines
// through crossings of lattice edges, unlabelled, in no particular sense. Both: the ridges
// then the valleys of one sampling of f (half the field reads of two calls), labelled "ridge"
// and "valley". Evaluated on a region: the lines through the squares meeting its bounding box
// (read one cell further), not cut to it. Throws tex::Error naming Creases for a cell that is
// not positive or a negative min_bend.
enum class CreaseKind { Ridge, Valley, Both };
Arrangement Creases(Field f, CreaseKind kind, double cell, double min_bend);

// ---- Controlled arrangements and mappers (thesis 5.3.1, 5.3.2) ----

namespace detail {
[[noreturn]] void wrong_arity(const char* what, const std::string& name, std::size_t want, std::size_t got);
}

// A function of n fields returning R, named for messages.
template <class R>
class Controlled {
public:
    using Fn = std::function<R(const std::vector<Field>&)>;

    Controlled(std::string name, std::size_t arity, Fn fn)
        : name_(std::move(name)), arity_(arity), fn_(std::move(fn)) {}

    R operator()(const std::vector<Field>& fields) const {
        if (fields.size() != arity_) detail::wrong_arity(what(), name_, arity_, fields.size());
        return fn_(fields);
    }
    template <class... F, std::enable_if_t<std::conjunction_v<std::is_convertible<F, Field>...>, int> = 0>
    R operator()(F&&... f) const {
        return (*this)(std::vector<Field>{Field(std::forward<F>(f))...});
    }
    const std::string& name() const { return name_; }
    std::size_t arity() const { return arity_; }

private:
    static const char* what() {
        return std::is_same_v<R, Arrangement> ? "controlled arrangement" : "controlled mapper";
    }
    std::string name_;
    std::size_t arity_;
    Fn fn_;
};

// (f1..fn) -> Arrangement.
class ControlledArrangement : public Controlled<Arrangement> {
public:
    using Controlled<Arrangement>::Controlled;
};

// (f1..fn) -> mapper of one kind of cell.
template <class CellT>
class ControlledMapper : public Controlled<std::function<Curves(const CellT&)>> {
public:
    using Controlled<std::function<Curves(const CellT&)>>::Controlled;
};
using ControlledVertexMapper = ControlledMapper<Vertex>;
using ControlledEdgeMapper = ControlledMapper<Edge>;
using ControlledFaceMapper = ControlledMapper<Face>;

// ---- Local control ----

// Counts the field reads that fall farther than `margin` outside the reading thread's
// window, while it lives. Reads with no window open are not checked. One at a time.
class LocalityCheck {
public:
    explicit LocalityCheck(double margin = 0);
    ~LocalityCheck();
    LocalityCheck(const LocalityCheck&) = delete;
    LocalityCheck& operator=(const LocalityCheck&) = delete;

    double margin() const;
    // Reads checked against a window, and those that fell outside it.
    std::size_t reads() const;
    std::size_t violations() const;
    // Largest distance of a read outside its window (0 when none).
    double worst() const;

    struct State;

private:
    std::unique_ptr<State> state_;
    State* previous_;
};

namespace detail {
// The window of a thread: follows parallel_for's work items like the random streams.
struct WindowState {
    bool open = false;
    BBox box;
};
WindowState capture_window();
void restore_window(const WindowState& w);
inline bool locality_checked() { return g_locality_checks.load(std::memory_order_relaxed) != 0; }
}  // namespace detail

// Opens a window for the reads of the current thread (innermost wins), restored at the end.
class FieldWindow {
public:
    explicit FieldWindow(const BBox& box);
    ~FieldWindow();
    FieldWindow(const FieldWindow&) = delete;
    FieldWindow& operator=(const FieldWindow&) = delete;

private:
    detail::WindowState saved_;
};

}  // namespace tex
