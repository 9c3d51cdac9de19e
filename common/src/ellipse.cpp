#include "colag/common/ellipse.hpp"

#include <Eigen/Eigenvalues>

namespace colag {

namespace {
constexpr double kMinVariance = 1e-12;  // (1 um)^2: keeps M invertible
}

Ellipse sigma_ellipse(const Vec2& mean, const Mat2& covariance, double k_sigma) {
  Mat2 c = 0.5 * k_sigma * k_sigma * (covariance + covariance.transpose());
  c(0, 0) = std::max(c(0, 0), kMinVariance);
  c(1, 1) = std::max(c(1, 1), kMinVariance);
  // Keep it positive definite: |c01| < sqrt(c00 c11).
  const double limit = std::sqrt(c(0, 0) * c(1, 1)) * (1.0 - 1e-9);
  c(0, 1) = c(1, 0) = std::clamp(c(0, 1), -limit, limit);
  return {mean, c};
}

Ellipse::Axes Ellipse::axes() const {
  Eigen::SelfAdjointEigenSolver<Mat2> eig(M);
  const Vec2 l = eig.eigenvalues().cwiseMax(0.0);  // ascending
  const Vec2 major = eig.eigenvectors().col(1);
  return {std::sqrt(l(1)), std::sqrt(l(0)), std::atan2(major.y(), major.x())};
}

Ellipse Ellipse::grown(double m) const {
  if (!(m > 0.0)) return *this;
  Eigen::SelfAdjointEigenSolver<Mat2> eig(M);
  const Vec2 l = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt() + Vec2::Constant(m);
  const Mat2& V = eig.eigenvectors();
  return {center, V * l.cwiseAbs2().asDiagonal() * V.transpose()};
}

bool Ellipse::contains(const Vec2& p) const {
  const Vec2 d = p - center;
  return d.dot(M.ldlt().solve(d)) <= 1.0;
}

}  // namespace colag
