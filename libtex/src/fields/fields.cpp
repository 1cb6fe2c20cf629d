// Control fields: builders, compositions, the locality check.
#include "libtex/fields.hpp"
#include "libtex/random.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tex {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::optional<BBox> intersect(const std::optional<BBox>& a, const std::optional<BBox>& b) {
    if (!a) return b;
    if (!b) return a;
    BBox r;
    r.xmin = std::max(a->xmin, b->xmin);
    r.ymin = std::max(a->ymin, b->ymin);
    r.xmax = std::min(a->xmax, b->xmax);
    r.ymax = std::min(a->ymax, b->ymax);
    return r;
}

std::optional<BBox> unite(const std::optional<BBox>& a, const std::optional<BBox>& b) {
    if (!a || !b) return std::nullopt;
    BBox r = *a;
    r.add(*b);
    return r;
}

class ConstantImpl : public FieldImpl {
public:
    explicit ConstantImpl(double v) : v_(v) {}
    double eval(const Point&) const override { return v_; }
    const char* kind() const override { return std::isnan(v_) ? "none" : "constant"; }

private:
    double v_;
};

class FunctionImpl : public FieldImpl {
public:
    FunctionImpl(Field::Fn fn, std::optional<BBox> domain) : fn_(std::move(fn)), domain_(domain) {}
    double eval(const Point& p) const override {
        if (domain_ && !domain_->contains(p)) return kNaN;
        return fn_(p);
    }
    std::optional<BBox> domain() const override { return domain_; }

private:
    Field::Fn fn_;
    std::optional<BBox> domain_;
};

class GridImpl : public FieldImpl {
public:
    explicit GridImpl(GridSamples g) : g_(std::move(g)) {
        BBox b;
        for (double c : {0.0, double(g_.width)})
            for (double r : {0.0, double(g_.height)}) {
                const auto& t = g_.transform;
                b.add(Point{t[0] + c * t[1] + r * t[2], t[3] + c * t[4] + r * t[5]});
            }
        box_ = b;
    }
    double eval(const Point& p) const override {
        return sample_grid(g_.values->data(), g_.width, g_.height, g_.transform, p);
    }
    std::optional<BBox> domain() const override { return box_; }
    const char* kind() const override { return "grid"; }

private:
    GridSamples g_;
    BBox box_;
};

// Regions indexed by a grid of their bounding boxes; a lookup tests the regions listed in
// the point's cell, in index order.
class RegionImpl : public FieldImpl {
public:
    RegionImpl(std::vector<Region> regions, std::vector<double> values, const char* kind)
        : locator_(std::move(regions)), values_(std::move(values)), kind_(kind) {}
    double eval(const Point& q) const override {
        const int k = locator_.find(q);
        return k >= 0 ? values_[std::size_t(k)] : kNaN;
    }
    std::optional<BBox> domain() const override { return locator_.area(); }
    const char* kind() const override { return kind_; }

private:
    RegionLocator locator_;  // every region kept (no area given), so indices are the values'
    std::vector<double> values_;
    const char* kind_;
};

// A field of the values of other fields.
template <class Op>
class ComposedImpl : public FieldImpl {
public:
    ComposedImpl(std::vector<Field> in, Op op, std::optional<BBox> domain)
        : in_(std::move(in)), op_(std::move(op)), domain_(domain) {}
    double eval(const Point& p) const override { return op_(in_, p); }
    std::optional<BBox> domain() const override { return domain_; }
    const char* kind() const override { return "composite"; }

private:
    std::vector<Field> in_;
    Op op_;
    std::optional<BBox> domain_;
};

template <class Op>
Field composed(std::vector<Field> in, Op op, std::optional<BBox> domain) {
    return Field(std::make_shared<ComposedImpl<Op>>(std::move(in), std::move(op), domain));
}

// The value of input i, read without counting a second read.
inline double at(const std::vector<Field>& in, std::size_t i, const Point& p) { return in[i].impl()->eval(p); }

template <class Op>
Field binary(const Field& a, const Field& b, Op op) {
    return composed({a, b}, [op](const std::vector<Field>& in, const Point& p) { return op(at(in, 0, p), at(in, 1, p)); },
                    intersect(a.domain(), b.domain()));
}

class VectorFnImpl : public VectorFieldImpl {
public:
    explicit VectorFnImpl(VectorField::Fn fn) : fn_(std::move(fn)) {}
    Point eval(const Point& p) const override { return fn_(p); }

private:
    VectorField::Fn fn_;
};

class VectorPairImpl : public VectorFieldImpl {
public:
    VectorPairImpl(Field x, Field y) : x_(std::move(x)), y_(std::move(y)) {}
    Point eval(const Point& p) const override { return {x_.impl()->eval(p), y_.impl()->eval(p)}; }

private:
    Field x_, y_;
};

// A field of a vector field's values.
template <class Op>
class OfVectorImpl : public FieldImpl {
public:
    OfVectorImpl(VectorField v, Op op) : v_(std::move(v)), op_(op) {}
    double eval(const Point& p) const override {
        const Point q = v_.impl()->eval(p);
        if (std::isnan(q.x) || std::isnan(q.y)) return kNaN;
        return op_(q);
    }
    const char* kind() const override { return "composite"; }

private:
    VectorField v_;
    Op op_;
};

template <class Op>
Field of_vector(VectorField v, Op op) {
    return Field(std::make_shared<OfVectorImpl<Op>>(std::move(v), op));
}

class GradientImpl : public VectorFieldImpl {
public:
    GradientImpl(Field f, double h) : f_(std::move(f)), h_(h) {}
    Point eval(const Point& p) const override {
        const FieldImpl& f = *f_.impl();
        return {(f.eval({p.x + h_, p.y}) - f.eval({p.x - h_, p.y})) / (2 * h_),
                (f.eval({p.x, p.y + h_}) - f.eval({p.x, p.y - h_})) / (2 * h_)};
    }

private:
    Field f_;
    double h_;
};

// ---- Locality ----

thread_local detail::WindowState t_window;
std::atomic<LocalityCheck::State*> g_active{nullptr};

}  // namespace

// ---- Field ----

namespace {
const std::shared_ptr<const FieldImpl>& nan_impl() {
    static const std::shared_ptr<const FieldImpl> none = std::make_shared<ConstantImpl>(kNaN);
    return none;
}
}  // namespace

Field::Field() : impl_(nan_impl()) {}
Field::Field(double v) : impl_(std::make_shared<ConstantImpl>(v)) {}
Field::Field(std::shared_ptr<const FieldImpl> impl) : impl_(std::move(impl)) {
    if (!impl_) impl_ = nan_impl();
}

Field Field::from_function(Fn fn) {
    if (!fn) return Field();
    return Field(std::make_shared<FunctionImpl>(std::move(fn), std::nullopt));
}

bool Field::has_value(const Point& p) const { return !std::isnan((*this)(p)); }

Field ConstantField(double v) { return Field(v); }

Field FunctionField(Field::Fn fn, std::optional<BBox> domain) {
    if (!fn) throw Error("FunctionField", "no function given");
    return Field(std::make_shared<FunctionImpl>(std::move(fn), domain));
}

// ---- Grids ----

double nearest_grid(const float* values, int width, int height, const std::array<double, 6>& t, const Point& w) {
    return nearest_grid_pixel(values, width, height, grid_pixel(t, w));
}

double nearest_grid_pixel(const float* values, int width, int height, const Point& p) {
    const int c = int(std::floor(p.x)), r = int(std::floor(p.y));
    if (c < 0 || r < 0 || c >= width || r >= height) return kNaN;
    return values[std::size_t(r) * width + c];
}

double sample_grid(const float* values, int width, int height, const std::array<double, 6>& t, const Point& w) {
    return sample_grid_pixel(values, width, height, grid_pixel(t, w));
}

double sample_grid_edge(const float* values, int width, int height, const Point& p) {
    const double fx = p.x - 0.5, fy = p.y - 0.5;
    if (!(p.x >= 0 && p.y >= 0 && p.x <= width && p.y <= height)) return kNaN;
    int x0 = int(fx), y0 = int(fy);
    x0 -= fx < x0;
    y0 -= fy < y0;
    const double tx = fx - x0, ty = fy - y0;
    double sum = 0, wsum = 0;
    for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
            const int cx = std::clamp(x0 + dx, 0, width - 1), cy = std::clamp(y0 + dy, 0, height - 1);
            const float v = values[std::size_t(cy) * width + cx];
            if (std::isnan(v)) continue;
            const double wgt = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty);
            sum += wgt * v;
            wsum += wgt;
        }
    if (wsum <= 1e-12) return nearest_grid_pixel(values, width, height, p);
    return sum / wsum;
}

Field GridField(GridSamples g) {
    if (g.width < 1 || g.height < 1)
        throw Error("GridField", "the grid is empty (" + std::to_string(g.width) + " x " + std::to_string(g.height) + ")");
    if (!g.values || g.values->size() != std::size_t(g.width) * std::size_t(g.height))
        throw Error("GridField", std::to_string(g.values ? g.values->size() : 0) + " values for a " +
                                     std::to_string(g.width) + " x " + std::to_string(g.height) + " grid");
    const auto& t = g.transform;
    if (t[1] * t[5] - t[2] * t[4] == 0 || !std::isfinite(t[1] * t[5] - t[2] * t[4]))
        throw Error("GridField", "the transform is not invertible");
    return Field(std::make_shared<GridImpl>(std::move(g)));
}

// ---- Face-wise constant fields ----

Field FaceField(MapPtr map, std::vector<double> values) {
    if (!map) throw Error("FaceField", "no planar map");
    const auto& faces = map->faces();
    if (values.size() != faces.size())
        throw Error("FaceField", std::to_string(values.size()) + " values for " + std::to_string(faces.size()) + " faces");
    std::vector<Region> regions(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        if (faces[f].unbounded || faces[f].cycles.empty()) continue;
        std::vector<std::vector<Point>> holes;
        for (std::size_t c = 1; c < faces[f].cycles.size(); ++c) holes.push_back(map->cycle_points(int(f), c));
        try {
            regions[f] = Region(map->cycle_points(int(f), 0), std::move(holes), "FaceField");
        } catch (const Error&) {
            // A face without area holds no point.
        }
    }
    return Field(std::make_shared<RegionImpl>(std::move(regions), std::move(values), "faces"));
}

Field RegionField(std::vector<Region> regions, std::vector<double> values) {
    if (values.size() != regions.size())
        throw Error("RegionField",
                    std::to_string(values.size()) + " values for " + std::to_string(regions.size()) + " regions");
    return Field(std::make_shared<RegionImpl>(std::move(regions), std::move(values), "faces"));
}

// ---- Compositions ----

Field Apply(Field f, std::function<double(double)> fn) {
    if (!fn) throw Error("Apply", "no function given");
    const auto dom = f.domain();
    return composed({std::move(f)},
                    [fn = std::move(fn)](const std::vector<Field>& in, const Point& p) {
                        const double v = at(in, 0, p);
                        return std::isnan(v) ? v : fn(v);
                    },
                    dom);
}

Field Combine(Field f, Field g, std::function<double(double, double)> fn) {
    if (!fn) throw Error("Combine", "no function given");
    return binary(f, g, [fn = std::move(fn)](double a, double b) { return std::isnan(a) || std::isnan(b) ? kNaN : fn(a, b); });
}

Field operator+(const Field& a, const Field& b) { return binary(a, b, std::plus<double>()); }
Field operator-(const Field& a, const Field& b) { return binary(a, b, std::minus<double>()); }
Field operator*(const Field& a, const Field& b) { return binary(a, b, std::multiplies<double>()); }
Field operator/(const Field& a, const Field& b) { return binary(a, b, std::divides<double>()); }
Field operator-(const Field& a) {
    return composed({a}, [](const std::vector<Field>& in, const Point& p) { return -at(in, 0, p); }, a.domain());
}

Field Pow(Field f, double exponent) {
    if (!std::isfinite(exponent)) throw Error("Pow", "the exponent must be finite");
    const auto dom = f.domain();
    return composed({std::move(f)},
                    [exponent](const std::vector<Field>& in, const Point& p) {
                        const double v = at(in, 0, p);
                        return std::isnan(v) ? v : std::pow(v, exponent);
                    },
                    dom);
}

Field Clamp(Field f, double lo, double hi) {
    if (!(lo <= hi)) throw Error("Clamp", "lo must not exceed hi");
    const auto dom = f.domain();
    return composed({std::move(f)},
                    [lo, hi](const std::vector<Field>& in, const Point& p) {
                        const double v = at(in, 0, p);
                        return std::isnan(v) ? v : std::clamp(v, lo, hi);
                    },
                    dom);
}

Field Restrict(Field f, const BBox& box) {
    const auto dom = intersect(f.domain(), box);
    return composed({std::move(f)},
                    [box](const std::vector<Field>& in, const Point& p) { return box.contains(p) ? at(in, 0, p) : kNaN; },
                    dom);
}

Field Restrict(Field f, Region region) {
    const auto dom = intersect(f.domain(), region.bbox());
    return composed({std::move(f)},
                    [region = std::move(region)](const std::vector<Field>& in, const Point& p) {
                        return region.contains(p) ? at(in, 0, p) : kNaN;
                    },
                    dom);
}

Field Fallback(Field f, Field g) {
    const auto dom = unite(f.domain(), g.domain());
    return composed({std::move(f), std::move(g)},
                    [](const std::vector<Field>& in, const Point& p) {
                        const double v = at(in, 0, p);
                        return std::isnan(v) ? at(in, 1, p) : v;
                    },
                    dom);
}

namespace {
// The nodes of one cell of a Noise lattice.
struct NoiseCell {
    bool valid = false;
    std::uint64_t key = 0;
    double wavelength = 0, fx = 0, fy = 0;
    double n00 = 0, n10 = 0, n01 = 0, n11 = 0;
};
}  // namespace

Field Noise(double wavelength) {
    if (!(wavelength > 0) || !std::isfinite(wavelength))
        throw Error("Noise", "the wavelength must be positive and finite (got " + std::to_string(wavelength) + ")");
    const std::uint64_t key = hash_combine(0x4E4F495345ULL, GetSeed());
    return FunctionField([key, wavelength](const Point& p) {
        const double x = p.x / wavelength, y = p.y / wavelength;
        const double fx = std::floor(x), fy = std::floor(y);
        // The value at node (fx + i, fy + j) hashes the column's hash with the row: each
        // column hashed once. Readings come in runs within one lattice cell (the points of a
        // stroke): the thread keeps the last cell's four nodes.
        thread_local NoiseCell last;
        if (!(last.valid && last.key == key && last.wavelength == wavelength && last.fx == fx && last.fy == fy)) {
            const std::uint64_t c0 = hash_double(key, fx), c1 = hash_double(key, fx + 1);
            auto node = [](std::uint64_t column, double row) { return 2 * unit_from_hash(hash_double(column, row)) - 1; };
            last = {true, key, wavelength, fx, fy, node(c0, fy), node(c1, fy), node(c0, fy + 1), node(c1, fy + 1)};
        }
        const double n00 = last.n00, n10 = last.n10, n01 = last.n01, n11 = last.n11;
        auto smooth = [](double t) { return t * t * (3 - 2 * t); };
        const double u = smooth(x - fx), v = smooth(y - fy);
        const double a = n00 + (n10 - n00) * u;
        const double b = n01 + (n11 - n01) * u;
        return a + (b - a) * v;
    });
}

// ---- Vector fields ----

VectorField::VectorField() : VectorField(Point{kNaN, kNaN}) {}
VectorField::VectorField(Fn fn) {
    if (!fn) throw Error("VectorField", "no function given");
    impl_ = std::make_shared<VectorFnImpl>(std::move(fn));
}
VectorField::VectorField(Field x, Field y) : impl_(std::make_shared<VectorPairImpl>(std::move(x), std::move(y))) {}
VectorField::VectorField(const Point& c) : impl_(std::make_shared<VectorFnImpl>([c](const Point&) { return c; })) {}
VectorField::VectorField(std::shared_ptr<const VectorFieldImpl> impl) : impl_(std::move(impl)) {
    if (!impl_) *this = VectorField();
}

Field Angle(VectorField v) {
    return of_vector(std::move(v), [](const Point& q) { return std::atan2(q.y, q.x); });
}

Field Norm(VectorField v) {
    return of_vector(std::move(v), [](const Point& q) { return std::hypot(q.x, q.y); });
}

Arrangement AlignToField(Arrangement a, Field angle) {
    return Arrangement([a = std::move(a), angle = std::move(angle)](const Region& r) {
        Curves c = a(r);
        for (Curve& cv : c.curves) {
            if (cv.closed || cv.points.size() < 2) continue;
            const Point p0 = cv.points.front(), p1 = cv.points.back();
            const Point d = p1 - p0;
            if (std::hypot(d.x, d.y) < 1e-12) continue;
            const Point mid = (p0 + p1) * 0.5;
            const double want = angle(mid);
            if (std::isnan(want)) continue;
            // Turn by the smallest angle that lays the curve on the axis `want`.
            double turn = std::remainder(want - std::atan2(d.y, d.x), M_PI);
            const double cs = std::cos(turn), sn = std::sin(turn);
            for (Point& q : cv.points) {
                const Point v = q - mid;
                q = mid + Point{cs * v.x - sn * v.y, sn * v.x + cs * v.y};
            }
        }
        return c;
    });
}

VectorField Gradient(Field f, double h) {
    if (!(h > 0) || !std::isfinite(h)) throw Error("Gradient", "the step must be positive");
    return VectorField(std::make_shared<GradientImpl>(std::move(f), h));
}

// ---- Controlled values ----

namespace detail {

void wrong_arity(const char* what, const std::string& name, std::size_t want, std::size_t got) {
    throw Error(name.empty() ? std::string(what) : name,
                std::string(what) + " '" + name + "' takes " + std::to_string(want) + " field" +
                    (want == 1 ? "" : "s") + ", got " + std::to_string(got));
}

}  // namespace detail

// ---- Local control ----

struct LocalityCheck::State {
    double margin = 0;
    std::atomic<std::size_t> reads{0}, violations{0};
    std::atomic<double> worst{0};
};

namespace detail {

std::atomic<int> g_locality_checks{0};

void locality_read(const Point& p) {
    if (!t_window.open) return;
    LocalityCheck::State* s = g_active.load(std::memory_order_acquire);
    if (!s) return;
    s->reads.fetch_add(1, std::memory_order_relaxed);
    const BBox& b = t_window.box;
    const double dx = std::max({b.xmin - p.x, 0.0, p.x - b.xmax});
    const double dy = std::max({b.ymin - p.y, 0.0, p.y - b.ymax});
    const double d = std::hypot(dx, dy);
    if (!(d > s->margin)) return;
    s->violations.fetch_add(1, std::memory_order_relaxed);
    double w = s->worst.load(std::memory_order_relaxed);
    while (d > w && !s->worst.compare_exchange_weak(w, d, std::memory_order_relaxed)) {
    }
}

WindowState capture_window() { return t_window; }
void restore_window(const WindowState& w) { t_window = w; }

}  // namespace detail

LocalityCheck::LocalityCheck(double margin) : state_(std::make_unique<State>()) {
    if (!(margin >= 0)) throw Error("LocalityCheck", "the margin must be a non-negative number");
    state_->margin = margin;
    previous_ = g_active.exchange(state_.get());
    detail::g_locality_checks.fetch_add(1);
}

LocalityCheck::~LocalityCheck() {
    g_active.store(previous_);
    detail::g_locality_checks.fetch_sub(1);
}

double LocalityCheck::margin() const { return state_->margin; }
std::size_t LocalityCheck::reads() const { return state_->reads.load(); }
std::size_t LocalityCheck::violations() const { return state_->violations.load(); }
double LocalityCheck::worst() const { return state_->worst.load(); }

FieldWindow::FieldWindow(const BBox& box) : saved_(t_window) {
    t_window.open = true;
    t_window.box = box;
}

FieldWindow::~FieldWindow() { t_window = saved_; }

}  // namespace tex
