#pragma once
// What a simulated mission yields: the metrics as the paper defines them (Sec. V-A), per UGV
// and averaged, the host time of each task, and what the mission figure draws.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "colag/common/ugv_motion_model.hpp"
#include "colag/msg/topics.hpp"
#include "colag/msg/ugv_status.hpp"
#include "colag/sim/mission/mission_config.hpp"
#include "colag/ugv/waiting.hpp"

namespace colag::sim {
class SimWorld;
}

namespace colag::mission {

struct UgvOutcome {
  int id = 0;
  bool reached = false;
  bool collided = false;
  double reach_time_s = -1.0;  // -1 when it did not reach
  // Standing still before it reached, by the ground truth (under 0.05 m/s), whatever the reason:
  // the paper counts only stops for t_pc < t_c; a user counts every one.
  double stopped_s = 0.0;
  int stops = 0;  // times it came to a stand
  // The firmware's own account of its stops: the parts (support, other_ugv, no_path, startup,
  // fault; see ugv/waiting.hpp) and their sum. It should match stopped_s to about a control
  // period per stop (the robot brakes and starts within one).
  double waiting_time_s = 0.0;
  std::array<double, ugv::kWaitParts> waiting_parts{};
  // The support part by what the UGV called the UAV for (see ugv/waiting.hpp), summing to it.
  std::array<double, ugv::kSupportCauses> support_causes{};
  // Mean normalised estimation error squared of its (x, y, yaw) estimate against the truth,
  // sampled every 100 ms from its first relative pose to its arrival: 3 when the estimator's
  // covariance is honest, far more when it is over-confident.
  double nees_mean = 0.0;
  std::uint64_t nees_samples = 0;
  // The wheel-odometry calibration its estimator learnt (scale, turn_scale, drift_per_m,
  // drift_per_s, slip; see ugv_motion_model.hpp), its 1-sigma, and what the simulated wheels
  // have.
  std::array<double, kCalibrationDim> calibration{};
  std::array<double, kCalibrationDim> calibration_sigma{};
  std::array<double, kCalibrationDim> calibration_true{};
  // Fleet time (see platform/fleet_clock.hpp): the UAV clock's steps it followed, and the error
  // bound it reported at the end (< 0: not synchronised).
  std::uint64_t clock_steps = 0;
  double clock_error_s = -1.0;
  double traj_length_m = 0.0;
  double min_clearance_m = 0.0;  // closest approach of its footprint to an obstacle or UGV
  std::uint64_t support_requests = 0;
  // What the network carried to it (CDR bytes of every sample it receives, msg::wire_bytes;
  // RTPS/UDP headers not included), per second of the mission.
  double bytes_in_per_s = 0.0;
  std::array<double, msg::kTopicCount> bytes_in_by_topic_per_s{};  // the same, by msg::Topic
  msg::UgvMode final_mode = msg::UgvMode::kWaitingForInit;         // what it reported last
  double blocked_s = 0.0;  // time it reported kBlocked (it gave up asking for support)
  // Why, the last time it was blocked (with final_mode kBlocked: why it is now).
  msg::BlockedReason blocked_reason = msg::BlockedReason::kNone;
  double goal_distance_m = 0.0;  // where it ended, from its goal (true position)
  // Its first collision (collided only): when (mission time), where (true position), with what
  // (-1 an obstacle, else the other UGV's id).
  double collided_at_s = -1.0;
  Vec2 collided_where = Vec2::Zero();
  int collided_with = -1;
  std::string end;  // how it ended, in words (summarise)
};

// Host CPU time of one kind of task over the mission (summed over the robots that run it).
struct TaskTime {
  std::string name;
  std::uint64_t steps = 0;
  double total_s = 0.0;
  double longest_ms = 0.0;
};

// With FaultConfig::base_fault_at_s: how UGV 0 and its firmware answered its base's fault.
struct BaseFaultOutcome {
  bool injected = false;
  double firmware_fault_after_s = -1.0;  // until its firmware said kFault (< 0: never)
  double still_after_s = -1.0;           // until its wheels stood (< 0: never)
  double max_speed_after_still = 0.0;    // m/s: it must not move again
};

struct MissionOutcome {
  MissionConfig config;
  std::vector<std::string> warnings;  // about the map (see map_checks.hpp)
  std::vector<TaskTime> task_times;   // in table order of first appearance
  std::vector<UgvOutcome> ugvs;
  // Averages per UGV, as in the paper (reach time over the UGVs that reached; those that did not
  // are missing from it, and counted). Waiting is what a user sees: each UGV's stopped_s.
  double reach_time_s = 0.0;
  int reach_missing = 0;
  double waiting_time_s = 0.0;
  double max_waiting_time_s = 0.0;
  std::array<double, ugv::kSupportCauses> support_causes_s{};  // mean per UGV, by cause
  double nees_mean = 0.0;               // the mean over the UGVs of their nees_mean
  double bytes_in_per_ugv_per_s = 0.0;  // the mean over the UGVs of their bytes_in_per_s
  std::array<double, msg::kTopicCount> bytes_in_per_ugv_by_topic_per_s{};  // the same, by topic
  double uav_bytes_in_per_s = 0.0;
  double uav_bytes_out_per_s = 0.0;
  double ugv_traj_length_m = 0.0;
  double uav_traj_length_m = 0.0;
  // With several UAVs: the closest two came to each other (3-D, true positions, sampled every
  // 100 ms once both were airborne; -1 with one UAV).
  double uav_min_separation_m = -1.0;
  int collisions = 0;
  bool all_reached = false;
  // The mission ended at config.max_time_s with a UGV still short of its goal (neither reached
  // nor collided): more time, not the firmware, might have brought it there.
  bool time_limit_reached = false;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  std::uint64_t map_patches = 0;
  std::uint64_t map_patch_bytes = 0;  // payload bytes of every patch sent
  std::uint64_t schedules = 0;
  std::uint64_t schedules_exact = 0;
  std::uint32_t plan_age_max = 0;  // most scheduling steps one plan stood unchanged
  // The UAV's time by what it did (after its first odometry): nothing to do or leading a UGV
  // (idle), flying to a support point (transit), circling one (hover), scouting; and the
  // scouting points it left unmapped (scout_timeout).
  double uav_idle_s = 0.0, uav_transit_s = 0.0, uav_hover_s = 0.0, uav_scout_s = 0.0;
  std::uint64_t scout_timeouts = 0;
  // The UAV's team filter: times a UGV became located (its mapped body forgotten), and LiDAR
  // returns kept out of the map as a live UGV's.
  std::uint64_t team_located = 0;
  std::uint64_t team_returns_dropped = 0;
  BaseFaultOutcome base_fault;
};

// What the mission figure draws.
struct MissionTrace {
  struct Sample {
    double t_s;
    Vec2 truth, estimate;
    bool initialised;
  };
  struct EllipseMark {
    Vec2 centre;
    Mat2 covariance;
  };
  struct SupportMark {
    int ugv;
    Vec2 point;
  };
  sim::BoxWorld world;
  std::vector<std::vector<Sample>> ugv_paths;
  std::vector<std::vector<EllipseMark>> ugv_ellipses;
  std::vector<Vec2> goals;
  std::vector<std::vector<Vec2>> vias;       // each UGV's route points before its goal
  std::vector<std::vector<Vec2>> uav_paths;  // each UAV's
  std::vector<SupportMark> support_points;
  struct Stop {
    int ugv;
    double from_s, to_s;
    Vec2 where;
    msg::UgvMode why;  // the mode it reported (never kDriving nor kArrived)
    msg::BlockedReason blocked;
  };
  std::vector<Stop> stops;
  std::vector<Vec2> collisions;
  std::vector<Vec2> unknown_cells;  // ground cells the UAV never saw (0.1 m), at the end
};

// Why a UGV stands, in words ("waiting for support", "blocked: no path to its goal").
std::string standing_reason(msg::UgvMode mode, msg::BlockedReason blocked);

// Completes an outcome whose UGVs have their id, reached, reach time, waiting time, support
// requests and final mode set: the ground truth from `world` (path length, clearance,
// collisions, distance to the goal), how each UGV ended, and the paper's averages. Shared by
// colag_sim's missions and colag_world (SITL).
void summarise(const sim::SimWorld& world, MissionOutcome& out);

std::string to_json(const MissionOutcome& outcome, bool include_wall_time = true);

// Exit code of a program that flew a mission: 0 every UGV reached its goal and nothing collided,
// 1 otherwise.
inline int exit_code(const MissionOutcome& o) {
  return o.all_reached && o.collisions == 0 ? 0 : 1;
}

}  // namespace colag::mission
