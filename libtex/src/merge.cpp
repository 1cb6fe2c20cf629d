// Merging operators and the mask they share with the cropping partitions.
//
// Masking induces one planar map of the subject curves together with the mask's face
// boundaries. The mask boundaries carry a reserved marker label on the side of the mask's
// bounded faces, so each face of the joint map knows whether it lies inside the mask as soon
// as one mask edge bounds it; the other faces (bounded only by subject curves) inherit the
// status of their neighbours, since crossing a subject curve does not enter or leave the
// mask. No point location is needed.
#include "libtex/merge.hpp"

#include <deque>

#include "libtex/error.hpp"
#include "libtex/parallel.hpp"

namespace tex {
namespace {

LabelId inside_marker() {
    static const LabelId id = intern_label("\x01libtex-inside");
    return id;
}

enum class Status : signed char { Unknown = -1, Out = 0, In = 1 };

// Faces of the joint map inside the mask. Curves with index >= n_subject are mask curves.
std::vector<Status> classify_faces(const PlanarMap& j, std::size_t n_subject) {
    const LabelId in = inside_marker();
    std::vector<Status> status(j.faces().size(), Status::Unknown);
    std::deque<int> queue;
    for (std::size_t f = 0; f < j.faces().size(); ++f) {
        const FaceRec& fr = j.faces()[f];
        bool has_mask = false, inside = false;
        for (const auto& cyc : fr.cycles)
            for (const Side& s : cyc) {
                const EdgeRec& e = j.edges()[s.edge];
                bool mask_edge = false;
                for (const auto& src : e.sources) mask_edge |= src.curve >= n_subject;
                if (!mask_edge) continue;
                has_mask = true;
                if ((s.left ? e.left_labels : e.right_labels).has(in)) inside = true;
            }
        if (has_mask) status[f] = inside ? Status::In : Status::Out;
        else if (fr.unbounded) status[f] = Status::Out;
        if (status[f] != Status::Unknown) queue.push_back(int(f));
    }
    // Flood across subject-only edges.
    while (!queue.empty()) {
        const int f = queue.front();
        queue.pop_front();
        for (const auto& cyc : j.faces()[f].cycles)
            for (const Side& s : cyc) {
                const EdgeRec& e = j.edges()[s.edge];
                const int g = s.left ? e.right : e.left;
                if (status[g] == Status::Unknown) {
                    status[g] = status[f];
                    queue.push_back(g);
                }
            }
    }
    return status;
}

Curves mask_core(Curves subject, const Curves& mask, MaskSide side, Border b) {
    const LabelId in = inside_marker();
    const bool keep_whole = (b == Border::KEEP_INSIDE || b == Border::KEEP_OUTSIDE);
    Curves pieces_src = keep_whole ? PlanarMap::induce(subject)->edge_curves() : subject;
    const std::size_t n_subject = pieces_src.curves.size();

    Curves joint = pieces_src;
    joint.points.clear();
    joint.curves.insert(joint.curves.end(), mask.curves.begin(), mask.curves.end());
    MapPtr jm = PlanarMap::induce(joint);
    const std::vector<Status> status = classify_faces(*jm, n_subject);

    const Status wanted = side == MaskSide::Inside ? Status::In : Status::Out;
    auto strip = [&](Curve c) {
        c.left.remove(in);
        c.right.remove(in);
        c.labels.remove(in);
        return c;
    };

    Curves out;
    out.points = subject.points;
    if (keep_whole) {
        // Whole edges of the subject's planar map, kept by the status of their pieces.
        std::vector<int> any(n_subject, 0), all(n_subject, 1), seen(n_subject, 0);
        for (const EdgeRec& e : jm->edges()) {
            bool on_mask = false;
            for (const auto& s : e.sources) on_mask |= s.curve >= n_subject;
            const bool ok = on_mask ? (status[e.left] == wanted || status[e.right] == wanted)
                                    : status[e.left] == wanted;
            for (const auto& s : e.sources) {
                if (s.curve >= n_subject) continue;
                seen[s.curve] = 1;
                any[s.curve] |= ok;
                all[s.curve] &= ok;
            }
        }
        for (std::size_t i = 0; i < n_subject; ++i) {
            const bool keep = b == Border::KEEP_INSIDE ? (seen[i] && all[i]) : any[i];
            if (keep) out.curves.push_back(pieces_src.curves[i]);
        }
        return out;
    }

    for (std::size_t ei = 0; ei < jm->edges().size(); ++ei) {
        const EdgeRec& e = jm->edges()[ei];
        bool on_mask = false, on_subject = false, mask_bounded = false;
        for (const auto& s : e.sources) {
            if (s.curve >= n_subject) {
                on_mask = true;
                const Curve& mc = joint.curves[s.curve];
                mask_bounded |= mc.left.has(in) || mc.right.has(in);
            } else {
                on_subject = true;
            }
        }
        bool keep = false;
        if (on_subject) {
            keep = on_mask ? (status[e.left] == wanted || status[e.right] == wanted)
                           : status[e.left] == wanted;
        }
        if (!keep && on_mask && b == Border::CROP_ADD_BOUNDARY) keep = mask_bounded;
        if (keep) out.curves.push_back(strip(jm->edge_curve(int(ei))));
    }
    return out;
}

}  // namespace

Curves apply_mask(const Curves& subject, const PlanarMap& mask_map, MaskSide side, Border b) {
    const LabelId in = inside_marker();
    Curves mask;
    mask.curves.reserve(mask_map.edges().size());
    for (const EdgeRec& e : mask_map.edges()) {
        const bool left_in = !mask_map.faces()[e.left].unbounded;
        const bool right_in = !mask_map.faces()[e.right].unbounded;
        if (!left_in && !right_in) continue;  // a dangling edge in the unbounded face
        Curve c;
        c.points = {mask_map.vertices()[e.source].point, mask_map.vertices()[e.target].point};
        if (left_in) c.left.add(in);
        if (right_in) c.right.add(in);
        mask.curves.push_back(std::move(c));
    }
    return mask_core(subject, mask, side, b);
}

Curves apply_mask(const Curves& subject, const Region& region, Border b) {
    Curves mask = region.boundary();
    for (auto& c : mask.curves) c.left.add(inside_marker());
    return mask_core(subject, mask, MaskSide::Inside, b);
}

Arrangement Union(Arrangement a1, Arrangement a2) {
    return Arrangement([a1 = std::move(a1), a2 = std::move(a2)](const Region& r) {
        Curves parts[2];
        parallel_for(2, [&](std::size_t i) { parts[i] = i == 0 ? a1(r) : a2(r); });
        parts[0].append(std::move(parts[1]));
        return std::move(parts[0]);
    });
}

static Arrangement masked(Arrangement a1, Arrangement a2, Border b, MaskSide side) {
    return Arrangement([a1 = std::move(a1), a2 = std::move(a2), b, side](const Region& r) {
        Curves subject;
        MapPtr mask;
        parallel_for(2, [&](std::size_t i) {
            if (i == 0) subject = a1(r);
            else mask = a2.induce(r);
        });
        return apply_mask(subject, *mask, side, b);
    });
}

Arrangement Inside(Arrangement a1, Arrangement a2, Border b) {
    return masked(std::move(a1), std::move(a2), b, MaskSide::Inside);
}

Arrangement Outside(Arrangement a1, Arrangement a2, Border b) {
    return masked(std::move(a1), std::move(a2), b, MaskSide::Outside);
}

}  // namespace tex
