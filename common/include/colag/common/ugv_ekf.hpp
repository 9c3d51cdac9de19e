#pragma once
// The UGV's pose estimator (paper Sec. III-A): an EKF on (x, y, yaw) predicted with wheel
// odometry and updated with the UGV pose observed by the UAV (UAV odometry composed with the
// relative pose). Differences from a textbook EKF, all for robustness on a real robot:
// - the state carries the wheel odometry's calibration (ugv_motion_model.hpp): scale, turn-rate
//   scale, heading drift per metre and per second, learnt from the relative poses. Without it a
//   3 % wheel-radius error made the estimate 10-100 times over-confident (NEES 69-830);
// - measurements are applied at their own time stamp: the filter keeps ~1 s of odometry
//   history, updates the state of that time and re-propagates to now (RPE arrives late);
// - a chi-square gate on the Mahalanobis distance rejects outliers; after many consecutive
//   rejections the filter re-initialises from the measurement (it had diverged);
// - the covariance update uses the Joseph form (stays symmetric positive definite);
// - the relative poses' reported covariance is scaled by what their innovations show
//   (innovation-based covariance matching, Mehra 1972): an AprilTag pose's covariance is a
//   constant while its true error grows with distance and obliquity. Only up, never below the
//   reported one, and slowly (over ~50 updates) so that outliers cannot drive it;
// - after a gap (no relative pose applied for a few seconds: a blackout, the UAV elsewhere) the
//   state is too uncertain to tell an outlier from a fix, and a gate wide enough for the truth
//   lets a tag a metre off through: a relative pose is then held until the next one confirms it
//   (their innovations agree), and only then are both applied. The very first one is held the
//   same way: nothing else checks it, and a start 0.8 m off with sigma 0.2 m (4 sigma) kept a
//   UGV's NEES at 18 for 100 s. Two catch an outlier many sigma out (near detections report
//   centimetres); one within a far detection's wide covariance still passes, and is left to the
//   gate and the reset.
#include <algorithm>
#include <cstdint>
#include <optional>

#include "colag/common/geometry.hpp"
#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/common/status.hpp"
#include "colag/common/time.hpp"
#include "colag/common/ugv_motion_model.hpp"

namespace colag {

struct PoseMeasurement {
  TimePoint stamp;
  Pose2 pose;
  Mat3 covariance = Mat3::Identity();  // (x, y, yaw)
};

struct UgvEkfConfig {
  OdometryNoise noise;
  OdometryCalibrationModel calibration;
  // The robot is located in the UAV's odometry frame, and that frame wanders against the ground
  // (a LiDAR-inertial odometry's slow drift and rare re-registration jumps, a few cm a minute):
  // the position's variance grows by frame_walk^2 per second whatever the wheels do. Without
  // it a UGV standing for minutes under the UAV grew ever surer (sigma 1.7 cm) while the frame
  // moved under it (NEES 8.5 over a mission). 0: a frame fixed to the ground.
  double frame_walk_m_per_sqrt_s = 0.005;
  double gate_chi2 = 16.27;         // chi-square, 3 dof, 99.9 %: one false reject in 1000
  double robust_chi2 = 7.81;        // 95 %: beyond it a measurement is down-weighted (Huber)
  int reset_after_rejections = 25;  // consecutive gate rejections => re-initialise
  // Re-acquisition: after this long without an applied relative pose one is applied only when
  // the next, within the window, agrees with it (0: every one is applied on its own).
  double reacquire_after_s = 3.0;
  double reacquire_window_s = 1.0;
  // The start: the first relative pose waits for one within this window that agrees with it
  // (the robot stands until it is localised). 0: the first one starts the estimator alone.
  double start_window_s = 2.0;
  bool adapt_measurement_noise = true;
  double max_measurement_noise_scale = 10.0;  // variance factor
  double measurement_noise_window = 50.0;     // updates averaged
};

struct UgvEkfCounters {
  std::uint64_t predictions = 0;
  std::uint64_t updates = 0;
  std::uint64_t rejected_gate = 0;      // outliers
  std::uint64_t rejected_stale = 0;     // older than the odometry history
  std::uint64_t rejected_invalid = 0;   // NaN/Inf, non-positive covariance
  std::uint64_t rejected_odometry = 0;  // odometry out of order or not finite
  std::uint64_t resets = 0;
  std::uint64_t held = 0;         // at the start or after a gap: waited for the next
  std::uint64_t unconfirmed = 0;  // held, and the next did not agree: dropped
};

class UgvEkf {
 public:
  static constexpr std::size_t kHistory = limits::kEkfHistory;  // 1.28 s at 50 Hz

  enum class Update : std::uint8_t {
    kInitialized,
    kApplied,
    kRejectedGate,
    kRejectedStale,
    kRejectedInvalid,
    kReset,
    kHeld  // at the start or after a gap: applied when the next agrees with it
  };

  explicit UgvEkf(const UgvEkfConfig& config = {}) : config_(config) {}

  bool initialized() const { return initialized_; }
  // One wheel-odometry sample: the twist measured over (previous stamp, stamp].
  Status predict(TimePoint stamp, double v_mps, double omega_radps);
  Update update(const PoseMeasurement& z);
  void reset();

  Pose2 pose() const { return {state_.x.head<2>(), state_.x(2)}; }
  Vec3 mean() const { return state_.x.head<3>(); }
  Mat3 covariance() const { return state_.P.topLeftCorner<3, 3>(); }
  // The whole state: pose and calibration (see ugv_motion_model.hpp).
  const UgvStateVec& state() const { return state_.x; }
  const UgvStateCov& state_covariance() const { return state_.P; }
  TimePoint stamp() const { return state_.t; }
  const UgvEkfCounters& counters() const { return counters_; }
  // The factor the relative poses' covariance is multiplied by (1: as reported).
  double measurement_noise_scale() const {
    return std::clamp(noise_mean_, 1.0, config_.max_measurement_noise_scale);
  }
  const UgvEkfConfig& config() const { return config_; }

 private:
  struct Step {
    TimePoint t;     // end of the step
    double v = 0.0;  // twist applied over the step
    double w = 0.0;
    UgvStateVec x = UgvStateVec::Zero();  // state at t (meaningful once initialised)
    UgvStateCov P = UgvStateCov::Zero();
  };
  // The newest history step at or before `stamp` (1-based: 0 when older than all of them).
  std::size_t step_at(TimePoint stamp) const;
  // The measurement's innovation against the state at its stamp (history step k, 1-based).
  Vec3 innovation_at(const PoseMeasurement& z, std::size_t k) const;
  Update apply(const PoseMeasurement& z, std::size_t k);
  // At the start or after a gap: whether `z` (at history step k) may be applied now (`held_`
  // confirms it; `held_` is applied first).
  bool confirmed(const PoseMeasurement& z, std::size_t k);
  // Whether two measurements close in time agree: their innovations (before the start: the
  // measurements themselves, the robot standing) within the gate of each other.
  bool agree(const PoseMeasurement& a, std::size_t ka, const PoseMeasurement& b,
             std::size_t kb) const;
  // Re-runs the prediction from history_[from] to the newest entry.
  void repropagate(std::size_t from);
  void advance(Step& cur, const Step& prev) const;  // cur from prev and cur's twist
  void clamp_calibration(UgvStateVec& x) const;

  UgvEkfConfig config_;
  bool initialized_ = false;
  int consecutive_rejections_ = 0;
  TimePoint last_applied_{};             // stamp of the newest relative pose applied
  std::optional<PoseMeasurement> held_;  // waiting for the next to confirm it
  double noise_mean_ = 1.0;              // used within [1, max]: measurement_noise_scale()
  double noise_samples_ = 0.0;
  Step state_;                          // the newest state
  RingBuffer<Step, kHistory> history_;  // past states, oldest first; back() == state_
  UgvEkfCounters counters_;
};

}  // namespace colag
