// Filling an outline: the region a frame bounds, and arrangements evaluated in it.
#include "libtex/domain.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "libtex/error.hpp"
#include "libtex/geometry.hpp"
#include "libtex/merge.hpp"

namespace tex {

Region FrameRegion(const Curves& frame, const std::string& op) {
    std::vector<const std::vector<Point>*> rings;
    for (const auto& c : frame.curves)
        if (c.closed && c.points.size() >= 3 && signed_area(c.points) != 0.0) rings.push_back(&c.points);
    if (rings.empty())
        throw Error(op, "the frame" + (frame.origin.empty() ? std::string() : " '" + frame.origin + "'") +
                            " has no closed curve with an area: it bounds no region");
    std::size_t outer = 0;
    for (std::size_t i = 1; i < rings.size(); ++i)
        if (std::abs(signed_area(*rings[i])) > std::abs(signed_area(*rings[outer]))) outer = i;
    std::vector<std::vector<Point>> holes;
    for (std::size_t i = 0; i < rings.size(); ++i) {
        if (i == outer) continue;
        // A hole lies inside the outside: all of its points do.
        for (const auto& p : *rings[i])
            if (!point_in_ring(p, *rings[outer]))
                throw Error(op, "a closed curve of the frame lies (partly) outside its largest one: "
                                "a frame bounds one region, holes inside it");
        holes.push_back(*rings[i]);
    }
    return Region(*rings[outer], std::move(holes), op);
}

Curves EvaluateInDomain(const Arrangement& a, const Curves& frame) {
    const Region r = FrameRegion(frame, "ExportSVGinDomain");
    const Curves texture = a(r);
    Curves out = apply_mask(texture, r, CROP);
    // Labelled points are cut too: those outside the region go.
    out.points.erase(std::remove_if(out.points.begin(), out.points.end(),
                                    [&](const LabeledPoint& p) { return !r.contains(p.point); }),
                     out.points.end());
    out.append(r.boundary());
    return out;
}

Arrangement InDomain(Arrangement a, Curves frame) {
    FrameRegion(frame, "InDomain");  // fail when the operator is applied, not when evaluated
    return Arrangement([a = std::move(a), frame = std::move(frame)](const Region&) {
        return EvaluateInDomain(a, frame);
    });
}

}  // namespace tex
