#pragma once
// The UGV's pose estimator (paper Sec. III-A): an EKF on (x, y, yaw) predicted with wheel
// odometry and updated with the UGV pose observed by the UAV (UAV odometry composed with the
// relative pose). Differences from a textbook EKF, all for robustness on a real robot:
// - measurements are applied at their own time stamp: the filter keeps ~1 s of odometry
//   history, updates the state of that time and re-propagates to now (RPE arrives late);
// - a chi-square gate on the Mahalanobis distance rejects outliers; after many consecutive
//   rejections the filter re-initialises from the measurement (it had diverged);
// - the covariance update uses the Joseph form (stays symmetric positive definite).
#include <cstdint>

#include "colag/common/geometry.hpp"
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
  double gate_chi2 = 16.27;         // chi-square, 3 dof, 99.9 %: one false reject in 1000
  int reset_after_rejections = 25;  // consecutive gate rejections => re-initialise
};

struct UgvEkfCounters {
  std::uint64_t predictions = 0;
  std::uint64_t updates = 0;
  std::uint64_t rejected_gate = 0;      // outliers
  std::uint64_t rejected_stale = 0;     // older than the odometry history
  std::uint64_t rejected_invalid = 0;   // NaN/Inf, non-positive covariance
  std::uint64_t rejected_odometry = 0;  // odometry out of order or not finite
  std::uint64_t resets = 0;
};

class UgvEkf {
 public:
  static constexpr std::size_t kHistory = 64;  // odometry steps kept (1.28 s at 50 Hz)

  enum class Update : std::uint8_t {
    kInitialized,
    kApplied,
    kRejectedGate,
    kRejectedStale,
    kRejectedInvalid,
    kReset
  };

  explicit UgvEkf(const UgvEkfConfig& config = {}) : config_(config) {}

  bool initialized() const { return initialized_; }
  // One wheel-odometry sample: the twist measured over (previous stamp, stamp].
  Status predict(TimePoint stamp, double v_mps, double omega_radps);
  Update update(const PoseMeasurement& z);
  void reset();

  Pose2 pose() const { return {state_.x.head<2>(), state_.x.z()}; }
  const Vec3& mean() const { return state_.x; }
  const Mat3& covariance() const { return state_.P; }
  TimePoint stamp() const { return state_.t; }
  const UgvEkfCounters& counters() const { return counters_; }
  const UgvEkfConfig& config() const { return config_; }

 private:
  struct Step {
    TimePoint t;     // end of the step
    double v = 0.0;  // twist applied over the step
    double w = 0.0;
    Vec3 x = Vec3::Zero();  // state at t (meaningful once initialised)
    Mat3 P = Mat3::Zero();
  };
  // Re-runs the prediction from history_[from] to the newest entry.
  void repropagate(std::size_t from);

  UgvEkfConfig config_;
  bool initialized_ = false;
  int consecutive_rejections_ = 0;
  Step state_;                          // the newest state
  RingBuffer<Step, kHistory> history_;  // past states, oldest first; back() == state_
  UgvEkfCounters counters_;
};

}  // namespace colag
