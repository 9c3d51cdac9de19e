#include <gtest/gtest.h>

#include <memory>

#include "colag/ugv/collision_predictor.hpp"
#include "map_fixtures.hpp"

using namespace colag;
using namespace colag::ugv;

namespace {

// Straight line along +x at constant 0.5 m/s from (0, 0) (the speed profile starts at v_max
// and brakes only at x = 10).
Trajectory straight_trajectory() {
  Path path;
  (void)path.waypoints.push_back(Vec2(0.0, 0.05));
  (void)path.waypoints.push_back(Vec2(10.0, 0.05));
  Trajectory t;
  EXPECT_TRUE(t.build(path, 0.5, {}));
  return t;
}

// Free map with an unknown block from x = 3.0 on.
std::unique_ptr<MapStore> map_with_unknown_ahead() {
  auto map = std::make_unique<MapStore>();
  EXPECT_TRUE(test::fill_map(*map, -3, -3, 3.0, 3, [](const Vec2&) { return CellState::kFree; }));
  return map;
}

OdometryNoise forward_noise_only() {
  OdometryNoise n;
  n.sigma_omega_radps = 0.0;  // no heading noise: the ellipses grow along x only
  n.sigma_v_fraction = n.sigma_omega_fraction = 0.0;
  return n;
}

}  // namespace

TEST(CollisionPredictor, NothingOnAFreeMapWithZeroCovariance) {
  auto map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*map, -3, -3, 13, 3, [](const Vec2&) { return CellState::kFree; }));
  PredictorConfig cfg;
  cfg.horizon_m = 20.0;
  CollisionPredictor predictor(cfg, forward_noise_only());
  Prediction p;
  const Trajectory traj = straight_trajectory();
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Zero(), traj, 0, *map, {}, p);
  EXPECT_EQ(p.kind, CollisionKind::kNone);
  EXPECT_GT(p.ellipses.size(), 40u);  // it did look all the way to the end
}

TEST(CollisionPredictor, MeanOnlyHitsWhereTheInflatedUnknownBegins) {
  auto map = map_with_unknown_ahead();
  // Unknown from x = 3.0, inflated by 0.25 m (square to square): cells from [2.7, 2.8) on.
  ASSERT_FALSE(map->predict_blocked(Vec2(2.65, 0.05)));
  ASSERT_TRUE(map->predict_blocked(Vec2(2.75, 0.05)));
  PredictorConfig cfg;
  cfg.horizon_m = 10.0;
  cfg.use_uncertainty = false;
  CollisionPredictor predictor(cfg, forward_noise_only());
  Prediction p;
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Identity(), straight_trajectory(), 0, *map, {},
                         p);
  ASSERT_EQ(p.kind, CollisionKind::kMap);
  EXPECT_EQ(p.cause, MapCause::kUnknownGround);
  // At 0.5 m/s the centre reaches x = 2.7 at t = 5.4 s (a multiple of the 0.2 s step).
  EXPECT_NEAR(p.time_s, 5.4, 1e-9);
  EXPECT_NEAR(p.point.x(), 2.7, 1e-6);
  EXPECT_NEAR(p.support_point.x(), 0.7, 1e-6);  // 2 m back along the planned velocity
  EXPECT_NEAR(p.support_point.y(), 0.05, 1e-6);
}

TEST(CollisionPredictor, ThreeSigmaEllipseHitsEarlierAsHandCalculated) {
  auto map = map_with_unknown_ahead();
  PredictorConfig cfg;
  cfg.horizon_m = 10.0;
  const OdometryNoise noise = forward_noise_only();
  CollisionPredictor predictor(cfg, noise);
  Prediction p;
  Mat3 P = Mat3::Zero();
  P(0, 0) = P(1, 1) = 0.01;  // sigma 0.1 m
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, P, straight_trajectory(), 0, *map, {}, p);
  ASSERT_EQ(p.kind, CollisionKind::kMap);
  // After k steps of 0.2 s, var_x = 0.01 + k * sigma_v^2 * 0.2^2. The ellipse's right end
  // x + 3 sigma_x reaches the blocked cells at 2.7 for the first k with 0.1 k + 3 sigma >= 2.7.
  int k = 0;
  for (;; ++k) {
    const double sx = std::sqrt(0.01 + k * noise.sigma_v_mps * noise.sigma_v_mps * 0.04);
    if (0.1 * k + 3 * sx >= 2.7) break;
  }
  EXPECT_EQ(k, 24);
  EXPECT_NEAR(p.time_s, 0.2 * k, 1e-9);
  EXPECT_NEAR(p.point.x(), 0.1 * k, 1e-6);
  // The covariance grew along the way, as in the EKF.
  EXPECT_GT(p.ellipses.back().M(0, 0), p.ellipses.front().M(0, 0));
}

TEST(CollisionPredictor, AnotherRobotAheadIsARobotConflictNotAMapOne) {
  auto map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*map, -3, -3, 13, 3, [](const Vec2&) { return CellState::kFree; }));
  PredictorConfig cfg;
  cfg.horizon_m = 10.0;
  CollisionPredictor predictor(cfg, forward_noise_only());
  const OtherRobot other{Vec2(4.0, 0.0), 0.75};
  Prediction p;
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Zero(), straight_trajectory(), 0, *map,
                         {&other, 1}, p);
  ASSERT_EQ(p.kind, CollisionKind::kRobot);
  EXPECT_NEAR(p.point.x(), 3.3, 0.11);  // where the discs first overlap
}

TEST(CollisionPredictor, AnotherRobotCuttingAcrossIsFollowedAlongItsVelocity) {
  auto map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*map, -3, -3, 13, 3, [](const Vec2&) { return CellState::kFree; }));
  PredictorConfig cfg;
  cfg.horizon_m = 10.0;
  CollisionPredictor predictor(cfg, forward_noise_only());
  Prediction p;
  // 2 m to the side of our path: standing there it is no danger; driving north at our speed
  // it reaches our path where we do, after about 4 s; driving south it never does.
  for (const double vy : {0.0, 0.5, -0.5}) {
    const OtherRobot other{Vec2(2.0, -2.0), 0.55, Vec2(0.0, vy)};
    predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Zero(), straight_trajectory(), 0, *map,
                           {&other, 1}, p);
    if (vy > 0.0) {
      ASSERT_EQ(p.kind, CollisionKind::kRobot);
      EXPECT_NEAR(p.point.x(), 2.0, 0.6);
      EXPECT_NEAR(p.time_s, 4.0, 1.3);
    } else {
      EXPECT_EQ(p.kind, CollisionKind::kNone) << vy;
    }
  }
}

TEST(CollisionPredictor, GoingFurtherIntoUnknownIsACollisionAtTheFirstStep) {
  // The robot's ellipse already touches the inflated unknown: that is excused (it is there),
  // but the very next step touches new unknown-blocked cells.
  auto map = map_with_unknown_ahead();
  CollisionPredictor predictor(PredictorConfig{}, forward_noise_only());
  Prediction p;
  predictor.predict_pose({Vec2(2.75, 0.05), 0.0}, Mat3::Zero(), straight_trajectory(), 27, *map, {},
                         p);
  ASSERT_EQ(p.kind, CollisionKind::kMap);
  EXPECT_NEAR(p.time_s, 0.2, 1e-9);  // with the 0.2 s step subtracted: stop now
}

TEST(CollisionPredictor, ARobotAlreadyInsideTheInflationMayLeaveButNotGoCloser) {
  // A box at x in [3.0, 3.5]; the robot's centre is at x = 2.82, inside the box's 0.25 m CP
  // inflation (it braked there while the box was still unknown): physically 0.07 m clear of the
  // cell edge (its body is narrower than the inflation's worst case of cell quantisation).
  auto map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*map, -3, -3, 9, 3, [](const Vec2& p) {
    return p.x() > 3.0 && p.x() < 3.5 && std::abs(p.y()) < 1.0 ? CellState::kOccupied
                                                               : CellState::kFree;
  }));
  ASSERT_TRUE(map->predict_blocked(Vec2(2.82, 0.05)));
  PredictorConfig cfg;
  cfg.horizon_m = 3.0;
  CollisionPredictor predictor(cfg, forward_noise_only());
  Prediction p;
  const auto line = [](const Vec2& a, const Vec2& b) {
    Path path;
    (void)path.waypoints.push_back(a);
    (void)path.waypoints.push_back(b);
    Trajectory t;
    EXPECT_TRUE(t.build(path, 0.0, {}));
    return t;
  };
  const Vec2 here(2.82, 0.05);
  predictor.predict_pose({here, M_PI}, Mat3::Identity() * 1e-4, line(here, Vec2(-1.0, 0.05)), 0,
                         *map, {}, p);
  EXPECT_EQ(p.kind, CollisionKind::kNone) << "backing away from the box must be allowed";
  predictor.predict_pose({here, 0.0}, Mat3::Identity() * 1e-4, line(here, Vec2(5.0, 0.05)), 0, *map,
                         {}, p);
  ASSERT_EQ(p.kind, CollisionKind::kMap) << "driving towards it must not be";
  EXPECT_EQ(p.cause, MapCause::kNearObstacle);
  EXPECT_LE(p.time_s, 0.6);
  // Sliding along the box face while edging away is allowed (exactly sideways is not: the
  // ellipse grows, so its worst case comes closer); angling in is not.
  predictor.predict_pose({here, M_PI / 2}, Mat3::Identity() * 1e-4, line(here, Vec2(2.62, 0.9)), 0,
                         *map, {}, p);
  EXPECT_EQ(p.kind, CollisionKind::kNone);
  predictor.predict_pose({here, 1.2}, Mat3::Identity() * 1e-4, line(here, Vec2(3.1, 0.9)), 0, *map,
                         {}, p);
  EXPECT_EQ(p.kind, CollisionKind::kMap);
}

// Issue 19.5: the robot is not exactly on its trajectory (out of the path, ahead of its
// schedule) and the controller takes that back in its own time. A wall from x = 1 m on, its
// face at y = 0.6: on the path (y = 0.05) the robot passes 0.55 m from it; 0.33 m off the
// path towards it, it would pass 0.22 m from it, closer than its radius: that must be predicted
// although the trajectory's samples are clear.
TEST(CollisionPredictor, ARobotOffItsTrajectoryIsCheckedWhereItIsNotWhereItShouldBe) {
  auto map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*map, -3, -3, 13, 3, [](const Vec2& p) {
    return p.y() > 0.6 && p.y() < 1.0 && p.x() > 1.0 && p.x() < 4.0 ? CellState::kOccupied
                                                                    : CellState::kFree;
  }));
  PredictorConfig cfg;
  cfg.horizon_m = 5.0;
  CollisionPredictor predictor(cfg, OdometryNoise{0.0, 0.0, 0.0, 0.0});  // point ellipses
  Prediction p;
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Zero(), straight_trajectory(), 0, *map, {}, p);
  EXPECT_EQ(p.kind, CollisionKind::kNone) << "on its path";
  predictor.predict_pose({Vec2(0, 0.38), 0.0}, Mat3::Zero(), straight_trajectory(), 0, *map, {}, p);
  ASSERT_EQ(p.kind, CollisionKind::kMap) << "0.33 m off its path towards the wall";
  EXPECT_NEAR(p.point.x(), 1.0, 0.15);  // where the wall begins
}

// Issue 19.1: already overlapping another robot's disc (its uncertainty is large: it is not
// localised yet) is not a collision; moving away is allowed, moving closer is not.
TEST(CollisionPredictor, InsideAnotherRobotsDiscItMayLeaveButNotGoCloser) {
  auto map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*map, -6, -3, 13, 3, [](const Vec2&) { return CellState::kFree; }));
  PredictorConfig cfg;
  cfg.horizon_m = 3.0;
  CollisionPredictor predictor(cfg, forward_noise_only());
  const OtherRobot other{Vec2(-1.5, 0.05), 2.5};  // we stand 1.5 m from its centre
  Prediction p;
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Zero(), straight_trajectory(), 0, *map,
                         {&other, 1}, p);
  EXPECT_EQ(p.kind, CollisionKind::kNone) << "driving away from it";
  Path back;
  (void)back.waypoints.push_back(Vec2(0.0, 0.05));
  (void)back.waypoints.push_back(Vec2(-5.0, 0.05));
  Trajectory towards;
  ASSERT_TRUE(towards.build(back, 0.5, {}));
  predictor.predict_pose({Vec2(0, 0.05), M_PI}, Mat3::Zero(), towards, 0, *map, {&other, 1}, p);
  EXPECT_EQ(p.kind, CollisionKind::kRobot) << "driving towards it";
}

// A UGV long without a relative pose: its 3-sigma ellipse (1.2 m) already reaches into a wall
// beside its path. Edging away from the wall, each step is "no closer" by its estimate, yet the
// estimate can be 0.75 m off: it must stop and ask for support, not drive on beside the wall.
// With a small ellipse the same path is clear.
TEST(CollisionPredictor, AnEllipseReachingIntoAWallNowMayNotDriveOnBesideIt) {
  auto map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*map, -3, -3, 13, 3, [](const Vec2& p) {
    return p.y() > 0.8 && p.y() < 1.2 && p.x() > -2.0 && p.x() < 8.0 ? CellState::kOccupied
                                                                     : CellState::kFree;
  }));
  Path path;
  (void)path.waypoints.push_back(Vec2(0.0, 0.05));
  (void)path.waypoints.push_back(Vec2(10.0, -0.5));  // away from the wall, slowly
  Trajectory away;
  ASSERT_TRUE(away.build(path, 0.5, {}));
  PredictorConfig cfg;
  cfg.horizon_m = 3.0;
  OdometryCalibrationModel known;
  known.estimate = false;
  // The ellipses keep their size: each step, the worst case is a little further from the wall.
  CollisionPredictor predictor(cfg, OdometryNoise{0.0, 0.0, 0.0, 0.0}, known);
  Prediction p;
  predictor.predict_pose({Vec2(0, 0.05), away[0].yaw_rad}, Mat3(Vec3(0.16, 0.16, 0.0).asDiagonal()),
                         away, 0, *map, {}, p);
  ASSERT_EQ(p.kind, CollisionKind::kMap);
  EXPECT_LE(p.time_s, 0.4);
  predictor.predict_pose({Vec2(0, 0.05), away[0].yaw_rad},
                         Mat3(Vec3(0.0025, 0.0025, 0.0).asDiagonal()), away, 0, *map, {}, p);
  EXPECT_EQ(p.kind, CollisionKind::kNone);
}

// The UAV's odometry frame wanders along the horizon as it does now (the estimator's frame
// walk): with exact wheels and a known pose, the ellipse k steps ahead has variance walk^2 t.
// Why a UGV calls the UAV (the waiting's support part is reported by cause): ground not known
// yet, a known obstacle its growing ellipse would come closer to, or an ellipse that already
// overlaps more blocked cells than the predictor can excuse.
TEST(CollisionPredictor, SaysWhyTheMapBlocksTheWay) {
  PredictorConfig cfg;
  cfg.horizon_m = 10.0;
  CollisionPredictor predictor(cfg, forward_noise_only());
  Prediction p;
  auto unknown = map_with_unknown_ahead();
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Identity() * 1e-4, straight_trajectory(), 0,
                         *unknown, {}, p);
  ASSERT_EQ(p.kind, CollisionKind::kMap);
  EXPECT_EQ(p.cause, MapCause::kUnknownGround);
  // Sigma 3 m now: its 9 m ellipse covers thousands of blocked cells of the unknown ground.
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Identity() * 9.0, straight_trajectory(), 0,
                         *unknown, {}, p);
  ASSERT_EQ(p.kind, CollisionKind::kMap);
  EXPECT_EQ(p.cause, MapCause::kUncertainNow);
  EXPECT_EQ(p.time_s, 0.0);
  // Known ground, a box beside the path at y = 0.7: exact, the robot passes it; with sigma
  // 0.1 m growing along the way, its worst case comes closer to the box than now.
  auto box = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*box, -3, -3, 13, 3, [](const Vec2& q) {
    return q.x() > 3.0 && q.x() < 3.5 && q.y() > 0.7 && q.y() < 1.2 ? CellState::kOccupied
                                                                    : CellState::kFree;
  }));
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Zero(), straight_trajectory(), 0, *box, {}, p);
  EXPECT_EQ(p.kind, CollisionKind::kNone);
  EXPECT_EQ(p.cause, MapCause::kNone);
  predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Identity() * 0.01, straight_trajectory(), 0,
                         *box, {}, p);
  ASSERT_EQ(p.kind, CollisionKind::kMap);
  EXPECT_EQ(p.cause, MapCause::kNearObstacle);
}

TEST(CollisionPredictor, TheFramesWanderGrowsTheEllipsesAhead) {
  auto map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*map, -3, -3, 13, 3, [](const Vec2&) { return CellState::kFree; }));
  PredictorConfig cfg;
  cfg.horizon_m = 3.0;
  OdometryCalibrationModel known;
  known.estimate = false;
  const double walk = 0.05;
  for (const double w : {0.0, walk}) {
    CollisionPredictor predictor(cfg, OdometryNoise{0.0, 0.0, 0.0, 0.0}, known, w);
    Prediction p;
    predictor.predict_pose({Vec2(0, 0.05), 0.0}, Mat3::Zero(), straight_trajectory(), 0, *map, {},
                           p);
    ASSERT_EQ(p.kind, CollisionKind::kNone);
    ASSERT_GT(p.ellipses.size(), 10u);
    // ellipses[0] is now; ellipses[k] is k steps of 0.2 s ahead. M = 3^2 x covariance.
    for (std::size_t k = 0; k < p.ellipses.size(); ++k) {
      const double var = w * w * 0.2 * static_cast<double>(k);
      EXPECT_NEAR(p.ellipses[k].M(0, 0), 9.0 * var, 1e-12) << k;
      EXPECT_NEAR(p.ellipses[k].M(1, 1), 9.0 * var, 1e-12) << k;
    }
  }
}
