#pragma once
// The UGV navigation task: estimator, map store, planner, controller, collision predictor and
// support protocol, driven by two loops of one executor table (their timing: UgvSchedule):
//   control_loop()  50 Hz: wheel odometry -> EKF predict, RPE -> EKF update, tracking -> Drive
//   planning_loop() 10 Hz: map patches, other UGVs, (re)planning, collision prediction,
//                          support requests, UgvStatus
// Pure task code: HAL and transport interfaces only; no heap, no exceptions, no OS calls in
// step(); every malformed input is rejected and counted in health().
#include <array>
#include <cstdint>
#include <optional>

#include "colag/common/overrun_governor.hpp"
#include "colag/common/stamp_gate.hpp"
#include "colag/hal/drive.hpp"
#include "colag/hal/wheel_odometry.hpp"
#include "colag/platform/fleet_clock.hpp"
#include "colag/platform/readers.hpp"
#include "colag/ugv/blocked_watch.hpp"
#include "colag/ugv/rpe_measurement.hpp"
#include "colag/ugv/ugv_nav_config.hpp"
#include "colag/ugv/waiting.hpp"

namespace colag::ugv {

struct UgvHealth {
  std::uint64_t odometry_rejected = 0;
  std::uint64_t uav_odometry_rejected = 0;
  std::uint64_t rpe_rejected = 0;    // malformed, wrong robot, too old / from the future
  std::uint64_t rpe_unmatched = 0;   // no UAV odometry within the tolerance of its stamp
  std::uint64_t rpe_outliers = 0;    // outside the EKF gate
  std::uint64_t rpe_ignored = 0;     // ablation no-rpe: used only to initialise
  std::uint64_t unsynchronised = 0;  // UAV odometry / relative poses refused: no fleet time yet
  std::uint64_t patches_rejected = 0;
  std::uint64_t statuses_rejected = 0;
  std::uint64_t drive_errors = 0;
  std::uint64_t watchdog_trips = 0;   // wheel odometry went silent
  std::uint64_t base_faults = 0;      // the base reported a fault (each new one counted once)
  std::uint64_t uav_unavailable = 0;  // times a UAV said its flight controller left the mission
  std::uint64_t plans = 0;
  std::uint64_t plan_failures = 0;
  std::uint64_t window_moves = 0;  // the map's window moved with the robot (map_window.hpp)
  std::uint64_t support_messages = 0;
  std::uint64_t overruns = 0;  // steps of either loop over budget (real-time executor only)
  int degradation = 0;         // OverrunGovernor level: 0 = full prediction horizon
  StampCounters stamps;        // every input stream's stamp checks, summed (planning loop)

  std::uint64_t rejected_inputs() const {
    return odometry_rejected + uav_odometry_rejected + rpe_rejected + rpe_unmatched + rpe_outliers +
           patches_rejected + statuses_rejected;
  }
};

// The answer to a new goal sent at run time (request_goal).
enum class GoalResult : std::uint8_t {
  kAccepted = 0,
  kNotFinite = 1,
  kOutsideMap = 2,  // beyond limits::kMaxSiteHalf_m of the world frame's origin
  kInObstacle = 3,  // on a cell its map knows occupied
  kWrongFrame = 4,  // (from the ROS 2 bridge) not in the fleet's world frame
};
inline const char* to_string(GoalResult r) {
  switch (r) {
    case GoalResult::kAccepted:
      return "accepted";
    case GoalResult::kNotFinite:
      return "refused: not a finite position";
    case GoalResult::kOutsideMap:
      return "refused: outside the site";
    case GoalResult::kInObstacle:
      return "refused: inside an obstacle";
    case GoalResult::kWrongFrame:
      return "refused: not in frame map";
  }
  return "refused";
}

// An operator's command at run time (request_command; ROS 2 `<ns>/command`).
enum class UgvCommand : std::uint8_t {
  kPause = 1,          // stop where it is (still estimating, mapping) until kResume
  kResume = 2,         // drive on after kPause
  kAbort = 3,          // cancel the mission: stop until a new goal or kReturnToStart
  kReturnToStart = 4,  // drive back to where it was first localised
};
enum class CommandResult : std::uint8_t {
  kAccepted = 0,
  kUnknown = 1,       // not a UgvCommand
  kNotPaused = 2,     // resume without a pause
  kNoStart = 3,       // return: it has not been localised yet, so it does not know its start
  kStartRefused = 4,  // return: its start is now outside its map or inside an obstacle
  kBusy = 5,          // (from the ROS 2 bridge) more commands at once than it queues
};
inline const char* to_string(CommandResult r) {
  switch (r) {
    case CommandResult::kAccepted:
      return "accepted";
    case CommandResult::kUnknown:
      return "refused: unknown command";
    case CommandResult::kNotPaused:
      return "refused: not paused";
    case CommandResult::kNoStart:
      return "refused: not localised yet, its start is unknown";
    case CommandResult::kStartRefused:
      return "refused: its start is outside the map or in an obstacle";
    case CommandResult::kBusy:
      return "refused: too many commands at once";
  }
  return "refused";
}

class UgvNavTask {
 public:
  UgvNavTask(const UgvNavConfig& config, platform::Transport& transport,
             hal::WheelOdometry& odometry, hal::Drive& drive);
  UgvNavTask(const UgvNavTask&) = delete;
  UgvNavTask& operator=(const UgvNavTask&) = delete;

  platform::Task& control_loop() { return control_loop_; }
  platform::Task& planning_loop() { return planning_loop_; }
  // The task's rows of an executor table, timed by config().schedule: control, then planning.
  std::array<platform::TaskEntry, 2> rows(int lane = 0) {
    return {platform::row(control_loop_, config_.schedule.control, lane),
            platform::row(planning_loop_, config_.schedule.planning, lane)};
  }

  msg::UgvMode mode() const { return mode_; }
  const UgvEkf& estimator() const { return ekf_; }
  const MapStore& map() const { return map_; }
  const Trajectory& trajectory() const { return trajectory_; }
  const Prediction& prediction() const { return prediction_; }
  const UgvHealth& health() const { return health_; }
  // Why the UGV is in kFault (kNone when it is not).
  const hal::DriveHealth& base_fault() const { return base_fault_; }
  const platform::UgvFleetClock& fleet_clock() const { return fleet_; }
  TimePoint now() const { return last_control_; }  // its clock, at its last control step
  double waiting_time_s() const {                  // stood still before arrival: the parts' sum
    Duration sum{};
    for (const Duration& d : waiting_parts_)
      sum += d;
    return to_seconds(sum);
  }
  const WaitingParts& waiting_parts() const { return waiting_parts_; }     // summing to it
  const SupportCauses& support_causes() const { return support_causes_; }  // the support part's
  msg::BlockedReason blocked_reason() const { return blocked_reason_; }    // with kBlocked
  bool requesting_support() const { return support_.requesting(); }
  const UgvNavConfig& config() const { return config_; }
  // Drives to `goal` (world frame) from now on, unless it is refused: not finite, outside the
  // map, or on a cell the map knows occupied (an unknown cell is accepted: the UAV will map it).
  // An arrived UGV drives again. Call between steps, on the task's thread.
  // A new goal also ends an abort (a pause holds until kResume).
  GoalResult request_goal(const Vec2& goal);
  const Vec2& goal() const { return goal_; }
  // Pause, resume, abort, return to start (`command`: a UgvCommand's value, checked here). While
  // paused or aborted it stands (kPaused, kAborted: its waiting counts them as `operator`) and
  // asks the UAV for nothing. Call between steps, on the task's thread.
  CommandResult request_command(std::uint8_t command);
  bool paused() const { return paused_; }
  bool aborted() const { return aborted_; }
  const msg::UgvStatus& last_status() const { return last_status_; }  // as last published
  // Whether it knows of UGV `id` from the UAV's lists (and plans around it when near).
  bool knows_ugv(RobotId id) const { return id < others_.size() && others_[id].known; }

 private:
  using Loop = platform::MemberLoop<UgvNavTask>;
  struct OtherUgv {
    bool known = false;
    TimePoint heard{};     // when its status was last heard (by the UAV, which relays it)
    TimePoint listed{};    // when a list last carried it (our clock)
    msg::NearbyUgv state;  // its stamp converted to our clock
  };

  Status init(TimePoint now);
  void control_step(TimePoint now);
  void planning_step(TimePoint now);
  void on_overrun(Duration step_time);

  // control loop parts
  void read_odometry(TimePoint now);
  void read_relative_poses(TimePoint now);
  void drive(TimePoint now, double dt_s);
  // planning loop parts
  void keep_map_window();
  void read_map_patches(TimePoint now);
  void read_other_ugvs(TimePoint now);
  void collect_others(TimePoint now);
  bool replan_needed(TimePoint now) const;
  void replan(TimePoint now);
  void predict_and_request(TimePoint now);
  void publish_status(TimePoint now);
  void fill_scout_point(msg::UgvStatus& s) const;
  void publish_request(msg::CollisionInfo& ci);  // stamped in fleet time

  StampLimits stamp_limits(bool increasing) const {
    return {config_.max_future_skew, config_.max_message_age, increasing};
  }
  void sum_stamp_counters();
  msg::BlockedReason standing_reason() const;
  void track_uncertainty();       // recent_3sigma_m_, each planning step
  double three_sigma_m() const;   // the position's 3-sigma ellipse's semi-major axis
  bool sure_of_position() const;  // 3 sigma within arrival_max_uncertainty_m: may arrive
  void command(TimePoint now, double v, double omega);

  UgvNavConfig config_;
  platform::Transport& transport_;
  hal::WheelOdometry& odometry_;
  hal::Drive& drive_;
  Loop control_loop_;
  Loop planning_loop_;
  bool initialised_ = false;

  platform::QueueReader<msg::UavOdometry, 32> uav_odometry_in_;
  platform::QueueReader<msg::RelativePose, 16> rpe_in_;
  platform::QueueReader<msg::MapPatch, 8> patches_in_;
  platform::QueueReader<msg::NearbyUgvs, 4> nearby_in_;

  // Each input stream's stamp checks.
  StampGate wheel_stamps_, rpe_stamps_, patch_stamps_, nearby_stamps_;

  platform::UgvFleetClock fleet_;
  UgvEkf ekf_;
  // Each UAV of the fleet (by its id): its odometry, to place the relative poses it measures;
  // and whether its flight controller flies the mission, as its last sample said.
  struct Uav {
    StampGate stamps;
    UavOdometryHistory history;
    msg::UavFlight flight = msg::UavFlight::kInControl;
    TimePoint last_stamp = kNever;  // its last sample's (fleet time)
    bool heard = false;
  };
  std::array<Uav, limits::kMaxUavs> uavs_{};
  // No UAV heard from flies the mission (each one's flight controller failed safe, was taken
  // over or lands): no support is coming.
  bool no_uav_in_control() const;
  MapStore map_;
  Planner planner_;
  Path path_;
  Trajectory trajectory_;
  Controller controller_;
  CollisionPredictor predictor_;
  Prediction prediction_;
  msg::UgvStatus last_status_;
  Vec2 goal_ = config_.goal;                    // where it drives (request_goal changes it)
  std::size_t vias_left_ = config_.via.size();  // of config_.via, the last ones still ahead
  // Where it drives now: the next point of its route, or its goal.
  const Vec2& target() const {
    return vias_left_ > 0 ? config_.via[config_.via.size() - vias_left_] : goal_;
  }
  SupportProtocol support_;
  BlockedWatch blocked_;
  std::array<OtherUgv, limits::kMaxUgvs> others_{};
  StaticVector<OtherRobot, limits::kMaxUgvs> others_predict_;
  StaticVector<DiscObstacle, limits::kMaxUgvs> others_plan_;

  msg::UgvMode mode_ = msg::UgvMode::kWaitingForInit;
  msg::BlockedReason blocked_reason_ = msg::BlockedReason::kNone;  // set with mode_
  // Why it is in kFault (odometry silent, or the base's own fault); kNone: no fault.
  hal::DriveHealth base_fault_;
  bool faulty() const { return base_fault_.fault != msg::BaseFault::kNone; }
  msg::BaseFault drive_fault_seen_ = msg::BaseFault::kNone;  // the base's, last period
  bool stopped_for_support_ = false;
  bool awaiting_fix_ = false;  // at the goal by its estimate, not sure enough to have arrived
  bool stopped_for_robot_ = false;
  // Held by another UGV: since when (through short releases), and when last.
  bool robot_held_ = false;
  TimePoint robot_stop_since_{}, robot_held_last_{};
  bool arrived_ = false;
  bool paused_ = false;        // by its operator, until resume
  bool aborted_ = false;       // by its operator, until a new goal
  std::optional<Vec2> start_;  // where it was first localised (return to start)
  bool replan_requested_ = true;
  bool no_path_ = false;
  std::uint64_t plan_blocked_seen_ = 0;
  std::uint64_t ekf_resets_seen_ = 0;
  TimePoint started_{};
  TimePoint last_control_{};
  TimePoint last_plan_{};
  WaitingParts waiting_parts_{};
  SupportCauses support_causes_{};
  SupportCause support_cause_ = SupportCause::kUnknownGround;  // the latest (see waiting.hpp)
  double cross_track_m_ = 0.0;
  double recent_3sigma_m_ = 0.0;  // the largest 3-sigma lately (fading): the planner's clearance
  double v_cmd_ = 0.0;
  double wheel_speed_ = 0.0;  // the newest wheel odometry's twist
  double still_speed_ = 0.0;  // |v| of the last few samples
  double wheel_omega_ = 0.0;
  double omega_cmd_ = 0.0;
  UgvHealth health_;
  OverrunGovernor governor_;
};

}  // namespace colag::ugv
