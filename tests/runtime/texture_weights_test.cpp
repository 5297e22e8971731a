// SPDX-License-Identifier: MIT
// Texture weights at the edges (issue "Fidelity", defect 3): continuous in
// sigma up to and including 1, and always a convex combination, also with
// weight limiting off.
#include <cmath>

#include "runtime_support.h"

using namespace posemorph;
using namespace posemorph::test;

TEST_CASE("texture weights are continuous in sigma up to 1, where every limited weight is below 1/2") {
  // At sigma = 1 the paper's formula is 0/0 when no weight passes 1/2.
  const double flat[] = {0.3, 0.45, 0.25}, peaked[] = {0.1, 0.62, 0.28};
  double at[3], near[3];
  TextureWeights(Span<const double>(flat, 3), 1.0, Span<double>(at, 3));
  for (double gap : {1e-3, 1e-6, 1e-9, 1e-13}) {
    TextureWeights(Span<const double>(flat, 3), 1.0 - gap, Span<double>(near, 3));
    for (int i = 0; i < 3; ++i) CHECK(std::fabs(at[i] - near[i]) <= 10 * gap);
  }
  for (int i = 0; i < 3; ++i) CHECK(std::fabs(at[i] - flat[i]) < 1e-15);  // the limit is w' itself
  // With a weight above 1/2, sigma = 1 is the cut to that pose.
  TextureWeights(Span<const double>(peaked, 3), 1.0, Span<double>(at, 3));
  CHECK(at[1] == 1.0);
  CHECK(at[0] == 0.0);
  // The same through WeightsJob, in place (texture may alias nothing here).
  const Rig rig = LoadTestRig("snake");
  const Weights w = WeightsAt(rig, 0.5, 0.5, 1.0);
  double sum = 0;
  for (double t : w.texture) sum += t;
  CHECK(std::fabs(sum - 1) < 1e-12);
}

TEST_CASE("texture weights are a convex combination everywhere, with or without weight limiting") {
  const Rig rig = LoadTestRig("snake");
  const PoseSpaceGrid& g = rig.grid();
  double lowest = 1, worst_sum = 0;
  for (bool limit : {true, false})
    for (double sigma : {0.0, 0.3, 1.0})
      for (int j = 0; j <= 60; ++j)
        for (int i = 0; i <= 60; ++i) {
          const double x = g.origin_x - 1 + (g.cell * g.cells_x + 2) * i / 60;
          const double y = g.origin_y - 1 + (g.cell * g.cells_y + 2) * j / 60;
          const Weights w = WeightsAt(rig, x, y, sigma, limit);
          double sum = 0;
          for (double t : w.texture) lowest = std::min(lowest, t), sum += t;
          worst_sum = std::max(worst_sum, std::fabs(sum - 1));
        }
  CHECK(lowest >= 0);
  CHECK(worst_sum < 1e-12);
  // The example: at (1.8, 0.2) without limiting the raw weights go
  // negative, and so did the texture weights (-0.23).
  const Weights w = WeightsAt(rig, 1.8, 0.2, 0, false);
  CHECK(*std::min_element(w.raw.begin(), w.raw.end()) < 0);
  CHECK(*std::min_element(w.texture.begin(), w.texture.end()) >= 0);
}
