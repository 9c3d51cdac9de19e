#pragma once
// Uncertainty-based collision prediction (paper Sec. III-C): a copy of the EKF covariance is
// propagated along the planned trajectory (dt 0.2 s) with the same motion model, and each
// k-sigma ellipse is rasterised exactly over the CP-Map (unknown = occupied). The first ellipse
// that touches a blocked cell (or another UGV's disc) is the predicted collision: its centre
// p_pc, the time t_pc to reach it, and the support point p_ps backed off along the planned
// velocity (where the UAV's sensors cover the danger).
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

// Another UGV as the predictor sees it: a disc around its estimated position.
struct OtherRobot {
  Vec2 p = Vec2::Zero();
  double radius_m = 0.0;  // both bodies + its 3-sigma extent + margin
};

enum class CollisionKind : std::uint8_t { kNone, kMap, kRobot };

struct Prediction {
  CollisionKind kind = CollisionKind::kNone;
  Vec2 point = Vec2::Zero();                                    // p_pc
  Vec2 support_point = Vec2::Zero();                            // p_ps
  double time_s = 0.0;                                          // t_pc from now
  StaticVector<Ellipse, limits::kMaxPredictionSteps> ellipses;  // every ellipse checked
};

class CollisionPredictor {
 public:
  CollisionPredictor(const PredictorConfig& config, const OdometryNoise& noise)
      : config_(config), noise_(noise) {}

  // `pose`, `covariance`: the EKF now; the robot is at trajectory sample `progress`.
  void predict(const Pose2& pose, const Mat3& covariance, const Trajectory& trajectory,
               std::size_t progress, const MapStore& map, std::span<const OtherRobot> others,
               Prediction& out) const;

  const PredictorConfig& config() const { return config_; }

 private:
  // Which obstacle, if any, the ellipse touches.
  CollisionKind check(const Ellipse& e, const MapStore& map,
                      std::span<const OtherRobot> others) const;

  PredictorConfig config_;
  OdometryNoise noise_;
};

}  // namespace colag::ugv
