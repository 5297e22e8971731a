// SPDX-License-Identifier: MIT
#include "posemorph/bake/inbetween_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "rig_message.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/jobs.h"

namespace posemorph::bake {
namespace {

double SignedArea(const double* x, const std::uint32_t* t) {
  const double ax = x[2 * t[0]], ay = x[2 * t[0] + 1];
  return 0.5 * ((x[2 * t[1]] - ax) * (x[2 * t[2] + 1] - ay) - (x[2 * t[1] + 1] - ay) * (x[2 * t[2]] - ax));
}

std::string Name(StringView s) { return RigString(s); }
std::string Number(double v) { return MessageNumber(v); }

}  // namespace

InbetweenCheck CheckInbetweens(const Rig& rig, const std::string& file, double max_work) {
  const std::uint32_t T = rig.triangle_count(), N = rig.pose_count(), V = rig.vertex_count();
  const std::uint32_t* tris = rig.triangles().data;
  // The smallest area each triangle has in a pose (validation made every one positive).
  std::vector<double> reference(T, std::numeric_limits<double>::infinity());
  for (std::uint32_t i = 0; i < N; ++i)
    for (std::uint32_t t = 0; t < T; ++t)
      reference[t] = std::min(reference[t], SignedArea(rig.pose_positions(i).data, tris + 3 * t));

  // Every part of the sampling shrinks together until frames x vertices fits
  // the budget: at most 64 poses and 1,024 paths keep even the smallest
  // sampling (2 per side, edge, pair and path) to a few thousand frames.
  PoseSpaceSampling sampling;
  std::vector<PoseSpaceSample> samples;
  for (int g = 64;; g = std::max(2, g * 3 / 4)) {
    sampling.grid = sampling.per_edge = sampling.per_pair = g;
    sampling.per_path = g >= 64 ? 200 : std::max(2, 3 * g);
    samples = SamplePoseSpace(rig, sampling);
    if (double(samples.size()) * V <= max_work || g == 2) break;
  }

  const auto start = std::chrono::steady_clock::now();
  InbetweenCheck check;
  check.min_area_ratio = std::numeric_limits<double>::infinity();
  check.grid = sampling.grid;
  check.frames = samples.size();
  // Per run of frames (EvaluateFramesOnEachCore), the smallest ratio in the
  // hull and, per triangle, the most inverted frame inside the hull and
  // outside it; the runs merged in order, each taking the first of equals.
  struct Lowest {
    double ratio = std::numeric_limits<double>::infinity();
    Eigen::Vector2d at = Eigen::Vector2d::Zero();
    std::uint32_t triangle = 0;
    std::vector<double> worst[2];
    std::vector<std::size_t> where[2];
  };
  std::vector<Eigen::Vector2d> points;
  for (const PoseSpaceSample& s : samples) points.push_back(s.at);
  std::vector<FrameBuffers> buffers;
  std::vector<Lowest> runs;
  const auto visit = [&](std::size_t run, std::size_t first, std::size_t count, const double* positions) {
    Lowest& low = runs[run];
    for (std::size_t s = first; s < first + count; ++s) {
      const double* x = positions + (s - first) * 2 * std::size_t(V);
      const int side = samples[s].in_hull ? 0 : 1;
      for (std::uint32_t t = 0; t < T; ++t) {
        const double ratio = SignedArea(x, tris + 3 * t) / reference[t];
        if (side == 0 && ratio < low.ratio) low.ratio = ratio, low.at = samples[s].at, low.triangle = t;
        if (ratio < low.worst[side][t]) low.worst[side][t] = ratio, low.where[side][t] = s;
      }
    }
    return true;
  };
  runs.resize(FrameRunCount(points.size()));
  for (Lowest& low : runs)
    for (int side = 0; side < 2; ++side)
      low.worst[side].assign(T, std::numeric_limits<double>::infinity()), low.where[side].assign(T, 0);
  if (!EvaluateFramesOnEachCore(rig, points, buffers, visit))
    throw BakeError(file, "internal error: the baked rig does not evaluate at an in-between");
  // The later runs folded into the first, in order.
  Lowest& all = runs[0];
  for (std::size_t r = 1; r < runs.size(); ++r) {
    const Lowest& low = runs[r];
    if (low.ratio < all.ratio) all.ratio = low.ratio, all.at = low.at, all.triangle = low.triangle;
    for (int side = 0; side < 2; ++side)
      for (std::uint32_t t = 0; t < T; ++t)
        if (low.worst[side][t] < all.worst[side][t])
          all.worst[side][t] = low.worst[side][t], all.where[side][t] = low.where[side][t];
  }
  if (all.ratio < check.min_area_ratio)
    check.min_area_ratio = all.ratio, check.min_at = all.at, check.min_triangle = all.triangle;
  const std::vector<double>(&worst)[2] = all.worst;
  const std::vector<std::size_t>(&where)[2] = all.where;
  for (std::uint32_t t = 0; t < T; ++t) {
    const int side = worst[0][t] > 0 ? 1 : 0;  // a fold inside the hull is the one reported
    if (worst[side][t] > 0) continue;
    const PoseSpaceSample& s = samples[where[side][t]];
    check.folds.push_back({t, worst[side][t], s.at, s.path, s.in_hull});
  }
  check.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::stable_sort(check.folds.begin(), check.folds.end(), [](const InbetweenFold& a, const InbetweenFold& b) {
    return a.in_hull != b.in_hull ? a.in_hull : a.area_ratio < b.area_ratio;
  });
  return check;
}

std::string DescribeFold(const Rig& rig, const InbetweenFold& fold) {
  const std::uint32_t N = rig.pose_count();
  std::vector<double> raw(N), limited(N);
  WeightsJob wj;
  wj.rig = &rig;
  wj.x = fold.at.x();
  wj.y = fold.at.y();
  wj.raw = MakeSpan(raw);
  wj.limited = MakeSpan(limited);
  wj.Run();
  std::vector<std::uint32_t> order(N);
  for (std::uint32_t i = 0; i < N; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return raw[a] > raw[b]; });
  std::ostringstream s;
  s << "triangle " << fold.triangle << " turns over (area " << Number(fold.area_ratio)
    << " of its smallest in a pose) at (" << Number(fold.at.x()) << ", " << Number(fold.at.y()) << ")";
  if (fold.path >= 0) s << " on path '" << Name(rig.path(std::uint32_t(fold.path)).name) << "'";
  if (!fold.in_hull) s << " (outside the pose points' hull)";
  s << " between ";
  std::size_t shown = 0;
  for (std::uint32_t k = 0; k < N && shown < 3; ++k) {
    const std::uint32_t i = order[k];
    if (shown > 0 && raw[i] < 0.05) break;
    s << (shown ? ", " : "") << "'" << Name(rig.pose_name(i)) << "' (" << Number(raw[i]) << ")";
    ++shown;
  }
  // Where a landmark would hold it: the mesh's boundary vertex nearest the
  // triangle in the dominant pose (boundary vertices lie on the outline, to
  // the simplification's tolerance, and correspond in every pose), given in
  // each pose's drawing pixels (y down, from the canvas's corner: the rig's
  // origin sits at the canvas's pivot).
  const std::uint32_t* t = rig.triangles().data + 3 * fold.triangle;
  const std::uint32_t T = rig.triangle_count();
  std::vector<std::uint32_t> uses(rig.vertex_count(), 0);
  {
    // An edge used by one triangle is a boundary edge: count each undirected edge.
    std::vector<std::uint64_t> edges;
    edges.reserve(3 * std::size_t(T));
    const std::uint32_t* all = rig.triangles().data;
    for (std::uint32_t k = 0; k < 3 * T; k += 3)
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t a = all[k + std::uint32_t(e)], b = all[k + std::uint32_t((e + 1) % 3)];
        edges.push_back((std::uint64_t(std::min(a, b)) << 32) | std::max(a, b));
      }
    std::sort(edges.begin(), edges.end());
    for (std::size_t k = 0; k < edges.size();) {
      std::size_t j = k;
      while (j < edges.size() && edges[j] == edges[k]) ++j;
      if (j - k == 1) ++uses[edges[k] >> 32], ++uses[edges[k] & 0xffffffffu];
      k = j;
    }
  }
  const double* dominant = rig.pose_positions(order[0]).data;
  const double cx = (dominant[2 * t[0]] + dominant[2 * t[1]] + dominant[2 * t[2]]) / 3,
               cy = (dominant[2 * t[0] + 1] + dominant[2 * t[1] + 1] + dominant[2 * t[2] + 1]) / 3;
  std::uint32_t nearest = t[0];
  double best = std::numeric_limits<double>::infinity();
  for (std::uint32_t v = 0; v < rig.vertex_count(); ++v) {
    if (uses[v] == 0) continue;
    const double d = std::hypot(dominant[2 * v] - cx, dominant[2 * v + 1] - cy);
    if (d < best) best = d, nearest = v;
  }
  // The part the triangle belongs to, on a layered character.
  const std::uint32_t part = PartOfTriangle(rig, fold.triangle);
  const bool layered = rig.part_count() > 1;
  if (layered) s << "; it is in part '" << Name(rig.part(part).name) << "'";
  s << "; a landmark on the outline there would hold it: ";
  for (std::size_t k = 0; k < shown; ++k) {
    const std::uint32_t i = order[k];
    const double* p = rig.pose_positions(i).data;
    const bool drawn = rig.pose_canvas(i).width > 0;
    double x = 0, y = 0;
    InDrawingPixels(rig, i, p[2 * nearest], p[2 * nearest + 1], &x, &y);
    const StringView image = layered ? rig.part_image(part, i) : rig.pose_image(i);
    s << (k ? ", " : "") << "(" << Number(x) << ", " << Number(y) << ") in "
      << (drawn && image.size ? Name(image) : "'" + Name(rig.pose_name(i)) + "'");
  }
  return s.str();
}

}  // namespace posemorph::bake
