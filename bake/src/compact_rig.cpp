// SPDX-License-Identifier: MIT
// CompactRig: the coarsest position and weight steps whose frames stay
// within the error budget, each trial encoded (compact_encoder.cpp), loaded
// with the runtime (runtime_oracle.h) and measured against the exact rig.
#include "posemorph/bake/compact_rig.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>

#include <Eigen/Dense>

#include "posemorph/bake/error.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/compact_codec.h"
#include "posemorph/jobs.h"
#include "posemorph/path.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "compact_encoder.h"
#include "runtime_oracle.h"

namespace posemorph::bake {
namespace {

namespace fmt = format;

using compact::Encoder;
using compact::RawSections;

// Frames sampled where the rig is used: the pose points, a grid over the
// convex hull of the pose points and its edges, and every path.
std::vector<Eigen::Vector2d> SamplePoints(const Rig& rig) {
  std::vector<Eigen::Vector2d> out;
  for (const PoseSpaceSample& s : SamplePoseSpace(rig, PoseSpaceSampling{})) out.push_back(s.at);
  return out;
}

// Whether the grid sums to 1 at every node (so the last pose need not be stored).
bool GridSumsToOne(const Rig& exact) {
  const std::uint64_t N = exact.pose_count();
  double worst_sum = 0;
  for (const Span<const double>& w : {exact.grid().weights, exact.grid().centre_weights})
    for (std::size_t g = 0; g < w.size / N; ++g) {
      double sum = 0;
      for (std::size_t i = 0; i < N; ++i) sum += w[g * N + i];
      worst_sum = std::max(worst_sum, std::fabs(sum - 1));
    }
  return worst_sum <= 1e-9;
}

// Largest distance a vertex travels between poses (centroids aligned): how
// far a weight error moves it.
double WeightReach(const Rig& exact) {
  const std::uint64_t V = exact.vertex_count(), N = exact.pose_count();
  double reach = 0;
  for (std::uint64_t i = 1; i < N; ++i) {
    const Span<const double> p = exact.pose_positions(std::uint32_t(i)), r = exact.pose_positions(0);
    const double* c = exact.pose_centroids().data;
    for (std::uint64_t v = 0; v < V; ++v)
      reach = std::max(reach, std::hypot((p[2 * v] - c[2 * i]) - (r[2 * v] - c[0]),
                                         (p[2 * v + 1] - c[2 * i + 1]) - (r[2 * v + 1] - c[1])));
  }
  return std::max(reach, 0.05 * exact.bounding_box_diagonal());
}

struct Trial {
  bool ok = false;
  double error = 0, pose_error = 0;
  RigSections sections;
  std::vector<std::int32_t> turns;
};

// Encodes at a position step and a weight step, loads the result with the
// runtime and measures every sample frame against the exact rig's.
struct Trials {
  const Rig& exact;
  Encoder& enc;
  const std::vector<Eigen::Vector2d>& samples;
  const std::vector<std::vector<double>>& reference;
  double accept;  // the error a trial may reach
  CompactReport& rep;

  Trial Attempt(double ps, double ws) {
    const std::uint64_t V = exact.vertex_count(), T = exact.triangle_count(), N = exact.pose_count();
    Trial t;
    ++rep.trials;
    // First without turns, to learn the principal angles the runtime derives.
    enc.turns.clear();
    const RigSections first = enc.Encode(ps, ws, nullptr);
    Rig rig;
    if (first.sections.empty() || !LoadWithRuntime(WriteRig(first), &rig)) return t;
    enc.turns.resize(T * N);
    for (std::uint64_t k = 0; k < T * N; ++k)
      enc.turns[k] = std::int32_t(std::llround((exact.angles()[k] - rig.angles()[k]) / (2 * M_PI)));
    t.sections = enc.Encode(ps, ws, nullptr);
    t.turns = enc.turns;
    if (!LoadWithRuntime(WriteRig(t.sections), &rig)) return t;
    std::vector<double> x;
    for (std::size_t s = 0; s < samples.size(); ++s) {
      if (!EvaluateFrame(rig, samples[s], x)) return t;
      double worst = 0;
      for (std::uint64_t v = 0; v < V; ++v)
        worst = std::max(worst, std::hypot(x[2 * v] - reference[s][2 * v], x[2 * v + 1] - reference[s][2 * v + 1]));
      t.error = std::max(t.error, worst);
      if (s < N) t.pose_error = std::max(t.pose_error, worst);
    }
    t.ok = t.error <= accept;
    return t;
  }
};

}  // namespace

RigSections CompactRig(const RigSections& exact_sections, const CompactSettings& settings, const std::string& file,
                       CompactReport* report) {
  if (!(settings.max_error_px > 0) || !(settings.pixels_per_unit > 0))
    throw BakeError(file, "the compact encoding needs a positive error budget and pixels per unit");
  const Rig exact = LoadWithRuntime(WriteRig(exact_sections), file, "internal error: the exact rig does not load");
  Encoder enc{exact, settings.max_error_px / 2, settings.pixels_per_unit, RawSections(exact_sections), {}, false};
  enc.derive_last_pose = GridSumsToOne(exact);

  const std::vector<Eigen::Vector2d> samples = SamplePoints(exact);
  std::vector<std::vector<double>> reference(samples.size());
  for (std::size_t s = 0; s < samples.size(); ++s)
    if (!EvaluateFrame(exact, samples[s], reference[s]))
      throw BakeError(file, "internal error: the exact rig does not evaluate");

  const double budget = settings.max_error_px / settings.pixels_per_unit;  // rig units
  const double reach = WeightReach(exact);
  // Accepted at 90% of the budget: frames between the samples may come out
  // slightly worse than the worst sample.
  CompactReport rep;
  Trials trials{exact, enc, samples, reference, 0.9 * budget, rep};
  auto attempt = [&](double ps, double ws) { return trials.Attempt(ps, ws); };
  // Positions first, with a fine grid, to within half the budget; then the
  // coarsest grid step that keeps the whole within budget.
  const double fine_weights = 1e-9;
  double ps = budget / 4;
  Trial best;
  for (int k = 0; k < 12; ++k, ps /= 2) {
    best = attempt(ps, fine_weights);
    if (best.ok && best.error <= budget / 2) break;
  }
  for (int k = 0; k < 4 && best.ok; ++k) {  // coarser while well inside
    Trial coarser = attempt(2 * ps, fine_weights);
    if (!coarser.ok || coarser.error > budget / 2) break;
    ps *= 2;
    best = std::move(coarser);
  }
  if (!best.ok) {
    // Nothing within budget (a sliver that folds under any step tried, say):
    // the exact encoding, and the caller says so.
    rep.fell_back = true;
    if (report) *report = rep;
    return exact_sections;
  }
  double ws = budget / (4 * reach);
  Trial t = attempt(ps, ws);
  if (t.ok) {
    for (int k = 0; k < 6; ++k) {
      Trial coarser = attempt(ps, 2 * ws);
      if (!coarser.ok) break;
      ws *= 2;
      t = std::move(coarser);
    }
  } else {
    for (int k = 0; k < 12 && !t.ok; ++k) {
      ws /= 2;
      t = attempt(ps, ws);
    }
  }
  if (!t.ok) t = std::move(best), ws = fine_weights;
  rep.max_error_px = t.error * settings.pixels_per_unit;
  rep.pose_error_px = t.pose_error * settings.pixels_per_unit;
  // The measured encoding again, now with its record of budget and error
  // (QINF, which the loader does not read).
  enc.turns = t.turns;
  const fmt::CompactInfo info{settings.max_error_px, rep.max_error_px, rep.pose_error_px, settings.pixels_per_unit};
  t.sections = enc.Encode(ps, ws, &rep, &info);
  rep.samples = std::uint32_t(samples.size());
  rep.position_step_px = ps * settings.pixels_per_unit;
  rep.weight_step = ws;
  if (report) *report = rep;
  return t.sections;
}

}  // namespace posemorph::bake
