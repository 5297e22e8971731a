// SPDX-License-Identifier: MIT
// The runtime's triangular solves against Eigen on a cotangent matrix the test
// assembles itself from the rest mesh.
#include <Eigen/SparseCholesky>
#include <cstring>
#include <random>

#include "ldlt_solve.h"
#include "rig_internals.h"
#include "test_support.h"

using namespace posemorph;
using namespace posemorph::test;

TEST_CASE("runtime solve equals Eigen SimplicialLDLT on the same system") {
  for (const bake::RigDescription& desc : {samples::SnakeRig(), samples::WormLineRig()}) {
    const Rig rig = Bake(desc);
    const std::uint32_t V = rig.vertex_count();
    const double* p = rig.pose_positions(0).data;
    // Cotangent weights: K_ab -= cot(angle opposite edge ab) / 2.
    std::vector<Eigen::Triplet<double>> entries;
    for (std::uint32_t t = 0; t < rig.triangle_count(); ++t) {
      const std::uint32_t* tri = rig.triangles().data + 3 * t;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t o = tri[k], a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
        const Eigen::Vector2d ea(p[2 * a] - p[2 * o], p[2 * a + 1] - p[2 * o + 1]);
        const Eigen::Vector2d eb(p[2 * b] - p[2 * o], p[2 * b + 1] - p[2 * o + 1]);
        const double cot = ea.dot(eb) / std::abs(ea.x() * eb.y() - ea.y() * eb.x());
        const std::pair<std::uint32_t, std::uint32_t> pairs[] = {{a, b}, {b, a}};
        for (auto [r, c] : pairs) {
          if (r == 0) continue;  // vertex 0 is pinned: its row and column go
          if (c != 0) entries.emplace_back(int(r - 1), int(c - 1), -cot / 2);
          entries.emplace_back(int(r - 1), int(r - 1), cot / 2);
        }
      }
    }
    Eigen::SparseMatrix<double> K(V - 1, V - 1);
    K.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> eigen(K);
    REQUIRE(eigen.info() == Eigen::Success);

    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uniform(-1, 1);
    for (int trial = 0; trial < 5; ++trial) {
      Eigen::MatrixXd b(V - 1, 2);
      for (int i = 0; i < b.size(); ++i) b.data()[i] = uniform(rng);
      const Eigen::MatrixXd expected = eigen.solve(b);
      std::vector<double> bi(2 * (V - 1)), scratch(2 * (V - 1)), x(2 * (V - 1));
      for (std::uint32_t k = 0; k + 1 < V; ++k) bi[2 * k] = b(k, 0), bi[2 * k + 1] = b(k, 1);
      detail::SolvePinned(rig, bi.data(), scratch.data(), x.data());
      double worst = 0, scale = 0;
      for (std::uint32_t k = 0; k + 1 < V; ++k) {
        worst = std::max({worst, std::abs(x[2 * k] - expected(k, 0)), std::abs(x[2 * k + 1] - expected(k, 1))});
        scale = std::max({scale, std::abs(expected(k, 0)), std::abs(expected(k, 1))});
      }
      CAPTURE(desc.name);
      CHECK(worst <= 1e-10 * scale);
      // In place (b and x the same array) gives the same answer.
      detail::SolvePinned(rig, bi.data(), scratch.data(), bi.data());
      CHECK(bi == x);
    }
  }
}

TEST_CASE("16-bit and 32-bit solve indices give the same bits, single and batched") {
  const bake::RigDescription desc = samples::SnakeRig();
  bake::RigDescription copy = desc;
  copy.parameters.compact = false;
  const std::vector<unsigned char> bytes = bake::BakeRig(copy);
  Rig narrow, wide;
  Error err;
  REQUIRE(LoadRig(bytes.data(), bytes.size(), &narrow, &err));
  LoadOptions options;
  options.wide_solve_indices = true;
  REQUIRE(LoadRig(bytes.data(), bytes.size(), &wide, &err, options));
  REQUIRE(detail::RigInternals::Solve(narrow).row_col2_16.size > 0);
  REQUIRE(detail::RigInternals::Solve(narrow).row_col2.size == 0);
  REQUIRE(detail::RigInternals::Solve(wide).row_col2_16.size == 0);
  REQUIRE(detail::RigInternals::Solve(wide).row_col2.size > 0);
  // The narrow rig's arena is smaller by the index bytes saved.
  CHECK(narrow.arena_bytes() < wide.arena_bytes());

  const std::uint32_t N = narrow.pose_count(), V = narrow.vertex_count();
  std::vector<double> raw(N), limited(N);
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0.3, 0.4}, {-0.8, 0.1}, {1.7, -2.0}}) {
    std::vector<double> out[2];
    for (int which = 0; which < 2; ++which) {
      const Rig& rig = which ? wide : narrow;
      WeightsJob wj;
      wj.rig = &rig;
      wj.x = x, wj.y = y;
      wj.raw = {raw.data(), N};
      wj.limited = {limited.data(), N};
      REQUIRE(wj.Run());
      std::vector<double> workspace(rig.morph_workspace_size());
      out[which].resize(2 * V);
      MorphJob mj;
      mj.rig = &rig;
      mj.weights = {raw.data(), N};
      mj.limited_weights = {limited.data(), N};
      mj.workspace = {workspace.data(), workspace.size()};
      mj.positions = {out[which].data(), out[which].size()};
      REQUIRE(mj.Run());
    }
    CHECK(std::memcmp(out[0].data(), out[1].data(), out[0].size() * sizeof(double)) == 0);
    // Batched on the wide rig equals single on the narrow one.
    std::vector<double> weights, all_limited;
    for (int c = 0; c < 9; ++c)
      weights.insert(weights.end(), raw.begin(), raw.end()),
          all_limited.insert(all_limited.end(), limited.begin(), limited.end());
    std::vector<double> batch(9 * 2 * V), workspace(wide.batch_workspace_size());
    MorphBatchJob bj;
    bj.rig = &wide;
    bj.count = 9;
    bj.weights = {weights.data(), weights.size()};
    bj.limited_weights = {all_limited.data(), all_limited.size()};
    bj.workspace = {workspace.data(), workspace.size()};
    bj.positions = {batch.data(), batch.size()};
    REQUIRE(bj.Run());
    for (int c = 0; c < 9; ++c)
      CHECK(std::memcmp(batch.data() + c * 2 * V, out[0].data(), 2 * V * sizeof(double)) == 0);
  }
}
