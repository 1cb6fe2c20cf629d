// Timing of carto::snap_borders (issue 11) on the faces of a GeoPackage, read as they are
// (no snapping), or on a synthetic grid of squares whose every side is digitised twice with
// different vertices.
//   bench_snap faces.gpkg [snap]       bench_snap --grid N VERTICES_PER_SIDE [snap]
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "carto/partition.hpp"

using namespace carto;

namespace {

Partition read_faces(const std::string& path) {
    GDALAllRegister();
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
    if (!ds) throw std::runtime_error("cannot open " + path);
    OGRLayer* l = ds->GetLayerByName("faces");
    if (!l) l = ds->GetLayer(0);
    Partition p;
    auto pts = [](const OGRLinearRing* r) {
        std::vector<Point> v;
        for (int i = 0; i < r->getNumPoints(); ++i) v.push_back({r->getX(i), r->getY(i)});
        return v;
    };
    for (auto& feat : *l) {
        const OGRGeometry* g = feat->GetGeometryRef();
        if (!g || wkbFlatten(g->getGeometryType()) != wkbPolygon) continue;
        const OGRPolygon* poly = g->toPolygon();
        std::vector<std::vector<Point>> holes;
        for (int k = 0; k < poly->getNumInteriorRings(); ++k) holes.push_back(pts(poly->getInteriorRing(k)));
        RockFace f;
        f.id = feat->GetFID();
        f.region = tex::Region(pts(poly->getExteriorRing()), holes);
        p.faces.push_back(std::move(f));
    }
    return p;
}

// n x n squares of 100 m; each face digitises its sides with its own `m` vertices, up to
// 0.2 m off the true line (a deterministic wobble).
Partition grid(int n, int m) {
    Partition p;
    auto wobble = [](double a, double b) { return 0.2 * std::sin(a * 12.9898 + b * 78.233); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x0 = 100.0 * i, y0 = 100.0 * j;
            const Point c[4] = {{x0, y0}, {x0 + 100, y0}, {x0 + 100, y0 + 100}, {x0, y0 + 100}};
            std::vector<Point> ring;
            for (int s = 0; s < 4; ++s) {
                const Point a = c[s], b = c[(s + 1) % 4];
                const Point off{-(b - a).y / 100.0, (b - a).x / 100.0};
                ring.push_back(a);
                for (int k = 1; k < m; ++k) {
                    // Own positions along the side: a quarter of a step apart from the neighbour's.
                    const double t = (k + ((i + j) % 2 ? 0.25 : 0.0)) / (m + 0.5);
                    const Point q = a + (b - a) * t;
                    ring.push_back(q + off * wobble(q.x + i, q.y + j));
                }
            }
            RockFace f;
            f.id = i * n + j + 1;
            f.region = tex::Region(ring);
            p.faces.push_back(std::move(f));
        }
    return p;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_snap faces.gpkg [snap] | bench_snap --grid N VERTICES [snap]\n");
        return 2;
    }
    const bool synthetic = std::string(argv[1]) == "--grid";
    const Partition p = synthetic ? grid(std::atoi(argv[2]), std::atoi(argv[3])) : read_faces(argv[1]);
    const int snap_arg = synthetic ? 4 : 2;
    const double snap = argc > snap_arg ? std::atof(argv[snap_arg]) : 0.5;
    std::size_t vertices = 0;
    for (const auto& f : p.faces) {
        vertices += f.region.outer().size();
        for (const auto& h : f.region.holes()) vertices += h.size();
    }
    std::vector<double> ms;
    Partition out;
    for (int run = 0; run < 5; ++run) {
        Partition q = p;
        const auto t0 = std::chrono::steady_clock::now();
        snap_borders(q, snap);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        out = std::move(q);
    }
    std::sort(ms.begin(), ms.end());
    bool same = out.faces.size() == p.faces.size();
    for (std::size_t i = 0; same && i < p.faces.size(); ++i)
        same = out.faces[i].region.outer() == p.faces[i].region.outer() && out.faces[i].region.holes() == p.faces[i].region.holes();
    label_boundaries(out, snap);
    std::size_t segs = 0, with_neighbour = 0;
    for (const auto& f : out.faces)
        for (const auto& s : f.boundary) {
            ++segs;
            with_neighbour += s.neighbor >= 0;
        }
    std::printf("%zu faces, %zu vertices: snap_borders %.1f ms (median of 5, min %.1f)%s; %zu of %zu segments with a neighbour\n",
                p.faces.size(), vertices, ms[2], ms[0], same ? ", rings unchanged" : ", rings changed", with_neighbour, segs);
    for (const auto& n : out.notes) std::printf("note: %s\n", n.c_str());
    return 0;
}
