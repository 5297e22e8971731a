// The runtime's triangular solves against Eigen on a cotangent matrix the test
// assembles itself from the rest mesh.
#include <Eigen/SparseCholesky>
#include <random>

#include "../runtime/src/ldlt_solve.h"
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
      detail::SolvePinned(rig.factor(), bi.data(), scratch.data(), x.data());
      double worst = 0, scale = 0;
      for (std::uint32_t k = 0; k + 1 < V; ++k) {
        worst = std::max({worst, std::abs(x[2 * k] - expected(k, 0)), std::abs(x[2 * k + 1] - expected(k, 1))});
        scale = std::max({scale, std::abs(expected(k, 0)), std::abs(expected(k, 1))});
      }
      CAPTURE(desc.name);
      CHECK(worst <= 1e-10 * scale);
      // In place (b and x the same array) gives the same answer.
      detail::SolvePinned(rig.factor(), bi.data(), scratch.data(), bi.data());
      CHECK(bi == x);
    }
  }
}
