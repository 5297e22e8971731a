// SPDX-License-Identifier: MIT
// The thin-plate spline through the pose points with the unit vectors as
// values: w(x) = sum_j a_j phi(|x - p_j|) + affine(x), phi(r) = r^2 log r, the
// function of least bending energy integral(W_xx^2 + 2 W_xy^2 + W_yy^2) over
// the whole plane with w(p_i) = e_i (Duchon; Bookstein). The pose-space
// weight field takes its values inside the points' hull from it
// (pose_space_weights.h).
#pragma once
#include <vector>

#include <Eigen/Core>

namespace posemorph::bake {

class ThinPlateSpline {
 public:
  // Distinct points, at least two. When they are collinear the field does
  // not vary across their line (the bending energy leaves that slope free).
  explicit ThinPlateSpline(const std::vector<Eigen::Vector2d>& points);

  // The N values at x; they sum to 1 (the affine part reproduces constants).
  Eigen::VectorXd operator()(const Eigen::Vector2d& x) const;

 private:
  std::vector<Eigen::Vector2d> points_;  // centred and scaled by 1/scale_
  Eigen::Vector2d centre_;
  double scale_ = 1;
  Eigen::Matrix2Xd axes_;         // the affine part's directions (1 or 2 columns)
  Eigen::MatrixXd coefficients_;  // (N + 1 + axes) x N: kernel weights, constant, slopes
};

}  // namespace posemorph::bake
