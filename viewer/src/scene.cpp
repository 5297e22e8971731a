// SPDX-License-Identifier: MIT
#include "scene.h"

#include <algorithm>
#include <cmath>

#include "posemorph/jobs.h"
#include "posemorph/path.h"

namespace posemorph::viewer {

View CharacterBounds(const Rig& rig) {
  View v{1e300, 1e300, -1e300, -1e300};
  for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
    const Span<const double> p = rig.pose_positions(i);
    for (std::size_t k = 0; k < p.size; k += 2) {
      v.x0 = std::min(v.x0, p.data[k]), v.x1 = std::max(v.x1, p.data[k]);
      v.y0 = std::min(v.y0, p.data[k + 1]), v.y1 = std::max(v.y1, p.data[k + 1]);
    }
  }
  const double margin = 0.06 * std::max(v.x1 - v.x0, v.y1 - v.y0);
  return {v.x0 - margin, v.y0 - margin, v.x1 + margin, v.y1 + margin};
}

std::uint32_t SceneCharacters(const Rig& rig, const Scene& scene) {
  if (scene.show_bases) return rig.pose_count();
  if (scene.compare_linear) return 2;
  return std::max<std::uint32_t>(scene.crowd, 1);
}

bool PrepareScene(const Rig& rig, const Scene& scene, RigRenderer& renderer, SceneScratch& scratch, View* view,
                  std::uint32_t* count, std::string* error) {
  const std::uint32_t N = rig.pose_count(), V = rig.vertex_count(), K = SceneCharacters(rig, scene);
  if (K > renderer.max_instances()) {
    *error = "a scene of " + std::to_string(K) + " characters is more than the renderer holds (" +
             std::to_string(renderer.max_instances()) + ")";
    return false;
  }
  int path = -1;
  if (!scene.path.empty()) {
    path = rig.FindPath(scene.path.c_str());
    if (path < 0) {
      *error = "the rig has no path \"" + scene.path + "\"";
      return false;
    }
  }
  const View one = CharacterBounds(rig);
  const double cw = one.x1 - one.x0, ch = one.y1 - one.y0;
  const std::uint32_t columns =
      scene.show_bases || scene.compare_linear ? K : std::uint32_t(std::ceil(std::sqrt(double(K))));
  const std::uint32_t rows = (K + columns - 1) / columns;
  const double sigma = scene.sigma < 0 ? rig.default_sigma() : scene.sigma;

  // Weights for every character, then its drawings and its place on the grid.
  scratch.raw.resize(std::size_t(K) * N);
  scratch.shear.resize(std::size_t(K) * N);
  scratch.texture.resize(N);
  for (std::uint32_t k = 0; k < K; ++k) {
    double x = scene.x, y = scene.y;
    if (scene.show_bases) {
      x = rig.pose_points().data[2 * k], y = rig.pose_points().data[2 * k + 1];
    } else if (path >= 0) {
      const PathView p = rig.path(std::uint32_t(path));
      const double t0 = p.keys.data[0], t1 = p.keys.data[p.keys.size - 3];
      const double t = scene.time + (scene.compare_linear ? 0.0 : (t1 - t0) * double(k) / double(K));
      SamplePath(p, t, &x, &y);
    }
    WeightsJob wj;
    wj.rig = &rig;
    wj.x = x, wj.y = y;
    wj.sigma = sigma;
    wj.shear_limit = scene.shear_limit;
    wj.raw = {scratch.raw.data() + std::size_t(k) * N, N};
    wj.shear = {scratch.shear.data() + std::size_t(k) * N, N};
    wj.texture = {scratch.texture.data(), N};
    if (!wj.Run()) {
      *error = "weights failed";
      return false;
    }
    InstanceData& inst = renderer.instances()[k];
    PickDrawings(scratch.texture.data(), N, &inst);
    inst.scale = 1;
    inst.offset[0] = float(cw * double(k % columns));
    inst.offset[1] = float(-ch * double(k / columns));
  }

  // Positions straight into the renderer's buffer (floats, character after character).
  const bool any_linear = scene.linear || scene.compare_linear;
  if (!any_linear) {
    scratch.workspace.resize(rig.batch_workspace_size());
    MorphBatchJob bj;
    bj.rig = &rig;
    bj.count = K;
    bj.weights = {scratch.raw.data(), scratch.raw.size()};
    bj.shear_weights = {scratch.shear.data(), scratch.shear.size()};
    bj.workspace = {scratch.workspace.data(), scratch.workspace.size()};
    bj.positions_f32 = {renderer.positions(), std::size_t(K) * 2 * V};
    if (!bj.Run()) {
      *error = "morph failed";
      return false;
    }
  } else {
    scratch.workspace.resize(rig.morph_workspace_size());
    scratch.positions.resize(2 * std::size_t(V));
    for (std::uint32_t k = 0; k < K; ++k) {
      const bool linear = scene.compare_linear ? k == 1 : scene.linear;
      MorphJob mj;
      mj.rig = &rig;
      mj.weights = {scratch.raw.data() + std::size_t(k) * N, N};
      mj.shear_weights = {scratch.shear.data() + std::size_t(k) * N, N};
      mj.interpolation = linear ? Interpolation::kLinear : Interpolation::kRigid;
      mj.workspace = {scratch.workspace.data(), scratch.workspace.size()};
      mj.positions = {scratch.positions.data(), scratch.positions.size()};
      mj.positions_f32 = {renderer.positions() + std::size_t(k) * 2 * V, 2 * std::size_t(V)};
      if (!mj.Run()) {
        *error = "morph failed";
        return false;
      }
    }
  }
  *view = {one.x0, one.y0 - ch * (rows - 1), one.x1 + cw * (columns - 1), one.y1};
  *count = K;
  return true;
}

}  // namespace posemorph::viewer
