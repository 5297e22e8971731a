// SPDX-License-Identifier: MIT
// Frames do not depend on the order of the triangle list or of the vertices
// (issue "Fidelity", defect 1): the per-pose 2 pi k of the unwrapped angles
// is chosen by the pose's area-weighted mean angle, not by triangle 0.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "gingerbread_rig.h"
#include "test_support.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

// The same rig with its vertices renumbered by `perm` (new index of old
// vertex v is perm[v]) and its triangles listed in `order`.
bake::RigDescription Permuted(const bake::RigDescription& rig, const std::vector<std::uint32_t>& perm,
                              const std::vector<std::size_t>& order) {
  bake::RigDescription out = rig;
  out.triangles.clear();
  for (std::size_t k : order) {
    const auto& t = rig.triangles[k];
    out.triangles.push_back({perm[t[0]], perm[t[1]], perm[t[2]]});
  }
  for (std::size_t i = 0; i < rig.poses.size(); ++i) {
    const bake::PoseDescription& a = rig.poses[i];
    bake::PoseDescription& b = out.poses[i];
    for (std::size_t v = 0; v < a.vertices.size(); ++v) b.vertices[perm[v]] = a.vertices[v];
    for (std::size_t v = 0; v < a.uvs.size(); ++v) b.uvs[perm[v]] = a.uvs[v];
  }
  return out;
}

// Frames at points spread over the pose points' box and beyond, positions
// mapped back to the original vertex numbering.
std::vector<double> Frames(const Rig& rig, const std::vector<std::uint32_t>& perm) {
  const Span<const double> p = rig.pose_points();
  double x0 = p[0], x1 = p[0], y0 = p[1], y1 = p[1];
  for (std::uint32_t i = 1; i < rig.pose_count(); ++i)
    x0 = std::min(x0, p[2 * i]), x1 = std::max(x1, p[2 * i]), y0 = std::min(y0, p[2 * i + 1]),
    y1 = std::max(y1, p[2 * i + 1]);
  std::vector<double> all;
  for (double fx : {-0.25, 0.1, 0.5, 0.83, 1.2})
    for (double fy : {-0.2, 0.3, 0.5, 0.9}) {
      const std::vector<double> x = MorphAt(rig, x0 + fx * (x1 - x0), y0 + fy * (y1 - y0 + 1e-9));
      for (std::size_t v = 0; v < perm.size(); ++v) all.push_back(x[2 * perm[v]]), all.push_back(x[2 * perm[v] + 1]);
    }
  return all;
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0;
  for (std::size_t k = 0; k < a.size(); ++k) worst = std::max(worst, std::fabs(a[k] - b[k]));
  return worst;
}

// A sample with every pose as a mesh (drawings mapped, deformations resolved).
bake::RigDescription Meshes(const bake::RigDescription& rig) {
  return bake::WithPoseMeshes(rig, bake::ResolvePoseMeshes(rig));
}

}  // namespace

TEST_CASE("a strip curled by 270 degrees gives the same in-betweens whichever triangle comes first") {
  // 14 vertices; pose 1 curled uniformly by 270 degrees.
  bake::RigDescription forward = BentStripRig(samples::Degrees(270), 6, 1);
  REQUIRE(forward.poses[0].vertices.size() == 14);
  bake::RigDescription reversed = forward;
  std::reverse(reversed.triangles.begin(), reversed.triangles.end());
  const Rig a = Bake(forward), b = Bake(reversed);
  const std::vector<double> xa = MorphAt(a, 0.5, 0), xb = MorphAt(b, 0.5, 0);
  CHECK(MaxDifference(xa, xb) <= 1e-12 * a.bounding_box_diagonal());
  // Half-way, the strip is curled by half of 270 degrees: of its 6 edge
  // segments the last turns by half of 5/6 x 270 = 112.5 degrees against the
  // first, and the first keeps the direction both orders agree on (before,
  // the reversed list turned the whole frame by a further 180 degrees:
  // -360 x w for w = 1/2).
  auto direction = [&](const std::vector<double>& x, std::uint32_t u, std::uint32_t v) {
    return std::atan2(x[2 * v + 1] - x[2 * u + 1], x[2 * v] - x[2 * u]);
  };
  const std::vector<double> rest = MorphAt(a, 0, 0);
  // Vertices along one long edge of the strip are 0, 2, 4, ..., 12 (two across).
  const double first_rest = direction(rest, 0, 2), first_mid = direction(xa, 0, 2);
  const double last_mid = direction(xa, 10, 12);
  double turn = (last_mid - first_mid) * 180 / M_PI;
  turn -= 360 * std::round((turn - 112.5) / 360);  // in the curl's direction
  MESSAGE("half-way: first edge at " << (first_mid - first_rest) * 180 / M_PI << " degrees, the last segment turned "
                                     << turn << " degrees against it");
  CHECK(std::fabs(turn - 112.5) < 1);
  CHECK(std::fabs(direction(xa, 0, 2) - direction(xb, 0, 2)) < 1e-9);
}

TEST_CASE("permuting triangles and vertices changes no frame of any sample beyond roundoff") {
  std::vector<bake::RigDescription> rigs = {samples::SnakeRig(), samples::WormLineRig(), samples::GingerbreadRig()};
  for (const char* name : {"pip", "sprout"})
    rigs.push_back(bake::ReadRigDescription(std::string(POSEMORPH_DRAWN_SAMPLES) + "/" + name + "/" + name + ".json"));
  std::mt19937 rng(2026);
  for (const bake::RigDescription& sample : rigs) {
    const bake::RigDescription rig = Meshes(sample);
    const std::size_t V = rig.poses[0].vertices.size();
    std::vector<std::uint32_t> identity(V);
    std::iota(identity.begin(), identity.end(), 0u);
    std::vector<std::size_t> order(rig.triangles.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    const Rig reference = Bake(rig);
    const std::vector<double> expected = Frames(reference, identity);
    for (int trial = 0; trial < 3; ++trial) {
      std::vector<std::uint32_t> perm = identity;
      std::shuffle(perm.begin(), perm.end(), rng);  // the pinned vertex lands anywhere
      std::shuffle(order.begin(), order.end(), rng);
      const Rig shuffled = Bake(Permuted(rig, perm, order));
      const double worst = MaxDifference(Frames(shuffled, perm), expected);
      CAPTURE(rig.name);
      CAPTURE(trial);
      CHECK(worst <= 1e-12 * reference.bounding_box_diagonal());
    }
  }
}
