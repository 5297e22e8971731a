// SPDX-License-Identifier: MIT
// The mapping's variants (map_again.cpp): when the first bake's in-betweens
// fold, or its mesh is below the quality floor or below
// mapping.min_angle, the drawings are mapped again in other ways and the
// bake keeps what measures better. Each variant is a BakeOnce of a changed
// description; one that cannot be baked at all is passed over. Internal to
// the bake.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "bake_attempt.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

// The fold retries, in order: the first variant whose in-betweens do not
// fold in the pose hull (or, when its mesh is below the quality floor, the
// last retry, registration, where that does not fold and reaches the
// floor), with *tried set to its place in the retries + 1, *name to its
// name and *chosen to its description; nothing when none does. `first`:
// the first mapping's report. Where it aligned the interiors, each variant
// is baked without that first and, where it does not fold, again with it;
// a retry that would map as the first mapping or an earlier retry did (the
// outlines' thin notches filled at the same scales) is not baked.
// Retries begin only until mapping.retry_seconds have passed since
// `started` (the bake's start): *left says how many were left untried.
struct RetriesLeft {
  std::size_t untried = 0, retries = 0;  // of the fold retries that would map differently
  double seconds = 0;                    // mapping.retry_seconds
};
std::optional<Attempt> MapAgainWithoutFolds(const RigDescription& description, const MappingReport& first,
                                            std::chrono::steady_clock::time_point started, int* tried,
                                            std::string* name, RigDescription* chosen, RetriesLeft* left);

// Half of mapping.min_angle: a mapped mesh below it is refined further and,
// where it stays below, warned of.
double QualityFloor(const MappingParameters& m);

// A mesh between a quarter of the floor and the floor (or below the floor
// where the outlines have at most 4,096 points in all poses), mapped again with
// more splitting, slivers removed or the correspondence smoothed: the best
// that does not fold, has a larger smallest angle and cross-fades at most
// 5% worse than `a`; nothing when none does. `drawings` reads the ghosting
// drawings when first needed; a's and the kept one's ghosting is measured
// once (GhostingOf).
std::optional<Attempt> RefineFurther(const RigDescription& chosen, Attempt& a,
                                     const std::function<const GhostingDrawings&()>& drawings);

// A mesh below mapping.min_angle (below the floor only where the outlines
// have at most 4,096 points in all poses), mapped by deformation
// (MappingParameters::registration) and with the outlines matched
// resisting stretch (MappingParameters::stretch_cost; 4 and 16 rounds of
// splitting): of those whose in-betweens do not fold, whose smallest angle
// gains enough and which cross-fade at most 5% worse than `a`, the one with
// the larger smallest angle up to min_angle (registration on a tie);
// nothing when none is.
std::optional<Attempt> MapAnotherWay(const RigDescription& chosen, Attempt& a,
                                     const std::function<const GhostingDrawings&()>& drawings);

}  // namespace posemorph::bake
