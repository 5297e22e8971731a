// SPDX-License-Identifier: MIT
#include "posemorph/bake/pose_space_samples.h"

#include <algorithm>
#include <atomic>
#include <thread>

#include <Eigen/Geometry>

#include "posemorph/jobs.h"
#include "posemorph/bake/run_each.h"
#include "posemorph/path.h"

namespace posemorph::bake {
namespace {

double Cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

bool Inside(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& p) {
  if (hull.size() < 3) return false;
  for (std::size_t e = 0; e < hull.size(); ++e)
    if (Cross(hull[e], hull[(e + 1) % hull.size()], p) < 0) return false;
  return true;
}

}  // namespace

std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> s) {
  std::sort(s.begin(), s.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Eigen::Vector2d> hull;
  for (int pass = 0; pass < 2; ++pass) {  // Andrew's monotone chain: lower, then upper
    const std::size_t start = hull.size();
    for (const auto& p : s) {
      while (hull.size() >= start + 2 && Cross(hull[hull.size() - 2], hull.back(), p) <= 0) hull.pop_back();
      hull.push_back(p);
    }
    hull.pop_back();
    std::reverse(s.begin(), s.end());
  }
  return hull;
}

std::vector<PoseSpaceSample> SamplePoseSpace(const Rig& rig, const PoseSpaceSampling& sampling) {
  const std::uint32_t N = rig.pose_count();
  std::vector<Eigen::Vector2d> pts;
  for (std::uint32_t i = 0; i < N; ++i) pts.emplace_back(rig.pose_points()[2 * i], rig.pose_points()[2 * i + 1]);
  std::vector<PoseSpaceSample> out;
  for (const auto& p : pts) out.push_back({p, -1, true});
  const std::vector<Eigen::Vector2d> hull = ConvexHull(pts);
  for (std::size_t e = 0; e < hull.size(); ++e) {
    const Eigen::Vector2d &a = hull[e], &b = hull[(e + 1) % hull.size()];
    for (int k = 1; k < sampling.per_edge; ++k)
      out.push_back({a + (b - a) * (double(k) / sampling.per_edge), -1, true});
  }
  Eigen::AlignedBox2d box;
  for (const auto& p : pts) box.extend(p);
  const int G = sampling.grid;
  for (int iy = 0; iy <= G && hull.size() >= 3; ++iy)
    for (int ix = 0; ix <= G; ++ix) {
      const Eigen::Vector2d p = box.min() + Eigen::Vector2d(box.sizes().x() * ix / G, box.sizes().y() * iy / G);
      if (Inside(hull, p)) out.push_back({p, -1, true});
    }
  for (std::uint32_t i = 0; i < N && sampling.per_pair > 0; ++i)
    for (std::uint32_t j = i + 1; j < N; ++j)
      for (int k = 1; k < sampling.per_pair; ++k)
        out.push_back({pts[i] + (pts[j] - pts[i]) * (double(k) / sampling.per_pair), -1, true});
  for (std::uint32_t k = 0; k < rig.path_count(); ++k) {
    const PathView path = rig.path(k);
    const double t0 = path.start_time(), t1 = path.end_time();
    for (int j = 0; j <= sampling.per_path; ++j) {
      double x, y;
      if (SamplePath(path, t0 + (t1 - t0) * j / sampling.per_path, &x, &y)) {
        const Eigen::Vector2d p(x, y);
        out.push_back({p, std::int32_t(k), Inside(hull, p)});
      }
    }
  }
  return out;
}

bool EvaluateFrame(const Rig& rig, const Eigen::Vector2d& at, std::vector<double>& x) {
  std::vector<double> limited;
  return EvaluateFrame(rig, at, x, limited);
}

bool EvaluateFrame(const Rig& rig, const Eigen::Vector2d& at, std::vector<double>& x, std::vector<double>& limited) {
  const std::size_t N = rig.pose_count();
  std::vector<double> raw(N), work(rig.morph_workspace_size());
  limited.assign(N, 0.0);
  x.assign(2 * std::size_t(rig.vertex_count()), 0);
  WeightsJob wj;
  wj.rig = &rig;
  wj.x = at.x();
  wj.y = at.y();
  wj.raw = MakeSpan(raw);
  wj.limited = MakeSpan(limited);
  MorphJob mj;
  mj.rig = &rig;
  mj.weights = MakeSpan(raw);
  mj.limited_weights = MakeSpan(limited);
  mj.workspace = MakeSpan(work);
  mj.positions = MakeSpan(x);
  return wj.Run() && mj.Run();
}

bool EvaluateFrames(const Rig& rig, const std::vector<Eigen::Vector2d>& at, std::size_t first, std::size_t count,
                    FrameBuffers& buffers) {
  const std::size_t N = rig.pose_count();
  buffers.raw.resize(count * N);
  buffers.limited.resize(count * N);
  buffers.workspace.resize(rig.batch_workspace_size());
  buffers.positions.resize(count * 2 * std::size_t(rig.vertex_count()));  // the job writes every value
  for (std::size_t k = 0; k < count; ++k) {
    WeightsJob wj;
    wj.rig = &rig;
    wj.x = at[first + k].x();
    wj.y = at[first + k].y();
    wj.raw = Span<double>{buffers.raw.data() + k * N, N};
    wj.limited = Span<double>{buffers.limited.data() + k * N, N};
    if (!wj.Run()) return false;
  }
  MorphBatchJob mj;
  mj.rig = &rig;
  mj.count = count;
  mj.weights = MakeSpan(buffers.raw);
  mj.limited_weights = MakeSpan(buffers.limited);
  mj.workspace = MakeSpan(buffers.workspace);
  mj.positions = MakeSpan(buffers.positions);
  return mj.Run();
}

std::size_t FrameRunCount(std::size_t n, unsigned threads) {
  const std::size_t groups = (n + kFrameBatch - 1) / kFrameBatch;
  const std::size_t most = threads > 0 ? threads : std::thread::hardware_concurrency();
  return std::max<std::size_t>(1, std::min<std::size_t>({groups, most, 8}));
}

bool EvaluateFramesOnEachCore(
    const Rig& rig, const std::vector<Eigen::Vector2d>& at, std::vector<FrameBuffers>& parts,
    const std::function<bool(std::size_t run, std::size_t first, std::size_t count, const double* positions)>& visit,
    unsigned threads) {
  const std::size_t groups = (at.size() + kFrameBatch - 1) / kFrameBatch;
  const std::size_t runs = FrameRunCount(at.size(), threads);
  parts.resize(runs);
  std::atomic<bool> stop{false}, failed{false};
  RunEach(runs, unsigned(runs), [&](std::size_t run) {
    // Run r takes groups [r * groups / runs, (r + 1) * groups / runs).
    for (std::size_t g = run * groups / runs; g < (run + 1) * groups / runs && !stop; ++g) {
      const std::size_t first = g * kFrameBatch, count = std::min(kFrameBatch, at.size() - first);
      if (!EvaluateFrames(rig, at, first, count, parts[run])) {
        failed = stop = true;
      } else if (!visit(run, first, count, parts[run].positions.data())) {
        stop = true;
      }
    }
  });
  return !failed;
}

}  // namespace posemorph::bake
