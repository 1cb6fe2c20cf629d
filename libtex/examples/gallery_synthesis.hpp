// Topology-constrained synthesis (seed 002) in the gallery: patterns from the project's own
// exemplars (synth_vine.svg: a stem with arches and hooks; synth_ladder.svg: rails and
// rungs) along a circle, along an open curve and in a rectangle, with one connected
// component, and with no holes.
#pragma once

#include <string>

#include "libtex/tex.hpp"

namespace gallery::synthesis {

// Seeded variation of the join costs used by the three examples (keyed by GetSeed and the
// curve, so another global seed gives another pattern of the same topology).
inline constexpr double kRandomness = 0.3;
// Topological events closer than this fraction of the exemplar's width form one group: the
// exemplars are about ten features wide, so the seed's 0.2 would leave three pieces.
inline constexpr double kEventGrouping = 0.03;

// Two rings of vine round the centre: the outer one a single component going all the way
// round, the inner one a single component with no hole (so it cannot close).
tex::Arrangement circle(const std::string& dir);
// Two waves of vine: one component (holes free), and one component with no hole.
tex::Arrangement curve(const std::string& dir);
// The ladder synthesized along the width, then along the height: one component.
tex::Arrangement rectangle(const std::string& dir);

}  // namespace gallery::synthesis
