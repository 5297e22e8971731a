// SPDX-License-Identifier: MIT
// The mapping's variants (map_again.h): the fold retries, further
// refinement below the quality floor and the mapping by deformation, each
// a BakeOnce of a changed description, kept by what it measures.
#include "map_again.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <iterator>
#include <thread>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/mapping/compatible_refinement.h"
#include "posemorph/bake/mesh_quality.h"
#include "posemorph/bake/run_each.h"

namespace posemorph::bake {
namespace {

// The mapping variants tried, in order, when the in-betweens fold: coarser
// matching, longer edges, both; then the outlines' thin notches filled; and
// last the mapping by deformation (MappingParameters::registration). (The
// outlines matched resisting stretch, tried too before registration, did
// not make the one failing bake at hand fold-free: tux-egypt from `init`'s
// start points alone.)
struct FoldRetry {
  double spacing_scale, edge_scale;
  bool fill_notches, registration;
  const char* name;
};
constexpr FoldRetry kFoldRetries[] = {
    {2, 1, false, false, "matched-sample spacing x2"},
    {1, 1.5, false, false, "longest edge x1.5"},
    {2, 1.5, false, false, "spacing x2, longest edge x1.5"},
    {1, 1, true, false, "the outlines' thin notches filled"},
    {2, 1, true, false, "thin notches filled, spacing x2"},
    {1, 1.5, true, false, "thin notches filled, longest edge x1.5"},
    {2, 1.5, true, false, "thin notches filled, spacing x2, longest edge x1.5"},
    {1, 1, false, true, "the first pose's mesh deformed onto the others (registration)"}};

// Fold retry k's description: `description` with kFoldRetries[k]'s
// settings; nothing when it would map the same as the description.
std::optional<RigDescription> FoldRetryVariant(const RigDescription& description, int k) {
  RigDescription variant = description;
  variant.mapping.spacing_scale = kFoldRetries[k].spacing_scale;
  variant.mapping.edge_scale = kFoldRetries[k].edge_scale;
  if (kFoldRetries[k].fill_notches) {
    if (!TracesPngOutline(description)) return std::nullopt;  // nothing is traced from a PNG: the same mapping
    variant.mapping.fill_notches = true;
  }
  if (kFoldRetries[k].registration) {
    if (description.mapping.registration) return std::nullopt;  // mapped so already
    variant.mapping.registration = true;
  }
  return variant;
}

// The quality floor: a mapped mesh whose smallest angle over all poses is
// below half of mapping.min_angle (10 degrees by default) is mapped again
// in the ways of kFurtherRefinements (refinement stops early once every
// angle reaches min_angle) until one reaches the floor. The best of them is
// kept when its in-betweens do not fold either and its smallest angle is
// larger; otherwise the first one stays. (Splitting more
// where one pose squeezes the outline, as an arm against the body does, can
// fold the in-betweens; trying the fold retries' variants too cost up to
// eight more mappings and gained nothing on the game-art corpus.) A mesh
// below a quarter of the floor (2.5 degrees) is mapped again only when its
// outlines are a sprite's (IsSprite): such an angle comes from a squeeze or
// an outline finer than any split lifts, and on a large outline mapping
// again only doubled the bake, while on a sprite it costs little and can
// lift it (fillets-ng's octopus curling its tentacles, 75 x 30 px: 1.34 ->
// 11.5 degrees, then 15.8 with the outlines matched resisting stretch).
constexpr int kFurtherRefinementRounds = 16;
// The ways tried, the best kept: more rounds of splitting; the usual rounds
// with the boundary vertices that make slivers removed (a short boundary
// edge where one pose squeezes the outline leaves a sliver no split lifts:
// Pip drawn at 1024 px, 5.1 -> 11.0 degrees).
struct FurtherRefinement {
  int rounds;
  bool collapse_slivers;
  int smoothing;  // MappingParameters::correspondence_smoothing
  const char* name;
};
// Then the outlines' correspondence averaged over 24, then 12, matched
// samples on each side (mapping/boundary_matching.h): where one pose
// squeezes the outline against another (an arm against the body in one,
// raised in the other), matching by bending alone gave many samples of one
// outline to one of the other (tux-yes: an edge of 0.31 px in 'down', 1.5
// px in 'up'). With 24: tux-yes 6.8 -> 12.4 degrees, its ghosting over the
// pose hull 24.4 -> 12.3; cat-walk 8.8 -> 15.1 degrees, 12.9 -> 8.7. The
// outcome swings with the width (tux-yes, 4 rounds, at 8 / 10 / 14 / 16 /
// 20 / 24: 10.1 / 8.4 / 10.4 / 10.3 / 10.8 / 12.4 degrees, folding at 8 and
// 10, ghosting 32.4 and 32.9 at 14 and 16), so a second width is tried.
// Not the default: on Pip and Sprout (8 samples) it cross-fades worse, 4.37
// -> 4.70 and 3.10 -> 3.95 over the pose hull.
constexpr int kFurtherSmoothing[] = {24, 12};
// A finer mesh whose ghosting over the pose hull (ghosting.h) is more than
// 5% worse than the first's is not kept: on the game-art corpus removing
// slivers lifted cat-springboots 12.8 -> 16.3 degrees and cat-walk 8.8 ->
// 9.9 but cross-faded 15% and 7% worse.
constexpr double kFurtherGhostingSlack = 1.05;
// A variant with more vertices than kVerticesPerOutlinePoint per point of
// a pose's traced outline (their mean over the poses; with parts, the
// parts' together), or than the first mesh where that has more, is not
// kept either: the mesh stays in proportion to the sprite. Without the
// bound, 16 rounds of splitting gave fillets-ng's big fish turning to face
// the player (60 x 30 px, outlines of 222, 200 and 176 points) 538
// vertices, 2.4 per point of its first outline.
using mapping::kVerticesPerOutlinePoint;
// A sprite's outlines: at most this many points in all poses together.
// Below a quarter of the floor (and, for the other ways, below the floor)
// only a sprite is mapped again: there the variants cost little, while a
// large outline finer than any split lifts only doubled the bake (a
// 1024-pixel star at 0.77 degrees: 3.3 s more, nothing kept; a spiral of
// 20,000 outline points at 8.9 degrees: 4.5 -> 10 s of CPU with
// registration, past the hostile corpus's bound).
constexpr std::size_t kSpriteOutlinePoints = 4096;
// The traced outlines' points, all poses together.
std::size_t OutlinePoints(const MappingReport& m) {
  std::size_t points = 0;
  for (std::size_t n : m.outline_vertices) points += n;
  return points;
}
bool IsSprite(const MappingReport& m) { return OutlinePoints(m) <= kSpriteOutlinePoints; }
bool WithinVertexBound(const MappingReport& variant, const MappingReport& first, std::size_t poses) {
  const double bound =
      kVerticesPerOutlinePoint * double(OutlinePoints(first)) / double(std::max<std::size_t>(poses, 1));
  return double(variant.vertices) <= std::max(bound, double(first.vertices));
}
// In this order; once one lifts the mesh over the floor, the rest are not tried.
constexpr FurtherRefinement kFurtherRefinements[] = {
    {4, true, 0, "slivers at the boundary removed"},
    {kFurtherRefinementRounds, false, 0, "16 rounds of splitting"},
    {4, false, kFurtherSmoothing[0], "the outlines' correspondence smoothed over 24 samples"},
    {kFurtherRefinementRounds, false, kFurtherSmoothing[0],
     "the outlines' correspondence smoothed over 24 samples, 16 rounds"},
    {4, false, kFurtherSmoothing[1], "the outlines' correspondence smoothed over 12 samples"},
    {kFurtherRefinementRounds, false, kFurtherSmoothing[1],
     "the outlines' correspondence smoothed over 12 samples, 16 rounds"}};

// BakeOnce of each of `variants`, a few at a time on as many threads (the
// machine's cores, at most kVariantsAtOnce: each holds a whole bake in
// memory), handed in order to `take` (nothing for a variant that cannot be
// baked: BakeError) until it returns true; the rest of those baked at the
// same time are dropped. The outcome is the one-at-a-time loop's: the same
// bakes (each the same bits on any thread) handed in the same order, any
// other exception thrown where that loop would have met it. A bake that
// folds in every fold retry tries eight of them: one at a time, tux-egypt
// without landmarks failed in 14.7-15.6 s on two cores.
// A variant for which `skip` (when given) returns true is not baked; it is
// asked as its batch is formed, after every earlier batch went to `take`.
constexpr unsigned kVariantsAtOnce = 2;
void BakeEachInOrder(const std::vector<RigDescription>& variants,
                     const std::function<bool(std::size_t, std::optional<Attempt>&)>& take,
                     const std::function<bool(std::size_t)>& skip = nullptr) {
  const std::size_t at_once = std::min(std::max(1u, std::thread::hardware_concurrency()), kVariantsAtOnce);
  for (std::size_t next = 0; next < variants.size();) {
    std::vector<std::size_t> batch;
    for (; batch.size() < at_once && next < variants.size(); ++next)
      if (!skip || !skip(next)) batch.push_back(next);
    const std::size_t n = batch.size();
    if (n == 0) break;  // the rest skipped
    std::vector<std::optional<Attempt>> baked(n);
    std::vector<std::exception_ptr> failed(n);
    RunEach(n, unsigned(n), [&](std::size_t k) {
      try {
        baked[k] = BakeOnce(variants[batch[k]]);
      } catch (const BakeError&) {
        // passed over, as a variant that cannot be baked
      } catch (...) {
        failed[k] = std::current_exception();
      }
    });
    for (std::size_t k = 0; k < n; ++k) {
      if (failed[k]) std::rethrow_exception(failed[k]);
      if (take(batch[k], baked[k])) return;
    }
  }
}

}  // namespace

// The first variant's bake whose in-betweens do not fold in the hull (or
// the registration variant's, below), with *tried set to its place in
// kFoldRetries + 1 and *chosen to its description; nothing when none does
// (a variant that cannot be baked at all is passed over).
std::optional<Attempt> MapAgainWithoutFolds(const RigDescription& description, const MappingReport& first,
                                            std::chrono::steady_clock::time_point started, int* tried,
                                            std::string* name, RigDescription* chosen, RetriesLeft* left) {
  const bool aligned = first.aligned;
  std::vector<RigDescription> variants;
  std::vector<int> place;  // each variant's k in kFoldRetries
  for (int k = 0; k < int(std::size(kFoldRetries)); ++k) {
    std::optional<RigDescription> variant = FoldRetryVariant(description, k);
    if (variant) variants.push_back(std::move(*variant)), place.push_back(k);
  }
  // Where the drawings align the interiors, that is most of a large
  // mesh's mapping (tux-egypt drawn 3x, 210 x 225 px, from init's start
  // points: 5.2 of its 6.2 s), and a bake that folds in every retry paid it
  // eight times (38 s). Each variant is first baked without it, and one
  // whose in-betweens do not fold is baked again with it and kept when that
  // does not fold either (else the next is tried).
  std::vector<RigDescription> quick = variants;
  if (aligned)
    for (RigDescription& v : quick) v.mapping.align_interiors = false;
  // A mapping that cannot be made as traced is made with the outlines'
  // thin notches filled (MapDrawings): a retry that fills them with the
  // spacing and edge scales of a mapping that did so already (the first, or
  // an earlier retry) is that mapping again, and is not baked again
  // (tux-egypt from init's start points: 3 of its 8 retries).
  std::vector<std::pair<double, double>> filled;  // spacing and edge scales mapped with notches filled
  auto note_filled = [&](const MappingReport& r, const MappingParameters& m) {
    if (r.mapped && r.filled_notch_corners > 0) filled.emplace_back(m.spacing_scale, m.edge_scale);
  };
  note_filled(first, description.mapping);
  auto mapped_already = [&](std::size_t j) {
    const MappingParameters& m = variants[j].mapping;
    return m.fill_notches &&
           std::find(filled.begin(), filled.end(), std::make_pair(m.spacing_scale, m.edge_scale)) != filled.end();
  };
  // Past mapping.retry_seconds since the bake began, the retries not begun
  // are left (a bake that will fail says so in bounded time: tux-egypt
  // drawn 3x, 210 x 225 px, from init's start points, ran its first
  // mapping for 7 s and its retries for 8 s more on two cores).
  const double limit = description.mapping.retry_seconds;
  *left = RetriesLeft{0, variants.size(), limit};
  auto skip = [&](std::size_t j) {
    if (mapped_already(j)) return true;
    if (limit > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() >= limit) {
      ++left->untried;
      return true;
    }
    return false;
  };
  std::optional<Attempt> found;
  std::size_t found_at = 0;
  BakeEachInOrder(
      quick,
      [&](std::size_t j, std::optional<Attempt>& again) {
        if (again) note_filled(again->drawings.report, variants[j].mapping);
        if (!again || again->inbetweens.FoldsInHull() > 0) return false;
        if (aligned) {
          try {
            again = BakeOnce(variants[j]);
          } catch (const BakeError&) {
            return false;  // passed over, as a variant that cannot be baked
          }
          if (again->inbetweens.FoldsInHull() > 0) return false;
        }
        found = std::move(again), found_at = j;
        return true;
      },
      skip);
  // A fold-free variant whose mesh is below the quality floor: the last
  // retry (registration) too, kept when it does not fold and reaches the
  // floor. fillets-ng's big fish turning to face the player and away
  // (60 x 30 px, its poses left, front and right on a line): folded once,
  // fold-free with thin notches filled and longer edges at 8.4 degrees,
  // which refining could not lift; registered, 11.9 degrees.
  const std::size_t last = variants.size() - 1;
  if (found && found_at < last && kFoldRetries[place[last]].registration && found->drawings.report.mapped &&
      found->drawings.report.min_angle_degrees < QualityFloor(description.mapping)) {
    BakeEachInOrder({variants[last]}, [&](std::size_t, std::optional<Attempt>& again) {
      if (again && again->inbetweens.FoldsInHull() == 0 &&
          again->drawings.report.min_angle_degrees >= QualityFloor(description.mapping))
        found = std::move(again), found_at = last;
      return true;
    });
  }
  if (found) {
    *tried = place[found_at] + 1;
    *name = kFoldRetries[place[found_at]].name;
    *chosen = variants[found_at];
  }
  return found;
}

double QualityFloor(const MappingParameters& m) { return m.min_angle / 2; }

std::optional<Attempt> RefineFurther(const RigDescription& chosen, Attempt& a,
                                     const std::function<const GhostingDrawings&()>& drawings) {
  const MappingReport& m = a.drawings.report;
  const double floor = QualityFloor(chosen.mapping);
  if (!m.mapped || m.min_angle_degrees >= floor || (m.min_angle_degrees < floor / 4 && !IsSprite(m)) ||
      chosen.mapping.refinement_rounds >= kFurtherRefinementRounds || chosen.mapping.collapse_slivers ||
      chosen.mapping.correspondence_smoothing > 0)
    return std::nullopt;
  std::optional<Attempt> best;
  const char* how = "";
  // The ghosting of the first mesh, where it can be measured: a finer mesh
  // that cross-fades worse is not kept.
  const GhostingDrawings& g = drawings();
  const Ghosting& before = GhostingOf(a, g, chosen.file);
  // The smoothed correspondence only where a pose squeezes the worst
  // triangle (not, say, on a spiral finer than any split lifts: 20,000
  // outline points, a second per mapping).
  const bool squeezed = Squeezed(FindSmallestAngle(a.written.rig));
  std::vector<RigDescription> variants;
  std::vector<const char*> names;
  for (const auto& [rounds, collapse, smoothing, name] : kFurtherRefinements) {
    if (smoothing > 0 && !squeezed) continue;
    RigDescription finer = chosen;
    finer.mapping.refinement_rounds = rounds;
    finer.mapping.collapse_slivers = collapse;
    finer.mapping.correspondence_smoothing = smoothing;
    variants.push_back(std::move(finer));
    names.push_back(name);
  }
  BakeEachInOrder(variants, [&](std::size_t j, std::optional<Attempt>& b) {
    if (!b) return false;
    const double angle = b->drawings.report.min_angle_degrees;
    if (b->inbetweens.FoldsInHull() > 0 ||
        angle <= (best ? best->drawings.report.min_angle_degrees : m.min_angle_degrees) ||
        !WithinVertexBound(b->drawings.report, m, chosen.poses.size()))
      return false;
    if (!before.hull.empty() && GhostingOf(*b, g, chosen.file).hull_mean > before.hull_mean * kFurtherGhostingSlack)
      return false;
    best = std::move(b);
    how = names[j];
    return angle >= floor;  // over the floor: the rest are not tried
  });
  if (best) {
    best->drawings.report.refined_further_from = m.min_angle_degrees;
    best->drawings.report.refined_further_by = how;
  }
  return best;
}

// The other ways to make the meshes, where the mesh is below
// mapping.min_angle (below the quality floor only on a sprite's outlines,
// below): the drawings mapped again by deforming pose
// 0's mesh onto the others (mapping by deformation,
// mapping/mesh_registration.h), and with the outlines matched resisting
// stretch (kStiffStretchCost per sample advanced on one outline alone, 4x
// the default), with the usual rounds of splitting and with 16 (cat-poncho
// 15.8 -> 20.0 degrees, gnujump-hero 14.3 -> 17.8). Each is kept when its in-betweens do not fold, its
// smallest angle reaches kAnotherWayGain times the first's (or min_angle)
// and it cross-fades at most 5% worse (kFurtherGhostingSlack); of them,
// the larger smallest angle up to min_angle, the first on a tie.
// Registration alone, on the game-art corpus, lifted tux-relax 12.1 ->
// 18.6 degrees and gnujump-hero 12.9 -> 19.0 (but ghosting 5.77 -> 7.46),
// folded the in-betweens of tux-egypt and cat-walk, and cross-faded Sprout
// 40% worse (3.10 -> 4.36) at 20 degrees: not the only way.
// A stiffer matching makes a limb that turns keep its length along the
// outline, so the matching turns it whole rather than sliding its outline
// round a corner (a raised arm's tip matched to its tip, not its side:
// mapping_test.cpp). Made the default, on the corpus it lifted tux-yes
// 12.4 -> 20.0, penguin-walk 14.8 -> 20.0, penguin-shadow 10.9 -> 20.0 and
// cat-poncho 10.3 -> 20.9 degrees, but lowered cat-walk 15.1 -> 10.3 and
// cat-springboots 12.8 -> 8.2 and cross-faded tux-egypt and tux-kiss 15%
// worse: not the default either.
// Below the floor (where refining further did not lift the mesh over it)
// only for a sprite's outlines (IsSprite): refining further has mapped
// such a mesh several times already, and on a large outline the other ways
// cost too much. On a sprite they rescue what refining could not:
// tuxtype's tux raising its arms (win0, win1: 85 x 120 px, 1,042 outline
// points) 9.07 -> 12.1 degrees by registration, ghosting over the pose
// hull 10.0 -> 9.58.
// A clear gain only: the registered mesh's angle swings with small changes
// of the drawing (Pip drawn at 256 / 512 / 4096 px: 12.1 / 2.9 / 9.3
// degrees, against 10.4 / 10.6 / 11.0 triangulated compatibly), so a gain
// of a few degrees would pick one way at one size and the other at the next.
constexpr double kAnotherWayGain = 1.25;
constexpr double kStiffStretchCost = 0.2;
std::optional<Attempt> MapAnotherWay(const RigDescription& chosen, Attempt& a,
                                     const std::function<const GhostingDrawings&()>& drawings) {
  const MappingReport& m = a.drawings.report;
  const double goal = chosen.mapping.min_angle;
  if (!m.mapped || m.min_angle_degrees >= goal || (m.min_angle_degrees < QualityFloor(chosen.mapping) && !IsSprite(m)))
    return std::nullopt;
  std::vector<RigDescription> variants;
  if (!chosen.mapping.registration) {
    RigDescription registered = chosen;
    registered.mapping.registration = true;
    variants.push_back(std::move(registered));
  }
  if (chosen.mapping.stretch_cost == 0) {
    RigDescription stiffer = chosen;
    stiffer.mapping.stretch_cost = kStiffStretchCost;
    variants.push_back(stiffer);
    if (stiffer.mapping.refinement_rounds < kFurtherRefinementRounds) {
      stiffer.mapping.refinement_rounds = kFurtherRefinementRounds;
      variants.push_back(std::move(stiffer));
    }
  }
  std::optional<Attempt> best;
  BakeEachInOrder(variants, [&](std::size_t, std::optional<Attempt>& b) {
    if (!b || b->inbetweens.FoldsInHull() > 0 || !WithinVertexBound(b->drawings.report, m, chosen.poses.size()))
      return false;
    const double angle = b->drawings.report.min_angle_degrees;
    if (std::min(angle, goal) < std::min(m.min_angle_degrees * kAnotherWayGain, goal) ||
        (best && std::min(angle, goal) <= std::min(best->drawings.report.min_angle_degrees, goal)))
      return false;
    const GhostingDrawings& g = drawings();
    const Ghosting& before = GhostingOf(a, g, chosen.file);
    if (!before.hull.empty() && GhostingOf(*b, g, chosen.file).hull_mean > before.hull_mean * kFurtherGhostingSlack)
      return false;
    best = std::move(b);
    return false;  // each is judged
  });
  if (best) {
    MappingReport& r = best->drawings.report;
    (r.registered && !chosen.mapping.registration ? r.registered_over : r.matched_stiffer_over) = m.min_angle_degrees;
  }
  return best;
}

}  // namespace posemorph::bake
