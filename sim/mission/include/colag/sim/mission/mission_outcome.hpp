#pragma once
// What a simulated mission yields: the metrics as the paper defines them (Sec. V-A), per UGV
// and averaged, the host time of each task, and what the mission figure draws.
#include <cstdint>
#include <string>
#include <vector>

#include "colag/msg/ugv_status.hpp"
#include "colag/sim/mission/mission_config.hpp"

namespace colag::sim {
class SimWorld;
}

namespace colag::mission {

struct UgvOutcome {
  int id = 0;
  bool reached = false;
  bool collided = false;
  double reach_time_s = -1.0;  // -1 when it did not reach
  // Standing still before it reached (true motion under 2 cm/s and 1 deg/s), whatever the
  // reason: the paper counts only stops for t_pc < t_c; a user counts every one.
  double waiting_time_s = 0.0;
  double init_wait_s = 0.0;  // the part of it before the first relative pose
  double traj_length_m = 0.0;
  double min_clearance_m = 0.0;  // closest approach of its footprint to an obstacle or UGV
  std::uint64_t support_requests = 0;
  msg::UgvMode final_mode = msg::UgvMode::kWaitingForInit;  // what it reported last
  double blocked_s = 0.0;  // time it reported kBlocked (it gave up asking for support)
  // Why, the last time it was blocked (with final_mode kBlocked: why it is now).
  msg::BlockedReason blocked_reason = msg::BlockedReason::kNone;
  double goal_distance_m = 0.0;  // where it ended, from its goal (true position)
  std::string end;               // how it ended, in words (summarise)
};

// Host CPU time of one kind of task over the mission (summed over the robots that run it).
struct TaskTime {
  std::string name;
  std::uint64_t steps = 0;
  double total_s = 0.0;
  double longest_ms = 0.0;
};

struct MissionOutcome {
  MissionConfig config;
  std::vector<std::string> warnings;  // about the map (see map_checks.hpp)
  std::vector<TaskTime> task_times;   // in table order of first appearance
  std::vector<UgvOutcome> ugvs;
  // Averages per UGV, as in the paper (reach time over the UGVs that reached).
  double reach_time_s = 0.0;
  double waiting_time_s = 0.0;
  double max_waiting_time_s = 0.0;
  double ugv_traj_length_m = 0.0;
  double uav_traj_length_m = 0.0;
  int collisions = 0;
  bool all_reached = false;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  std::uint64_t map_patches = 0;
  std::uint64_t map_patch_bytes = 0;  // payload bytes of every patch sent
  std::uint64_t schedules = 0;
  std::uint64_t schedules_exact = 0;
  // The UAV's team filter: times a UGV became located (its mapped body forgotten), and LiDAR
  // returns kept out of the map as a live UGV's.
  std::uint64_t team_located = 0;
  std::uint64_t team_returns_dropped = 0;
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
  std::vector<Vec2> uav_path;
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
