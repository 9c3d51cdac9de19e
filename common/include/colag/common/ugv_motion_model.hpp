#pragma once
// The differential-drive motion model of the paper's Eq. (3)-(4): state (x, y, yaw), input the
// wheel-odometry twist (v, omega) over dt:
//   x' = x + cos(yaw) v dt,  y' = y + sin(yaw) v dt,  yaw' = yaw + omega dt
//   P' = F P F^T + B Q B^T,  F = df/dstate, B = df/d(v, omega), Q = diag(sigma_v^2, sigma_w^2).
// Shared by the EKF and the collision predictor (which propagates a copy along the plan).
#include <Eigen/Core>

#include "colag/common/geometry.hpp"

namespace colag {

using Vec3 = Eigen::Vector3d;

// Odometry noise, per sample: white noise on the measured twist. The proportional terms model
// wheel slip (the paper's 1 % multiplicative noise on the true motion).
struct OdometryNoise {
  double sigma_v_mps = 0.0336;
  double sigma_omega_radps = 0.0292;
  double sigma_v_fraction = 0.01;
  double sigma_omega_fraction = 0.01;
};

inline void propagate(Vec3& x, Mat3& P, double v, double omega, double dt, const OdometryNoise& n) {
  const double c = std::cos(x.z()), s = std::sin(x.z());
  Mat3 F = Mat3::Identity();
  F(0, 2) = -s * v * dt;
  F(1, 2) = c * v * dt;
  Eigen::Matrix<double, 3, 2> B;
  B << c * dt, 0.0, s * dt, 0.0, 0.0, dt;
  const double fv = n.sigma_v_fraction * v, fw = n.sigma_omega_fraction * omega;
  const Eigen::Vector2d q(n.sigma_v_mps * n.sigma_v_mps + fv * fv,
                          n.sigma_omega_radps * n.sigma_omega_radps + fw * fw);
  x.x() += c * v * dt;
  x.y() += s * v * dt;
  x.z() = wrap_angle(x.z() + omega * dt);
  P = F * P * F.transpose() + B * q.asDiagonal() * B.transpose();
}

}  // namespace colag
