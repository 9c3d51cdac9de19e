#include "colag/common/ugv_ekf.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace colag {

namespace {
bool finite(const Mat3& m) {
  return m.allFinite();
}
}  // namespace

void UgvEkf::advance(Step& cur, const Step& prev) const {
  cur.x = prev.x;
  cur.P = prev.P;
  const double dt = to_seconds(cur.t - prev.t);
  propagate(cur.x, cur.P, cur.v, cur.w, dt, config_.noise, config_.calibration.walk());
  add_frame_walk(cur.P, config_.frame_walk_m_per_sqrt_s, dt);
}

void UgvEkf::clamp_calibration(UgvStateVec& x) const {
  const OdometryCalibrationModel& m = config_.calibration;
  x(kScaleV) = std::clamp(x(kScaleV), -m.max_scale, m.max_scale);
  x(kScaleW) = std::clamp(x(kScaleW), -m.max_scale, m.max_scale);
  x(kWPerMetre) = std::clamp(x(kWPerMetre), -m.max_omega_per_m_radpm, m.max_omega_per_m_radpm);
  x(kWBias) = std::clamp(x(kWBias), -m.max_omega_bias_radps, m.max_omega_bias_radps);
  x(kSlip) = std::clamp(x(kSlip), -m.max_slip_per_radps, m.max_slip_per_radps);
}

void UgvEkf::reset() {
  initialized_ = false;
  consecutive_rejections_ = 0;
  held_.reset();
  noise_mean_ = 1.0;
  noise_samples_ = 0.0;
  history_.clear();
  state_ = Step{};
}

Status UgvEkf::predict(TimePoint stamp, double v_mps, double omega_radps) {
  if (!std::isfinite(v_mps) || !std::isfinite(omega_radps)) {
    ++counters_.rejected_odometry;
    return {Errc::kInvalidArgument, "odometry not finite"};
  }
  if (!history_.empty() && stamp <= history_.back().t) {
    ++counters_.rejected_odometry;
    return {Errc::kOutOfRange, "odometry out of order"};
  }
  Step step;
  step.t = stamp;
  step.v = v_mps;
  step.w = omega_radps;
  if (initialized_) {
    advance(step, state_);
    ++counters_.predictions;
  }
  history_.push_overwrite(step);
  state_ = step;
  return Status::ok();
}

void UgvEkf::repropagate(std::size_t from) {
  for (std::size_t i = from + 1; i < history_.size(); ++i)
    advance(history_[i], history_[i - 1]);
  state_ = history_.back();
}

std::size_t UgvEkf::step_at(TimePoint stamp) const {
  std::size_t k = history_.size();
  while (k > 0 && history_[k - 1].t > stamp)
    --k;
  return k;
}

Vec3 UgvEkf::innovation_at(const PoseMeasurement& z, std::size_t k) const {
  Vec3 e = Vec3(z.pose.p.x(), z.pose.p.y(), z.pose.yaw_rad) - history_[k - 1].x.head<3>();
  e.z() = wrap_angle(e.z());
  return e;
}

UgvEkf::Update UgvEkf::update(const PoseMeasurement& z) {
  const Mat3& reported = z.covariance;
  if (!all_finite(z.pose.p) || !std::isfinite(z.pose.yaw_rad) || !finite(reported) ||
      reported(0, 0) <= 0.0 || reported(1, 1) <= 0.0 || reported(2, 2) <= 0.0 ||
      reported.determinant() <= 0.0) {
    ++counters_.rejected_invalid;
    return Update::kRejectedInvalid;
  }
  // The newest step at or before the measurement; a measurement newer than every odometry
  // sample applies to the newest state.
  std::size_t k = step_at(z.stamp);
  if (k == 0 && !history_.empty()) {
    ++counters_.rejected_stale;
    return Update::kRejectedStale;
  }
  if (history_.empty()) {  // no odometry yet: start the history at the measurement
    Step s;
    s.t = z.stamp;
    history_.push_overwrite(s);
    k = 1;
  }
  const bool starting = !initialized_;
  if (!confirmed(z, k)) return Update::kHeld;
  const Update u = apply(z, k);
  return starting && initialized_ ? Update::kInitialized : u;
}

bool UgvEkf::confirmed(const PoseMeasurement& z, std::size_t k) {
  const bool starting = !initialized_;
  if (starting ? !(config_.start_window_s > 0.0)
               : !(config_.reacquire_after_s > 0.0) ||
                     to_seconds(z.stamp - last_applied_) <= config_.reacquire_after_s) {
    return true;
  }
  if (held_) {
    const PoseMeasurement first = *held_;
    held_.reset();
    const double apart = std::abs(to_seconds(z.stamp - first.stamp));
    const std::size_t kf = step_at(first.stamp);
    if (apart <= (starting ? config_.start_window_s : config_.reacquire_window_s) &&
        (starting || kf > 0) && agree(z, k, first, kf)) {
      // The first is applied before this one; at the start, one older than the odometry
      // history is not, and this one starts the estimator (it agreed with it).
      if (kf > 0) (void)apply(first, kf);
      return true;
    }
    ++counters_.unconfirmed;
  }
  held_ = z;
  ++counters_.held;
  return false;
}

bool UgvEkf::agree(const PoseMeasurement& a, std::size_t ka, const PoseMeasurement& b,
                   std::size_t kb) const {
  // Initialised, both innovations carry the state's error at their stamps, which the odometry
  // between them (under a second) barely changes: what differs is the two measurements' own
  // errors. Before the start the robot stands: the measurements themselves are compared.
  Vec3 d;
  if (initialized_) {
    d = innovation_at(a, ka) - innovation_at(b, kb);
  } else {
    d = Vec3(a.pose.p.x() - b.pose.p.x(), a.pose.p.y() - b.pose.p.y(),
             a.pose.yaw_rad - b.pose.yaw_rad);
  }
  d.z() = wrap_angle(d.z());
  const Mat3 S = measurement_noise_scale() * (a.covariance + b.covariance);
  return d.dot(S.ldlt().solve(d)) <= config_.gate_chi2;
}

UgvEkf::Update UgvEkf::apply(const PoseMeasurement& z, std::size_t k) {
  const Mat3& reported = z.covariance;
  const Mat3 R = measurement_noise_scale() * reported;
  Step& at = history_[k - 1];
  const Vec3 zv(z.pose.p.x(), z.pose.p.y(), wrap_angle(z.pose.yaw_rad));

  // The pose from the measurement; the calibration learnt so far is kept (a reset follows a
  // divergence, which a wrong calibration may have caused: its covariance goes back to the
  // prior so that it is learnt again quickly).
  const auto initialise = [&](Update result) {
    at.x.head<3>() = zv;
    at.P.setZero();
    at.P.topLeftCorner<3, 3>() = R;
    at.P.diagonal().tail<kCalibrationDim>() = config_.calibration.prior_variance();
    initialized_ = true;
    consecutive_rejections_ = 0;
    last_applied_ = z.stamp;
    held_.reset();
    repropagate(k - 1);
    return result;
  };
  if (!initialized_) return initialise(Update::kInitialized);

  const Vec3 innovation = innovation_at(z, k);
  const Mat3 S = at.P.topLeftCorner<3, 3>() + R;
  const double d2 = innovation.dot(S.ldlt().solve(innovation));
  if (!(d2 <= config_.gate_chi2)) {
    ++counters_.rejected_gate;
    if (++consecutive_rejections_ >= config_.reset_after_rejections) {
      ++counters_.resets;
      return initialise(Update::kReset);
    }
    return Update::kRejectedGate;
  }
  consecutive_rejections_ = 0;
  if (config_.adapt_measurement_noise) {
    // E[e e^T] = P + lambda R0: lambda's estimate from this innovation, (e^T R0^-1 e -
    // tr(R0^-1 P)) / 3, averaged (a plain mean at first, then over the window) and used within
    // [1, max].
    const Mat3 R0inv = reported.inverse();
    const double sample =
        (innovation.dot(R0inv * innovation) - (R0inv * at.P.topLeftCorner<3, 3>()).trace()) / 3.0;
    noise_samples_ = std::min(noise_samples_ + 1.0, config_.measurement_noise_window);
    noise_mean_ += (sample - noise_mean_) / noise_samples_;
  }
  // Huber: a measurement further out than the robust bound (inside the gate) counts less, as if
  // its covariance were larger by sqrt(d2 / bound): a moderate outlier (a tag half a metre off,
  // inside the gate of an uncertain state) pulls the estimate less.
  const Mat3 Ru = d2 > config_.robust_chi2 ? std::sqrt(d2 / config_.robust_chi2) * R : R;
  const Mat3 Su = at.P.topLeftCorner<3, 3>() + Ru;
  // H = [I3 0]: the measurement sees the pose; the calibration through its correlation.
  const Eigen::Matrix<double, kUgvStateDim, 3> K = at.P.leftCols<3>() * Su.inverse();
  UgvStateCov IK = UgvStateCov::Identity();
  IK.leftCols<3>() -= K;
  at.x += K * innovation;
  at.x(2) = wrap_angle(at.x(2));
  clamp_calibration(at.x);
  at.P = IK * at.P * IK.transpose() + K * Ru * K.transpose();  // Joseph form
  at.P = 0.5 * (at.P + at.P.transpose());
  ++counters_.updates;
  last_applied_ = std::max(last_applied_, z.stamp);
  repropagate(k - 1);
  return Update::kApplied;
}

}  // namespace colag
