// Microprocessor: traces, chips and solder joints (see gallery_micro.hpp).
#include "gallery_micro.hpp"
#include "gallery.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gallery::micro {
using namespace tex;

namespace {

Curves load(const std::string& dir, const std::string& name) { return gallery::element(dir + "/" + name); }

}  // namespace

Point snap(const Point& p) { return {kStep * std::floor(p.x / kStep), kStep * std::floor(p.y / kStep)}; }

// ---- Level 1 ----

Arrangement trace_layer(const std::string& dir, int i) {
    const Curves trace = load(dir, "mp_net" + std::to_string(i) + ".svg");
    const Point start = PointLabeled(trace, "start");
    const double density = kTraceDensities[kTraceDensityOf[i - 1]] / kTraceThinning;
    return MapToFaces([trace, start](const Face& f) { return MatchPoint(trace, start, snap(Centroid(f))); },
                      RandomPartition(IrregularProperties(density), KEEP_OUTSIDE));
}

Arrangement traces(const std::string& dir) {
    Arrangement all = trace_layer(dir, 1);
    for (int i = 2; i <= 12; ++i) all = Merge(all, trace_layer(dir, i));
    return all;
}

// ---- Level 2 ----

Curves chip_on(const std::vector<Curves>& kinds, const Face& f) {
    const auto n = kinds.size();
    const auto k = std::min(n - 1, std::size_t(std::floor(Random(f, 0.0, double(n), 0))));
    const double s = 1 + std::floor(Random(f, 0.0, 4.0, 1));
    const Curves chip = Scale(kinds[k], s);
    return MatchPoint(chip, BBoxCenter(chip), snap(Centroid(f)));
}

Arrangement chips(const std::string& dir) {
    std::vector<Curves> kinds;
    for (int k = 1; k <= kChipKinds; ++k) kinds.push_back(load(dir, "mp_ship" + std::to_string(k) + ".svg"));
    return MapToFaces([kinds](const Face& f) { return chip_on(kinds, f); },
                      UniformPartition(IrregularProperties(kChipDensity), KEEP_OUTSIDE));
}

// ---- The board and its pads ----

Arrangement board(const std::string& dir) {
    // In this order: the traces' partitions take the first streams, the chips' the next.
    Arrangement level1 = traces(dir);
    Arrangement level2 = chips(dir);
    return Outside(std::move(level1), std::move(level2), CROP_ADD_BOUNDARY);
}

bool is_connector(const Vertex& v) { return IncidentEdges(v).size() == 3 && HasLabel(IncidentFaces(v), "ship"); }

bool is_joint(const Vertex& v) { return IncidentEdges(v).size() == 1; }

namespace {

Arrangement pads_on(const std::string& dir, Arrangement on) {
    const Curves connector = load(dir, "mp_connector.svg");
    const Curves joint = load(dir, "mp_joint.svg");
    return MapToVertices(
        [connector, joint](const Vertex& v) {
            if (is_connector(v)) return MatchPoint(connector, BBoxCenter(connector), Location(v));
            if (is_joint(v)) return MatchPoint(joint, BBoxCenter(joint), Location(v));
            return Nothing();
        },
        std::move(on));
}

}  // namespace

Arrangement pads(const std::string& dir) { return pads_on(dir, board(dir)); }

Arrangement microprocessor(const std::string& dir) {
    const Arrangement lvl = board(dir);
    return Outside(lvl, pads_on(dir, lvl), CROP_ADD_BOUNDARY);
}

}  // namespace gallery::micro
