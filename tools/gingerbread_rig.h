// SPDX-License-Identifier: MIT
// The gingerbread figure: one drawn pose (a mesh of grid cells inside a
// head + body + arms + legs mask) and four poses made from it by dragging
// handles, as in the paper's section 3.2.
#pragma once
#include <cmath>
#include <map>

#include "posemorph/bake/rig_description.h"

namespace posemorph::samples {

inline bool InGingerbread(double x, double y) {
  const bool head = x * x + (y - 3.2) * (y - 3.2) <= 1.0;
  const bool body = std::abs(x) <= 0.9 && y >= 0.2 && y <= 2.5;
  const bool arms = std::abs(x) <= 2.45 && y >= 1.6 && y <= 2.2;
  const bool legs = std::abs(x) >= 0.2 && std::abs(x) <= 0.85 && y >= -1.6 && y <= 0.4;
  return head || body || arms || legs;
}

inline bake::RigDescription GingerbreadRig() {
  const double h = 0.25, x0 = -2.5, y0 = -1.75;
  const int nx = 20, ny = 24;
  std::map<std::pair<int, int>, std::uint32_t> index;
  bake::RigDescription rig;
  rig.name = "gingerbread";
  bake::PoseDescription rest;
  rest.name = "rest";
  auto vertex = [&](int i, int j) {
    auto [it, inserted] = index.try_emplace({i, j}, std::uint32_t(rest.vertices.size()));
    if (inserted) rest.vertices.emplace_back(x0 + i * h, y0 + j * h);
    return it->second;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (!InGingerbread(x0 + (i + 0.5) * h, y0 + (j + 0.5) * h)) continue;
      const std::uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
      // Alternate the diagonal so the mesh has no preferred shear direction.
      if ((i + j) % 2)
        rig.triangles.push_back({a, b, c}), rig.triangles.push_back({a, c, d});
      else
        rig.triangles.push_back({a, b, d}), rig.triangles.push_back({b, c, d});
    }
  rest.point = {0, 0};
  rig.poses.push_back(rest);

  // Handle spots: hands, feet, top of the head, hips.
  const Eigen::Vector2d left_hand(-2.3, 1.9), right_hand(2.3, 1.9), left_foot(-0.5, -1.5), right_foot(0.5, -1.5),
      head(0, 4.05), hips(0, 0.35);
  auto deformed = [&](const std::string& name, double px, double py,
                      std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> moves) {
    bake::PoseDescription p;
    p.name = name;
    p.point = {px, py};
    p.deformed = true;
    p.deform.from = "rest";
    for (const auto& [at, to] : moves) {
      bake::HandleDescription handle;
      handle.at = at, handle.to = to;
      p.deform.handles.push_back(handle);
    }
    rig.poses.push_back(p);
  };
  deformed("wave", 1, 0.3,
           {{left_foot, left_foot},
            {right_foot, right_foot},
            {left_hand, {-2.2, 1.4}},
            {right_hand, {1.7, 3.7}},
            {head, {0.15, 4.05}}});
  deformed("cheer", 0, 1,
           {{left_foot, {-0.8, -1.5}},
            {right_foot, {0.8, -1.5}},
            {left_hand, {-1.8, 3.9}},
            {right_hand, {1.8, 3.9}},
            {head, {0, 4.2}}});
  deformed("lean", -1, 0.3,
           {{left_foot, left_foot}, {right_foot, right_foot}, {head, {-1.4, 3.7}}, {hips, {0.1, 0.35}}});
  deformed("crouch", 0, -1,
           {{left_foot, {-0.7, -1.5}},
            {right_foot, {0.7, -1.5}},
            {head, {0, 3.1}},
            {left_hand, {-2.1, 0.9}},
            {right_hand, {2.1, 0.9}}});
  rig.parameters.grid_resolution = 64;
  rig.parameters.grid_resolution_given = true;  // written into the description, as committed
  rig.parameters.sigma = 0.25;
  rig.paths.push_back(
      {"dance", true, true, {{0, 0, 0}, {0.6, 1, 0.3}, {1.2, 0, 1}, {1.8, -1, 0.3}, {2.4, 0, -1}, {3, 0, 0}}, {}});
  return rig;
}

}  // namespace posemorph::samples
