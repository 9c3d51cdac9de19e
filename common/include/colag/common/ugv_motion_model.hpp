#pragma once
// The differential-drive motion model of the paper's Eq. (3)-(4), extended with the wheel
// odometry's calibration. State (x, y, yaw, a_v, a_w, c, b, k), input the wheel-odometry twist
// (v_m, w_m) over dt. The robot's true twist is
//   v = (1 + a_v) v_m                    a_v: the wheels' scale error (radius off)
//   w = (1 + a_w) w_m + c v_m + b        a_w: turn-rate scale (track off)
//       - k w_m |w_m|                    c:   heading drift per metre (left and right wheels
//                                             of different size: turns while driving straight)
//                                        b:   heading drift per second while moving (camber)
//                                        k:   skid-steer slip: the faster it turns, the larger
//                                             the share of the turn its wheels skid away
// which is what two wheels with their own scale error and a track error give exactly (up to a
// v term in w_m small enough to ignore: c L^2 / 4), plus the first term of skid steering's slip
// (a constant share of the turn is a_w's; a share growing with the turn rate is k's: without it
// a robot that turns both slowly and on the spot learns neither right). Then
//   x' = x + cos(yaw) v dt,  y' = y + sin(yaw) v dt,  yaw' = yaw + w dt,  calibration kept
//   P' = F P F^T + B Q B^T + W dt,  F = df/dstate, B = df/d(v_m, w_m), Q = the twist's noise,
//   W = the calibration's random walk (tyres wear, the ground changes).
// With the calibration zero and its covariance zero this is the paper's 3-state model exactly.
// Shared by the EKF and the collision predictor, which propagates a copy along the plan: the
// calibration's uncertainty makes the error grow with the distance ahead, not its square root.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "colag/common/geometry.hpp"

namespace colag {

using Vec3 = Eigen::Vector3d;

inline constexpr int kPoseDim = 3;
inline constexpr int kCalibrationDim = 5;
inline constexpr int kUgvStateDim = kPoseDim + kCalibrationDim;
using UgvStateVec = Eigen::Matrix<double, kUgvStateDim, 1>;
using UgvStateCov = Eigen::Matrix<double, kUgvStateDim, kUgvStateDim>;

// Indices of the calibration in the state.
enum UgvStateIndex : int { kScaleV = 3, kScaleW = 4, kWPerMetre = 5, kWBias = 6, kSlip = 7 };

// Odometry noise, per sample: white noise on the measured twist. The proportional terms model
// wheel slip (the paper's 1 % multiplicative noise on the true motion).
struct OdometryNoise {
  double sigma_v_mps = 0.0336;
  double sigma_omega_radps = 0.0292;
  double sigma_v_fraction = 0.01;
  double sigma_omega_fraction = 0.01;
};

// The calibration's random walk: variance added per second and per radian turned (zero: the
// calibration is known, as the predictor uses it when the estimator does not estimate it).
struct CalibrationWalk {
  Eigen::Matrix<double, kCalibrationDim, 1> per_s =
      Eigen::Matrix<double, kCalibrationDim, 1>::Zero();
  Eigen::Matrix<double, kCalibrationDim, 1> per_rad =
      Eigen::Matrix<double, kCalibrationDim, 1>::Zero();
};

// What the robot's wheel odometry may get wrong systematically: the prior (1 sigma) of each
// calibration state and how fast each may change. Defaults are what an uncalibrated wheeled
// robot shows: wheel radii within a few percent (tyre wear, pressure, load), left and right
// differing by as much (0.03 x sqrt(2) / 0.4 m track = 0.1 rad per metre), skid-steer turn
// rates 5-20 % short of the wheels' on loose ground, more so the faster they turn (0.1 per rad/s:
// 10 % of a 1 rad/s turn lost beyond the constant share). A robot calibrated with UMBmark can set
// smaller priors; `estimate = false` gives the paper's 3-state filter.
struct OdometryCalibrationModel {
  bool estimate = true;
  double sigma_scale_v = 0.03;
  double sigma_scale_omega = 0.08;
  double sigma_omega_per_m_radpm = 0.10;
  double sigma_omega_bias_radps = 0.01;
  double sigma_slip_per_radps = 0.10;
  // Random walk, per sqrt(second): the calibration may change over minutes, not seconds.
  double walk_scale_per_sqrt_s = 0.001;
  double walk_omega_per_m_per_sqrt_s = 0.002;
  double walk_omega_bias_per_sqrt_s = 0.0002;
  double walk_slip_per_sqrt_s = 0.001;
  // And per sqrt(radian turned): a skid-steer's turn scale and slip change with the ground under
  // each turn (grass, gravel, a wet patch), so what the last turns taught holds only roughly for
  // the next. Without it the filter grew sure of them over a few turns and a fast 140 deg pivot
  // ended 0.11 rad off with a reported sigma of 0.03 (NEES 15, a box grazed in the field world).
  double walk_turn_per_sqrt_rad = 0.03;
  // Never believed beyond these (an outlier must not make the robot think it drives in circles).
  double max_scale = 0.3;
  double max_omega_per_m_radpm = 0.5;
  double max_omega_bias_radps = 0.1;
  double max_slip_per_radps = 0.5;

  Eigen::Matrix<double, kCalibrationDim, 1> prior_variance() const {
    if (!estimate) return Eigen::Matrix<double, kCalibrationDim, 1>::Zero();
    return {sigma_scale_v * sigma_scale_v, sigma_scale_omega * sigma_scale_omega,
            sigma_omega_per_m_radpm * sigma_omega_per_m_radpm,
            sigma_omega_bias_radps * sigma_omega_bias_radps,
            sigma_slip_per_radps * sigma_slip_per_radps};
  }
  CalibrationWalk walk() const {
    CalibrationWalk w;
    if (!estimate) return w;
    w.per_s = {walk_scale_per_sqrt_s * walk_scale_per_sqrt_s,
               walk_scale_per_sqrt_s * walk_scale_per_sqrt_s,
               walk_omega_per_m_per_sqrt_s * walk_omega_per_m_per_sqrt_s,
               walk_omega_bias_per_sqrt_s * walk_omega_bias_per_sqrt_s,
               walk_slip_per_sqrt_s * walk_slip_per_sqrt_s};
    const double turn = walk_turn_per_sqrt_rad * walk_turn_per_sqrt_rad;
    w.per_rad(kScaleW - kPoseDim) = turn;
    w.per_rad(kSlip - kPoseDim) = turn;
    return w;
  }
};

// Below this measured twist the wheels stand still: nothing moves, not even by the bias.
inline constexpr double kWheelsStill = 1e-4;
inline bool wheels_moving(double v_m, double w_m) {
  return std::abs(v_m) + std::abs(w_m) > kWheelsStill;
}

// The robot's twist from the measured one and the calibration in `x`.
inline Eigen::Vector2d calibrated_twist(const UgvStateVec& x, double v_m, double w_m) {
  const bool moving = wheels_moving(v_m, w_m);
  return {(1.0 + x(kScaleV)) * v_m, (1.0 + x(kScaleW)) * w_m - x(kSlip) * w_m * std::abs(w_m) +
                                        x(kWPerMetre) * v_m + (moving ? x(kWBias) : 0.0)};
}

// What the linearisation leaves out: a heading off by e moves the robot d (1 - cos e) ~ d e^2 / 2
// less far along its heading than the filter thinks, whatever the sign of e. Its rms per metre is
// sqrt(3) / 2 sigma_yaw^2 (E[e^4] = 3 sigma^4), and a heading error persists, so the shortfall
// adds up along the path: the along-heading standard deviation grows by that much per metre
// (coherently: as if fully correlated with the along-heading error already there). Negligible
// while the heading is known (sigma 0.05 rad: 2 mm per metre); it matters when an uncalibrated
// robot drives blind and its heading sigma reaches 0.3 rad: there the first-order covariance
// said 0.12 m along the path where the truth was 0.5 m off (NEES 27, standing 130 s).
inline void add_heading_second_order(UgvStateCov& P, double c, double s, double distance_m) {
  const double var_yaw = P(2, 2);
  const double grow = 0.5 * std::sqrt(3.0) * var_yaw * distance_m;
  if (!(grow > 0.0)) return;
  const Eigen::Vector2d u(c, s);
  const double along = u.dot(P.topLeftCorner<2, 2>() * u);
  P.topLeftCorner<2, 2>() +=
      (2.0 * std::sqrt(std::max(along, 0.0)) * grow + grow * grow) * u * u.transpose();
}

// The UAV odometry frame the robot is located in wanders against the ground (ugv_ekf.hpp,
// `frame_walk_m_per_sqrt_s`): the position's variance grows by walk^2 per second, wheels or not.
inline void add_frame_walk(UgvStateCov& P, double walk_m_per_sqrt_s, double dt) {
  const double var = walk_m_per_sqrt_s * walk_m_per_sqrt_s * dt;
  P(0, 0) += var;
  P(1, 1) += var;
}

// One step of the model; `walk`: the calibration's random walk.
inline void propagate(UgvStateVec& x, UgvStateCov& P, double v_m, double w_m, double dt,
                      const OdometryNoise& n, const CalibrationWalk& walk) {
  const double c = std::cos(x(2)), s = std::sin(x(2));
  const bool moving = wheels_moving(v_m, w_m);
  const Eigen::Vector2d tw = calibrated_twist(x, v_m, w_m);
  const double v = tw(0), w = tw(1);
  UgvStateCov F = UgvStateCov::Identity();
  F(0, 2) = -s * v * dt;
  F(1, 2) = c * v * dt;
  F(0, kScaleV) = c * v_m * dt;
  F(1, kScaleV) = s * v_m * dt;
  F(2, kScaleW) = w_m * dt;
  F(2, kWPerMetre) = v_m * dt;
  F(2, kWBias) = moving ? dt : 0.0;
  F(2, kSlip) = -w_m * std::abs(w_m) * dt;
  Eigen::Matrix<double, kUgvStateDim, 2> B = Eigen::Matrix<double, kUgvStateDim, 2>::Zero();
  B(0, 0) = c * (1.0 + x(kScaleV)) * dt;
  B(1, 0) = s * (1.0 + x(kScaleV)) * dt;
  B(2, 0) = x(kWPerMetre) * dt;
  B(2, 1) = (1.0 + x(kScaleW) - 2.0 * x(kSlip) * std::abs(w_m)) * dt;
  // Encoders that count no tick while the wheels stand are exact: no noise then (the wandering
  // of the frame the robot is located in is the estimator's:
  // UgvEkfConfig::frame_walk_m_per_sqrt_s).
  const double fv = n.sigma_v_fraction * v_m, fw = n.sigma_omega_fraction * w_m;
  const Eigen::Vector2d q =
      moving ? Eigen::Vector2d(n.sigma_v_mps * n.sigma_v_mps + fv * fv,
                               n.sigma_omega_radps * n.sigma_omega_radps + fw * fw)
             : Eigen::Vector2d::Zero();
  x(0) += c * v * dt;
  x(1) += s * v * dt;
  x(2) = wrap_angle(x(2) + w * dt);
  P = F * P * F.transpose() + B * q.asDiagonal() * B.transpose();
  P.diagonal().tail<kCalibrationDim>() += walk.per_s * dt + walk.per_rad * (std::abs(w_m) * dt);
  add_heading_second_order(P, c, s, std::abs(v) * dt);
}

}  // namespace colag
