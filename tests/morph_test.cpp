// SPDX-License-Identifier: MIT
// Properties of the morph: poses reproduced, Alexa's closed form for N = 2,
// rigid motions stay rigid, unwrapped angles keep bent strips intact.
#include <Eigen/Dense>

#include "gingerbread_rig.h"
#include "test_support.h"

using namespace posemorph;
using namespace posemorph::test;
using posemorph::samples::Degrees;

namespace {

// Signed angle of the best-fit rotation from q to x (both centred) and the
// largest distance left after that rigid fit, relative to `scale`.
double RigidFitError(const std::vector<double>& x, const std::vector<Eigen::Vector2d>& q, double scale, double* angle) {
  const std::size_t V = q.size();
  Eigen::Vector2d cx = Eigen::Vector2d::Zero(), cq = Eigen::Vector2d::Zero();
  for (std::size_t v = 0; v < V; ++v) cx += Eigen::Vector2d(x[2 * v], x[2 * v + 1]), cq += q[v];
  cx /= double(V), cq /= double(V);
  double dot = 0, cross = 0;
  for (std::size_t v = 0; v < V; ++v) {
    const Eigen::Vector2d a = q[v] - cq, b = Eigen::Vector2d(x[2 * v], x[2 * v + 1]) - cx;
    dot += a.dot(b), cross += a.x() * b.y() - a.y() * b.x();
  }
  *angle = std::atan2(cross, dot);
  const Eigen::Rotation2Dd R(*angle);
  double worst = 0;
  for (std::size_t v = 0; v < V; ++v)
    worst = std::max(worst, (Eigen::Vector2d(x[2 * v], x[2 * v + 1]) - (cx + R * (q[v] - cq))).norm());
  return worst / scale;
}

}  // namespace

TEST_CASE("each pose is reproduced at its pose-space point") {
  for (bake::RigDescription desc :
       {samples::SnakeRig(), samples::WormLineRig(), BentStripRig(Degrees(300)), samples::GingerbreadRig()}) {
    desc =
        bake::WithPoseMeshes(desc, bake::ResolvePoseMeshes(desc));  // so `original` holds the deformed poses' vertices
    const bake::RigDescription original = desc;
    const Rig rig = Bake(desc);
    for (std::uint32_t i = 0; i < rig.pose_count(); ++i) {
      CAPTURE(original.name);
      CAPTURE(i);
      for (bool limit_weights : {true, false}) {
        const std::vector<double> x =
            MorphAt(rig, original.poses[i].point.x(), original.poses[i].point.y(), limit_weights);
        CHECK(MaxVertexDistance(x, original.poses[i].vertices) <= 1e-9 * rig.bounding_box_diagonal());
      }
      // And from exact one-hot weights, in single precision for the GPU: the
      // float copy is the double result rounded, so within 2^-24 of each coordinate.
      std::vector<double> e(rig.pose_count(), 0.0);
      e[i] = 1;
      std::vector<double> work(rig.morph_workspace_size()), x(2 * rig.vertex_count());
      std::vector<float> xf(x.size());
      MorphJob job;
      job.rig = &rig, job.weights = MakeSpan(e), job.limited_weights = MakeSpan(e);
      job.workspace = MakeSpan(work), job.positions = MakeSpan(x), job.positions_f32 = MakeSpan(xf);
      REQUIRE(job.Run());
      CHECK(MaxVertexDistance(x, original.poses[i].vertices) <= 1e-9 * rig.bounding_box_diagonal());
      double float_error = 0;
      for (std::size_t k = 0; k < x.size(); ++k) float_error = std::max(float_error, std::abs(double(xf[k]) - x[k]));
      CHECK(float_error <= 1e-6 * rig.bounding_box_diagonal());
    }
  }
}

TEST_CASE("N = 2 equals Alexa's closed form solved densely") {
  // Pose 1: bent by 110 degrees, stretched along and squashed across, so both
  // the rotation and the stretch interpolation matter.
  bake::RigDescription desc = BentStripRig(Degrees(110), 12, 3);
  for (auto& v : desc.poses[1].vertices) v = Eigen::Vector2d(1.3 * v.x() + 0.2 * v.y(), 0.8 * v.y() + 0.1 * v.x());
  const bake::RigDescription original = desc;
  const Rig rig = Bake(desc);
  const auto& tris = original.triangles;
  const auto& p0 = original.poses[0].vertices;
  const auto& p1 = original.poses[1].vertices;
  const int V = int(p0.size());

  // Per triangle: rest gradient operator, area, and the polar split of A by SVD.
  Eigen::Matrix<double, 2, 3> D;
  D << 1, 0, -1, 0, 1, -1;
  struct Tri {
    Eigen::Matrix<double, 2, 3> G;
    double area, theta;
    Eigen::Matrix2d S;
  };
  std::vector<Tri> data;
  std::vector<double> mass(V, 0.0);
  double total = 0;
  for (const auto& t : tris) {
    Eigen::Matrix2d E, F;
    E << p0[t[0]] - p0[t[2]], p0[t[1]] - p0[t[2]];
    F << p1[t[0]] - p1[t[2]], p1[t[1]] - p1[t[2]];
    const Eigen::Matrix2d A = F * E.inverse();
    Eigen::JacobiSVD<Eigen::Matrix2d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Matrix2d R = svd.matrixU() * svd.matrixV().transpose();
    REQUIRE(R.determinant() > 0);
    Tri d;
    d.G = E.inverse().transpose() * D;
    d.area = 0.5 * E.determinant();
    d.theta = std::atan2(R(1, 0), R(0, 0));
    d.S = svd.matrixV() * svd.singularValues().asDiagonal() * svd.matrixV().transpose();
    data.push_back(d);
    for (int k = 0; k < 3; ++k) mass[t[k]] += d.area / 3;
    total += d.area;
  }
  Eigen::Vector2d c0 = Eigen::Vector2d::Zero(), c1 = Eigen::Vector2d::Zero();
  for (int v = 0; v < V; ++v) c0 += mass[v] / total * p0[v], c1 += mass[v] / total * p1[v];

  for (double t = 0; t <= 1.0001; t += 0.125) {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(V, V), b = Eigen::MatrixXd::Zero(V, 2);
    for (std::size_t k = 0; k < tris.size(); ++k) {
      const Tri& d = data[k];
      const Eigen::Matrix2d At =
          Eigen::Rotation2Dd(t * d.theta).toRotationMatrix() * ((1 - t) * Eigen::Matrix2d::Identity() + t * d.S);
      const Eigen::Matrix3d Kt = d.area * d.G.transpose() * d.G;
      const Eigen::Matrix<double, 3, 2> bt = d.area * d.G.transpose() * At.transpose();
      for (int r = 0; r < 3; ++r) {
        b.row(tris[k][r]) += bt.row(r);
        for (int c = 0; c < 3; ++c) K(tris[k][r], tris[k][c]) += Kt(r, c);
      }
    }
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(V, 2);
    x.bottomRows(V - 1) = K.bottomRightCorner(V - 1, V - 1).ldlt().solve(b.bottomRows(V - 1));
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (int v = 0; v < V; ++v) c += mass[v] / total * x.row(v).transpose();
    const Eigen::Vector2d shift = (1 - t) * c0 + t * c1 - c;

    const std::vector<double> w = {1 - t, t};
    const std::vector<double> got = Morph(rig, w, w);
    double worst = 0;
    for (int v = 0; v < V; ++v)
      worst = std::max(worst, (Eigen::Vector2d(got[2 * v], got[2 * v + 1]) - (x.row(v).transpose() + shift)).norm());
    CAPTURE(t);
    CHECK(worst <= 1e-9 * rig.bounding_box_diagonal());
  }
}

TEST_CASE("a pose rotated by 170 degrees interpolates by rigid rotations only") {
  bake::RigDescription desc = BentStripRig(Degrees(60), 16, 3);
  const Eigen::Rotation2Dd R(Degrees(170));
  for (std::size_t v = 0; v < desc.poses[0].vertices.size(); ++v)
    desc.poses[1].vertices[v] = R * desc.poses[0].vertices[v] + Eigen::Vector2d(3, -2);
  const bake::RigDescription original = desc;
  const Rig rig = Bake(desc);
  for (double t = -0.25; t <= 1.25001; t += 0.05) {
    CAPTURE(t);
    const std::vector<double> w = {1 - t, t};
    double angle = 0;
    CHECK(RigidFitError(Morph(rig, w, w), original.poses[0].vertices, rig.bounding_box_diagonal(), &angle) <= 1e-9);
    // Angle t x 170 degrees, compared on the circle.
    CHECK(std::abs(std::remainder(angle - t * Degrees(170), 2 * M_PI)) <= 1e-9);
  }
  // Through the weight field too, weight limiting included: still rigid.
  for (double px = -0.5; px <= 1.5; px += 0.1) {
    double angle = 0;
    CHECK(RigidFitError(MorphAt(rig, px, 0.3), original.poses[0].vertices, rig.bounding_box_diagonal(), &angle) <=
          1e-9);
  }
}

TEST_CASE("a strip bent past 270 degrees keeps every triangle positive along the whole path") {
  const Rig rig = Bake(BentStripRig(Degrees(300), 40, 3));
  // Unwrapping made the baked angles continuous over the adjacency and let
  // them run past pi, where atan2 alone would have jumped by 2 pi.
  const std::uint32_t N = rig.pose_count();
  double largest = 0;
  for (std::uint32_t t = 0; t < rig.triangle_count(); ++t)
    largest = std::max(largest, std::abs(rig.angles()[t * N + 1]));
  CHECK(largest > Degrees(280));
  // The bent pose itself squeezes its inner edge (area ratio 0.74); every
  // in-between shape keeps every triangle at least that large: positive, no tear.
  auto ratio_at = [&](double t) { return MinAreaRatio(rig, Morph(rig, {1 - t, t}, {1 - t, t})); };
  const double end_ratio = std::min(ratio_at(0), ratio_at(1));
  CHECK(end_ratio > 0.7);
  for (double t = 0; t <= 1.0001; t += 0.01) {
    CAPTURE(t);
    CHECK(ratio_at(t) >= end_ratio - 1e-6);
  }
}

TEST_CASE("collinear pose points bake, evaluate, and extrapolate without degenerate triangles") {
  const bake::RigDescription desc = samples::WormLineRig();
  const Rig rig = Bake(desc);
  // The three points lie on y = 0; the field must still be defined off the line.
  const double far[][2] = {{-50, 0}, {50, 0}, {0, 40}, {0, -40}, {-1e6, 1e6}, {30, -30}, {1.5, 0}, {-1.4, 0.7}};
  for (const auto& p : far) {
    CAPTURE(p[0]);
    CAPTURE(p[1]);
    const Weights w = WeightsAt(rig, p[0], p[1]);
    double sum = 0;
    for (double v : w.raw) sum += v;
    CHECK(sum == doctest::Approx(1).epsilon(1e-12));
    const std::vector<double> x = Morph(rig, w.raw, w.limited);
    CHECK(MinAreaRatio(rig, x) > 0.5);
  }
}

TEST_CASE("weight limiting keeps extrapolation past a squashed pose from collapsing") {
  // Three poses on a line: rest, squashed across to 30%, stretched along.
  bake::RigDescription desc = BentStripRig(0, 16, 3);
  desc.poses[1].name = "squashed";
  for (auto& v : desc.poses[1].vertices) v.y() *= 0.3;
  bake::PoseDescription longer = desc.poses[0];
  longer.name = "longer";
  longer.point = {-1, 0};
  for (auto& v : longer.vertices) v.x() *= 1.5;
  desc.poses.push_back(longer);
  const Rig rig = Bake(desc);
  // Far beyond "squashed" the raw weights extrapolate (rest < 0, squashed > 1).
  const Weights w = WeightsAt(rig, 40, 0);
  CHECK(w.raw[0] < -0.3);
  CHECK(w.raw[1] > 1.3);
  const double limited = MinAreaRatio(rig, Morph(rig, w.raw, w.limited));
  const double unlimited = MinAreaRatio(rig, Morph(rig, w.raw, w.raw));
  MESSAGE("min area ratio far out: " << limited << " limited, " << unlimited << " without");
  CHECK(limited > 0.25);   // the squashed pose's own 0.3, no further
  CHECK(unlimited < 0.1);  // extrapolated stretch folds the strip flat or over
}
