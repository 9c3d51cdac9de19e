#include "colag/common/ugv_ekf.hpp"

#include <Eigen/LU>
#include <cmath>

namespace colag {

namespace {
bool finite(const Mat3& m) {
  return m.allFinite();
}
}  // namespace

void UgvEkf::reset() {
  initialized_ = false;
  consecutive_rejections_ = 0;
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
    step.x = state_.x;
    step.P = state_.P;
    propagate(step.x, step.P, v_mps, omega_radps, to_seconds(stamp - state_.t), config_.noise);
    ++counters_.predictions;
  }
  history_.push_overwrite(step);
  state_ = step;
  return Status::ok();
}

void UgvEkf::repropagate(std::size_t from) {
  for (std::size_t i = from + 1; i < history_.size(); ++i) {
    const Step& prev = history_[i - 1];
    Step& cur = history_[i];
    cur.x = prev.x;
    cur.P = prev.P;
    propagate(cur.x, cur.P, cur.v, cur.w, to_seconds(cur.t - prev.t), config_.noise);
  }
  state_ = history_.back();
}

UgvEkf::Update UgvEkf::update(const PoseMeasurement& z) {
  const Mat3& R = z.covariance;
  if (!all_finite(z.pose.p) || !std::isfinite(z.pose.yaw_rad) || !finite(R) || R(0, 0) <= 0.0 ||
      R(1, 1) <= 0.0 || R(2, 2) <= 0.0 || R.determinant() <= 0.0) {
    ++counters_.rejected_invalid;
    return Update::kRejectedInvalid;
  }
  // The newest step at or before the measurement; a measurement newer than every odometry
  // sample applies to the newest state.
  std::size_t k = history_.size();
  while (k > 0 && history_[k - 1].t > z.stamp)
    --k;
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
  Step& at = history_[k - 1];
  const Vec3 zv(z.pose.p.x(), z.pose.p.y(), wrap_angle(z.pose.yaw_rad));

  const auto initialise = [&](Update result) {
    at.x = zv;
    at.P = R;
    initialized_ = true;
    consecutive_rejections_ = 0;
    repropagate(k - 1);
    return result;
  };
  if (!initialized_) return initialise(Update::kInitialized);

  Vec3 innovation = zv - at.x;
  innovation.z() = wrap_angle(innovation.z());
  const Mat3 S = at.P + R;
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
  const Mat3 K = at.P * S.inverse();
  const Mat3 IK = Mat3::Identity() - K;
  at.x += K * innovation;
  at.x.z() = wrap_angle(at.x.z());
  at.P = IK * at.P * IK.transpose() + K * R * K.transpose();  // Joseph form
  at.P = 0.5 * (at.P + at.P.transpose());
  ++counters_.updates;
  repropagate(k - 1);
  return Update::kApplied;
}

}  // namespace colag
