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
#include <tuple>

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

// Frames sampled where the rig is used: the pose points, a grid over the
// convex hull of the pose points (24 cells a side) and its edges (32 parts
// each), and every path (201 frames each). Where frames x vertices would
// pass kMaxMeasureWork (a rig of tens of thousands of vertices with paths),
// grid, edges and paths are sampled more sparsely together, down to 2 parts
// each, so that each trial costs a bounded number of vertex evaluations.
constexpr double kMaxMeasureWork = 1e7;

std::vector<Eigen::Vector2d> SamplePoints(const Rig& rig) {
  PoseSpaceSampling sampling;
  std::vector<PoseSpaceSample> samples = SamplePoseSpace(rig, sampling);
  while (double(samples.size()) * rig.vertex_count() > kMaxMeasureWork &&
         (sampling.grid > 2 || sampling.per_edge > 2 || sampling.per_path > 2)) {
    sampling.grid = std::max(2, sampling.grid * 3 / 4);
    sampling.per_edge = std::max(2, sampling.per_edge * 3 / 4);
    sampling.per_path = std::max(2, sampling.per_path * 3 / 4);
    samples = SamplePoseSpace(rig, sampling);
  }
  std::vector<Eigen::Vector2d> out;
  for (const PoseSpaceSample& s : samples) out.push_back(s.at);
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

// Whole turns of the exact rig's angles over the principal angles of its own
// positions (the polar split of E_i E_0^-1, as the runtime's decoder takes
// it): what a trial's decoded positions nearly always give too.
std::vector<std::int32_t> ExactTurns(const Rig& exact) {
  const std::uint64_t T = exact.triangle_count(), N = exact.pose_count();
  std::vector<std::int32_t> turns(T * N);
  auto edges = [&](std::uint64_t i, const std::uint32_t* tri) {
    const double* p = exact.pose_positions(std::uint32_t(i)).data;
    Eigen::Matrix2d e;
    e << p[2 * tri[0]] - p[2 * tri[2]], p[2 * tri[1]] - p[2 * tri[2]], p[2 * tri[0] + 1] - p[2 * tri[2] + 1],
        p[2 * tri[1] + 1] - p[2 * tri[2] + 1];
    return e;
  };
  for (std::uint64_t t = 0; t < T; ++t) {
    const std::uint32_t* tri = exact.triangles().data + 3 * t;
    const Eigen::Matrix2d rest_inverse = edges(0, tri).inverse();
    for (std::uint64_t i = 0; i < N; ++i) {
      const Eigen::Matrix2d a = edges(i, tri) * rest_inverse;
      const double alpha = std::atan2(a(1, 0) - a(0, 1), a(0, 0) + a(1, 1));
      turns[t * N + i] = std::int32_t(std::llround((exact.angles()[t * N + i] - alpha) / (2 * M_PI)));
    }
  }
  return turns;
}

struct Trial {
  bool ok = false;
  double error = 0, pose_error = 0;
  RigSections sections;
  std::vector<std::int32_t> turns;
};

// Encodes at a position step and a weight step, loads the result with the
// runtime and measures the sample frames against the exact rig's, stopping
// at the first frame beyond what a trial may reach.
struct Trials {
  const Rig& exact;
  Encoder& enc;
  const std::vector<Eigen::Vector2d>& samples;
  const std::vector<std::vector<double>>& reference;
  double accept;  // the error a trial may reach
  CompactReport& rep;
  // Whole turns per position step: the angles the runtime derives depend on
  // the decoded positions only, so trials of weight steps at one position
  // step share them. A new position step starts from the last step's turns.
  std::map<double, std::vector<std::int32_t>> turns_at{};
  std::vector<std::int32_t> guess;     // starts as the exact positions' own turns
  RuntimeArena arena{};                // a large rig's arena faulted in once, not once per load
  std::vector<FrameBuffers> frames{};  // one per run of frames

  // A trial that goes beyond `stop_above` (at most `accept`) is refused.
  Trial Attempt(double ps, double ws, double stop_above) {
    const std::uint64_t V = exact.vertex_count(), T = exact.triangle_count(), N = exact.pose_count();
    Trial t;
    ++rep.trials;
    Rig rig;
    const auto known = turns_at.find(ps);
    enc.turns = known != turns_at.end() ? known->second : guess;
    t.sections = enc.Encode(ps, ws, nullptr);
    if (t.sections.sections.empty() || !arena.Load(WriteRig(t.sections), &rig)) return t;
    if (known == turns_at.end()) {
      // The turns that bring each angle the runtime derived to the exact
      // angle; when a guessed turn was wrong, encoded and loaded again.
      bool corrected = false;
      for (std::uint64_t k = 0; k < T * N; ++k) {
        const auto c = std::llround((exact.angles()[k] - rig.angles()[k]) / (2 * M_PI));
        if (c != 0) enc.turns[k] = std::int32_t(enc.turns[k] + c), corrected = true;
      }
      turns_at.emplace(ps, enc.turns);
      guess = enc.turns;
      if (corrected) {
        t.sections = enc.Encode(ps, ws, nullptr);
        if (t.sections.sections.empty() || !arena.Load(WriteRig(t.sections), &rig)) return t;
      }
    }
    t.turns = enc.turns;
    // Each run of frames (EvaluateFramesOnEachCore) keeps its own worst; a
    // trial is refused at the first group beyond stop_above, whatever the
    // other frames give.
    const std::size_t runs = FrameRunCount(samples.size());
    std::vector<double> error(runs, 0.0), pose_error(runs, 0.0);
    const bool evaluated = EvaluateFramesOnEachCore(
        rig, samples, frames, [&](std::size_t run, std::size_t first, std::size_t count, const double* positions) {
          for (std::size_t k = 0; k < count; ++k) {
            const double* f = positions + k * 2 * V;
            const std::vector<double>& r = reference[first + k];
            double worst = 0;
            for (std::uint64_t v = 0; v < V; ++v)
              worst = std::max(worst, std::hypot(f[2 * v] - r[2 * v], f[2 * v + 1] - r[2 * v + 1]));
            error[run] = std::max(error[run], worst);
            if (first + k < N) pose_error[run] = std::max(pose_error[run], worst);
          }
          return error[run] <= stop_above;
        });
    for (std::size_t run = 0; run < runs; ++run)
      t.error = std::max(t.error, error[run]), t.pose_error = std::max(t.pose_error, pose_error[run]);
    t.ok = evaluated && t.error <= stop_above;
    return t;
  }
};

}  // namespace

RigSections CompactRig(const RigSections& exact_sections, const CompactSettings& settings, const std::string& file,
                       CompactReport* report) {
  if (!(settings.max_error_px > 0) || !(settings.pixels_per_unit > 0))
    throw BakeError(file, "the compact encoding needs a positive error budget and pixels per unit");
  const Rig exact = LoadWithRuntime(WriteRig(exact_sections), file, "internal error: the exact rig does not load");
  Encoder enc{exact, settings.max_error_px / 2, settings.pixels_per_unit, exact_sections, {}, false};
  enc.derive_last_pose = GridSumsToOne(exact);

  const std::vector<Eigen::Vector2d> samples = SamplePoints(exact);
  std::vector<std::vector<double>> reference(samples.size());
  const std::size_t frame_size = 2 * std::size_t(exact.vertex_count());
  std::vector<FrameBuffers> frames;
  const auto keep = [&](std::size_t, std::size_t first, std::size_t count, const double* positions) {
    for (std::size_t k = 0; k < count; ++k)
      reference[first + k].assign(positions + k * frame_size, positions + (k + 1) * frame_size);
    return true;
  };
  if (!EvaluateFramesOnEachCore(exact, samples, frames, keep))
    throw BakeError(file, "internal error: the exact rig does not evaluate");

  const double budget = settings.max_error_px / settings.pixels_per_unit;  // rig units
  const double reach = WeightReach(exact);
  // Accepted at 90% of the budget: frames between the samples may come out
  // slightly worse than the worst sample.
  CompactReport rep;
  Trials trials{exact, enc, samples, reference, 0.9 * budget, rep, {}, ExactTurns(exact), {}, std::move(frames)};
  // Each trial once: the searches below come back to a step they tried.
  std::map<std::tuple<double, double, double>, Trial> tried;
  auto attempt = [&](double ps, double ws, double stop_above) {
    const std::tuple<double, double, double> key{ps, ws, std::min(stop_above, trials.accept)};
    auto it = tried.find(key);
    if (it == tried.end()) it = tried.emplace(key, trials.Attempt(ps, ws, std::get<2>(key))).first;
    return it->second;
  };
  // Positions first, with a fine grid, to within half the budget: from half
  // the budget down, halving, to the first step that is; then coarser while
  // it stays so, up to 16 times that step and at most 4 budgets.
  const double fine_weights = 1e-9;
  double ps = budget / 2;
  Trial best;
  for (int k = 0; k < 13; ++k, ps /= 2) {
    // Beyond half the budget the next, finer step is tried; the last step
    // tried may use the whole budget.
    best = attempt(ps, fine_weights, k < 12 ? budget / 2 : budget);
    if (best.ok && best.error <= budget / 2) break;
  }
  const double coarsest = std::min(16 * ps, 4 * budget);
  while (best.ok && 2 * ps <= coarsest) {  // coarser while well inside
    Trial coarser = attempt(2 * ps, fine_weights, budget / 2);
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
  // Then the weights: the step that moves a vertex by a quarter of the
  // budget (w0) or, first, twice that; coarser while within budget, up to
  // 64 w0, or finer until it is, down to w0 / 4096.
  const double w0 = budget / (4 * reach);
  double ws = 2 * w0;
  Trial t = attempt(ps, ws, budget);
  if (!t.ok) ws = w0, t = attempt(ps, ws, budget);
  if (t.ok) {
    while (ws < 64 * w0) {
      Trial coarser = attempt(ps, 2 * ws, budget);
      if (!coarser.ok) break;
      ws *= 2;
      t = std::move(coarser);
    }
  } else {
    for (int k = 0; k < 12 && !t.ok; ++k) {
      ws /= 2;
      t = attempt(ps, ws, budget);
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
