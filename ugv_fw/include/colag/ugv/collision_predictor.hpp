#pragma once
// Uncertainty-based collision prediction (paper Sec. III-C): a copy of the EKF covariance is
// propagated along the planned trajectory (dt 0.2 s) with the same motion model (the whole
// state's: an uncertain wheel calibration makes the error grow with the distance), and each
// k-sigma ellipse is rasterised exactly over the CP-Map (unknown = occupied). The first ellipse
// that touches a blocked cell (or another UGV's disc) is the predicted collision: its centre
// p_pc, the time t_pc to reach it, and the support point p_ps backed off along the planned
// velocity (where the UAV's sensors cover the danger).
// A collision means getting into danger, not being near it already (otherwise a robot that
// braked just inside an inflated area, a box revealed where unknown was, could never move
// again, not even away): the blocked cells the ellipse overlaps now are excused; touching any
// other cell blocked by unknown is a collision (only the UAV can clear it); near a known
// obstacle, a step is a collision only if its worst case (centre distance minus the ellipse's
// semi-major axis) comes closer to an occupied cell than the robot is now, or than the
// inflation radius when it is outside it.
#include <algorithm>
#include <cstdint>
#include <span>

#include "colag/common/ellipse.hpp"
#include "colag/common/map_store.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/common/ugv_motion_model.hpp"
#include "colag/ugv/trajectory.hpp"

namespace colag::ugv {

struct PredictorConfig {
  double dt_s = 0.2;
  double horizon_m = 2.0;  // straight-line distance from the start
  double max_horizon_s = 30.0;
  double k_sigma = 3.0;
  double support_back_off_m = 2.0;
  bool use_uncertainty = true;  // false: the ablation "collision check on the mean only"
};

// Another UGV as the predictor sees it: a disc around its estimated position, moving on at its
// reported velocity (a disc that stood still hid a UGV cutting across from a converging lane
// until the bodies touched).
struct OtherRobot {
  Vec2 p = Vec2::Zero();
  double radius_m = 0.0;  // both bodies + its 3-sigma extent + margin
  Vec2 v = Vec2::Zero();  // m/s, world frame
};

enum class CollisionKind : std::uint8_t { kNone, kMap, kRobot };
// Why a map collision was predicted: the ellipse meets ground not known yet (or leaves the map),
// comes closer to a known obstacle than the robot's worst case is now, or the ellipse now is
// already too uncertain for the obstacles it overlaps.
enum class MapCause : std::uint8_t { kNone, kUnknownGround, kNearObstacle, kUncertainNow };

struct Prediction {
  CollisionKind kind = CollisionKind::kNone;
  MapCause cause = MapCause::kNone;                             // for kMap
  Vec2 point = Vec2::Zero();                                    // p_pc
  Vec2 support_point = Vec2::Zero();                            // p_ps
  double time_s = 0.0;                                          // t_pc from now
  StaticVector<Ellipse, limits::kMaxPredictionSteps> ellipses;  // every ellipse checked
};

class CollisionPredictor {
 public:
  // `frame_walk_m_per_sqrt_s`: the estimator's (UgvEkfConfig): the frame wanders along the
  // horizon as it does now.
  CollisionPredictor(const PredictorConfig& config, const OdometryNoise& noise,
                     const OdometryCalibrationModel& calibration = {},
                     double frame_walk_m_per_sqrt_s = 0.0)
      : config_(config),
        noise_(noise),
        walk_(calibration.walk()),
        frame_walk_m_per_sqrt_s_(frame_walk_m_per_sqrt_s) {}

  // `state`, `covariance`: the EKF now (pose and calibration); the robot is at trajectory
  // sample `progress`.
  void predict(const UgvStateVec& state, const UgvStateCov& covariance,
               const Trajectory& trajectory, std::size_t progress, const MapStore& map,
               std::span<const OtherRobot> others, Prediction& out);
  // A pose whose odometry calibration is known exactly.
  void predict_pose(const Pose2& pose, const Mat3& covariance, const Trajectory& trajectory,
                    std::size_t progress, const MapStore& map, std::span<const OtherRobot> others,
                    Prediction& out);

  const PredictorConfig& config() const { return config_; }
  // Shortens the look-ahead (distance and time) to this share of the configured one: the
  // planning loop's way to shed work when it overruns. Clamped to [0.5, 1]: half of the default
  // 2 m still covers the robot stop distance (1.5 s at 0.5 m/s).
  void set_horizon_scale(double scale) { horizon_scale_ = std::clamp(scale, 0.5, 1.0); }
  double horizon_scale() const { return horizon_scale_; }

 private:
  // Which obstacle, if any, the ellipse touches: a blocked cell not in excused_ that is near
  // unknown, or near occupied with the ellipse closer than `closest_allowed_m` to it; or another
  // robot's disc, entered (or, already overlapping now, entered deeper than now).
  // `cause`: why, for a kMap.
  CollisionKind check(const Ellipse& e, double t, const MapStore& map,
                      std::span<const OtherRobot> others, double closest_allowed_m,
                      MapCause& cause) const;

  static constexpr std::size_t kMaxExcused = 8192;
  static constexpr double kDistanceSearch_m = 1.0;
  PredictorConfig config_;
  OdometryNoise noise_;
  CalibrationWalk walk_;
  double frame_walk_m_per_sqrt_s_ = 0.0;
  double horizon_scale_ = 1.0;
  // Blocked cells under the current ellipse (ascending indices): touching them is not news.
  StaticVector<std::uint32_t, kMaxExcused> excused_;
  // Per other robot: how far the ellipse now is outside its disc (< 0: overlapping already).
  // As with the map, an overlap that is there now is not news: getting deeper is.
  StaticVector<double, limits::kMaxUgvs> robot_floor_;
};

}  // namespace colag::ugv
