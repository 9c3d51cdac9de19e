#pragma once
// Every parameter of the UGV navigation task, with the defaults of DESIGN.md / the paper.
#include "colag/common/geometry.hpp"
#include "colag/common/map_store.hpp"
#include "colag/common/map_window.hpp"
#include "colag/common/planner.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/common/time.hpp"
#include "colag/common/ugv_ekf.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/platform/fleet_clock.hpp"
#include "colag/ugv/blocked_watch.hpp"
#include "colag/ugv/collision_predictor.hpp"
#include "colag/ugv/controller.hpp"
#include "colag/ugv/support_protocol.hpp"
#include "colag/ugv/trajectory.hpp"
#include "colag/ugv/ugv_schedule.hpp"

namespace colag::ugv {

struct UgvNavConfig {
  RobotId id = 0;
  Vec2 goal = Vec2::Zero();
  // Passed through in this order before the goal (world frame): each counts as passed once the
  // robot believes itself within via_pass_radius_m of it; it does not stop there. A goal sent
  // at run time (request_goal) replaces the rest of the route.
  StaticVector<Vec2, limits::kMaxRouteVias> via;
  double via_pass_radius_m = 1.0;
  UgvSchedule schedule;  // the loops' rates, budgets and offsets
  // Where the robot is believed to start (mission plan). Used only to call the UAV before the
  // first relative pose initialises the estimator; never fused.
  bool has_start_guess = false;
  Pose2 start_guess;
  double start_guess_sigma_m = 1.0;

  double body_radius_m = 0.25;
  UgvEkfConfig ekf;
  // The planner keeps its path clearance_m from obstacles where a detour costs less than twice
  // the length it saves (clearance_cost 1): room for the 3-sigma position uncertainty the
  // collision prediction checks (0.45 m beyond the body's 0.25 m). A path that hugged the
  // P-Map's 0.4 m inflation stopped the robot for the UAV whenever its 3 sigma passed 0.15 m.
  // The cost is scaled by how far the robot's recent 3 sigma (its largest, fading with
  // clearance_memory_s) went past that 0.15 m, up to the band's 0.3 m: a robot the UAVs fix often
  // plans the plain path (with two UAVs on dense 7 the full band only made paths longer).
  MapStoreConfig map{.clearance_m = 0.7};
  double clearance_memory_s = 20.0;
  WindowPolicy map_window;  // when the map's window moves with the robot (map_window.hpp)
  PlannerConfig planner{.clearance_cost = 1.0};
  TrajectoryLimits limits;
  ControllerConfig controller;
  PredictorConfig predictor;
  SupportConfig support;
  BlockedConfig blocked;
  platform::FleetClockConfig fleet_clock;

  double stop_time_s = 0.4;        // t_c: stop when a collision is predicted sooner
  double resume_margin_s = 0.2;    // hysteresis before driving on
  double robot_stop_time_s = 1.5;  // stop for another UGV predicted closer than this
  // Held this long by another UGV, it asks the UAV for a fix where it stands: its own
  // uncertainty is part of what keeps them apart, and a UGV parked at its goal never moves
  // away (with a narrow camera nothing else brought the UAV, and a UGV stood for good 2.6 m
  // from its goal beside another's). 0: never.
  double robot_fix_after_s = 10.0;
  // Its status says where, within this far along its planned path, the path first comes near an
  // unknown cell (UgvStatus::scout_point_m): where the UAV scouts when nothing is requested.
  // 0: never said.
  double scout_range_m = 12.0;
  Duration replan_period = std::chrono::seconds(1);
  Duration no_path_retry = std::chrono::seconds(1);
  double replan_cross_track_m = 0.5;  // off the path by more than this => replan
  // At its goal by its estimate, it has arrived only when this sure (3-sigma position, m) of
  // being there; otherwise it asks the UAV for a relative pose there. (A UGV 0.69 m off its goal
  // said "arrived" after a long leg without a relative pose.)
  double arrival_max_uncertainty_m = 0.3;
  // Encoder frames come at 50 Hz: three missing ones mean a fault. With the 20 ms control loop
  // the robot is commanded to zero within 80 ms (+ scheduling jitter) of the last frame.
  Duration odometry_timeout = std::chrono::milliseconds(60);
  Duration odometry_startup_grace = std::chrono::seconds(1);
  Duration rpe_match_tolerance = std::chrono::milliseconds(100);
  Duration max_message_age = std::chrono::seconds(2);         // older RPE / patches are ignored
  Duration max_future_skew = std::chrono::milliseconds(200);  // newer than now + this: rejected
  // Another UGV not heard from is not forgotten: it stays an obstacle whose disc grows at this
  // speed (the fastest a UGV drives) with the time since it was heard, until it is heard again
  // or the disc would cover the whole map.
  double other_ugv_max_speed_mps = 0.7;
  double other_ugv_range_m = 6.0;  // other UGVs farther than this are not planned around
  // The UAV's lists of the UGVs near us are complete within their radius, which alternates
  // (uav/nearby_relay.hpp): a UGV missing from a list is forgotten when it was last seen
  // within the radius less this margin (where the UAV would have listed it), and kept for
  // `nearby_keep` when it was farther (a list of a smaller radius says nothing of it).
  double nearby_margin_m = 1.0;
  Duration nearby_keep = std::chrono::seconds(1);
  bool use_rpe_updates = true;  // false: the ablation "RPE only initialises the EKF"
};

}  // namespace colag::ugv
