#include "libtex/mappers.hpp"

#include <cmath>
#include <utility>

#include "libtex/cells.hpp"
#include "libtex/curves.hpp"
#include "libtex/error.hpp"
#include "libtex/labels.hpp"
#include "libtex/random.hpp"

namespace tex {

EdgeMapper JitterEdges(const std::string& label, double theta, double across, double along, double r, double gap,
                       Field gate, double gate_min) {
    const LabelId id = intern_label(label);
    const Point d{std::cos(theta), std::sin(theta)}, n{-d.y, d.x};
    const double half_across = across * r / 2, half_along = along * r / 2;
    return [=, gate = std::move(gate)](const Edge& e) -> Curves {
        if (!record(e).labels.has(id)) return Nothing();
        if (gate_min > 0 && !(gate(LocationAt(e, 0.5)) >= gate_min)) return Nothing();
        auto moved = [&](const Vertex& v) {
            return Location(v) + n * Random(v, -half_across, half_across, 0) +
                   d * Random(v, -half_along, half_along, 1);
        };
        // One curve, moved and shortened where it lies (MatchPoints then Scale, without the
        // copy each of them makes).
        const Vertex s = SourceVertex(e), t = TargetVertex(e);
        Curves c = ToCurve(e);
        detail::match_points_in_place(c, Location(s), Location(t), moved(s), moved(t));
        if (gap < 1) detail::scale_in_place(c, gap);
        return c;
    };
}

double ThinRank(long long k) {
    constexpr double phi = 0.6180339887498948482;  // (sqrt(5) - 1) / 2
    const double x = double(k) * phi;
    return x - std::floor(x);
}

EdgeMapper ThinLines(EdgeMapper inner, double theta, double spacing, Field keep, Region owner) {
    if (!inner) throw Error("ThinLines", "no inner mapper");
    if (!(spacing > 0) || !std::isfinite(spacing)) throw Error("ThinLines", "the spacing must be positive and finite");
    if (!std::isfinite(theta)) throw Error("ThinLines", "theta must be finite");
    const Point n{-std::sin(theta), std::cos(theta)};
    const bool owned = !owner.empty();
    return [=, inner = std::move(inner), keep = std::move(keep), owner = std::move(owner)](const Edge& e) -> Curves {
        const Point mid = LocationAt(e, 0.5);
        if (owned && !owner.contains(mid)) return Nothing();
        const double t = (mid.x * n.x + mid.y * n.y) / spacing;
        if (!(std::abs(t) < 1e15)) return Nothing();  // beyond exact integers: no line index
        const double k = keep(mid);
        if (!(ThinRank(std::llround(t)) < k)) return Nothing();
        return inner(e);
    };
}

}  // namespace tex
