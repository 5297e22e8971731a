// SPDX-License-Identifier: MIT
#include "posemorph/bake/thin_plate_spline.h"

#include <Eigen/Dense>
#include <cmath>

namespace posemorph::bake {
namespace {

double Phi(double r) { return r > 0 ? r * r * std::log(r) : 0.0; }

}  // namespace

ThinPlateSpline::ThinPlateSpline(const std::vector<Eigen::Vector2d>& points) {
  const int n = int(points.size());
  // Centre and scale the points to unit spread: the system is then
  // conditioned alike at any pose-space scale (scaling only adds an affine
  // term to the kernel sum, which the side conditions remove).
  centre_.setZero();
  for (const auto& p : points) centre_ += p;
  centre_ /= double(n);
  scale_ = 0;
  for (const auto& p : points) scale_ = std::max(scale_, (p - centre_).norm());
  if (!(scale_ > 0)) scale_ = 1;
  for (const auto& p : points) points_.push_back((p - centre_) / scale_);
  // The affine part spans the directions the points extend in: both axes,
  // or for collinear points only their line.
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const auto& p : points_) scatter += p * p.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  const bool collinear = eig.eigenvalues()(0) <= 1e-12 * eig.eigenvalues()(1);
  axes_ = collinear ? Eigen::Matrix2Xd(eig.eigenvectors().col(1)) : Eigen::Matrix2Xd(Eigen::Matrix2d::Identity());
  const int d = int(axes_.cols()), m = n + 1 + d;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A(i, j) = Phi((points_[std::size_t(i)] - points_[std::size_t(j)]).norm());
    A(i, n) = A(n, i) = 1;
    for (int k = 0; k < d; ++k) A(i, n + 1 + k) = A(n + 1 + k, i) = axes_.col(k).dot(points_[std::size_t(i)]);
  }
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, n);
  rhs.topRows(n).setIdentity();
  coefficients_ = A.fullPivLu().solve(rhs);
}

Eigen::VectorXd ThinPlateSpline::operator()(const Eigen::Vector2d& x) const {
  const int n = int(points_.size()), d = int(axes_.cols());
  const Eigen::Vector2d y = (x - centre_) / scale_;
  Eigen::VectorXd basis(n + 1 + d);
  for (int j = 0; j < n; ++j) basis(j) = Phi((y - points_[std::size_t(j)]).norm());
  basis(n) = 1;
  for (int k = 0; k < d; ++k) basis(n + 1 + k) = axes_.col(k).dot(y);
  return coefficients_.transpose() * basis;
}

}  // namespace posemorph::bake
