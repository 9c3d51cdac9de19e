#pragma once
// A simulated ColAG mission on the host: the real UavSupervisorTask and UgvNavTasks, behind the
// real CAN drivers, against the simulated world, over the loopback transport, under the
// lock-step executor. Same configuration and seed => the same outcome, bit for bit (only the
// wall-clock figures differ). Metrics as the paper defines them (Sec. V-A).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "colag/common/geometry.hpp"
#include "colag/common/status.hpp"
#include "colag/sim/world/box_world.hpp"

namespace colag::sim {
class SimWorld;
}

namespace colag::mission {

enum class Ablation { kNone, kNoRpe, kNoUncertainty, kNoScheduling, kNoTimeWindows };
const char* to_string(Ablation a);
bool parse_ablation(const std::string& s, Ablation& out);

// A simulated-time interval [from_s, to_s); empty when to_s <= from_s.
struct TimeWindow {
  double from_s = 0.0, to_s = 0.0;
  bool contains(double t) const { return t >= from_s && t < to_s; }
  bool empty() const { return !(to_s > from_s); }
};
bool parse_window(const std::string& s, TimeWindow& out);  // "T0:T1" in seconds

// Fault injection (issue 8): network faults on every topic of the loopback transport, outages
// of the UAV (all its topics) or of its relative poses alone, and a wheel-encoder scale error.
struct FaultConfig {
  double loss = 0.0;  // share of samples dropped, 0..1
  double latency_ms = 0.0, jitter_ms = 0.0;
  TimeWindow uav_blackout;  // odometry, relative poses, map patches and plans all lost
  TimeWindow rpe_blackout;  // relative poses lost
  double odom_bias = 0.0;   // the encoders report (1 + bias) x the true motion
  bool any() const {
    return loss > 0.0 || latency_ms > 0.0 || jitter_ms > 0.0 || !uav_blackout.empty() ||
           !rpe_blackout.empty() || odom_bias != 0.0;
  }
};

struct MissionConfig {
  std::string scenario = "dense";  // "sparse" (40 boxes), "dense" (80 boxes), or "file"
  std::string map_file;            // PCD, when scenario == "file"
  int ugvs = 3;                    // 1 .. limits::kMaxUgvs
  std::uint64_t seed = 1;
  Ablation ablation = Ablation::kNone;
  bool self_perception = false;  // the paper's S.P. baseline: own LiDAR + true pose, no UAV
  double max_time_s = 400.0;
  int lidar_columns = 1200;  // horizontal resolution of the simulated LiDARs (0.3 deg)
  double goal_tolerance_m =
      0.5;  // "reached": stopped at the goal with the true position this close
  double predict_horizon_m = 2.0;  // UGV collision-prediction horizon (straight-line distance)
  int threads = 2;  // cores the simulation may use (1..8); the results do not depend on it
  FaultConfig faults;
  std::function<void(double fraction)> progress;  // called every simulated second (optional)
};

struct UgvOutcome {
  int id = 0;
  bool reached = false;
  bool collided = false;
  double reach_time_s = -1.0;   // -1 when it did not reach
  double waiting_time_s = 0.0;  // stopped because t_pc < t_c (the paper's waiting time)
  double init_wait_s = 0.0;     // stopped before the first relative pose (not in the paper)
  double traj_length_m = 0.0;
  double min_clearance_m = 0.0;  // closest approach of its footprint to an obstacle or UGV
  std::uint64_t support_requests = 0;
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
  std::vector<TaskTime> task_times;  // in table order of first appearance
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
    bool for_support;  // waiting for the UAV (t_pc < t_c); otherwise before the first RPE
  };
  std::vector<Stop> stops;
  std::vector<Vec2> collisions;
  std::vector<Vec2> unknown_cells;  // ground cells the UAV never saw (0.1 m), at the end
};

// The paper's layout (Sec. V): UGV i starts at (x_i, 16) heading -y and drives to (x_i, -16),
// x = 0, -2, 2, -4, 4, ...; the UAV starts at (0, 15, 1). Shared with colag_world (SITL).
Pose2 ugv_start(int i);
Vec2 ugv_goal(int i);
Vec3 uav_start();
// The scenario's obstacles: generated from the seed (sparse / dense) or loaded (file).
bool build_world(const MissionConfig& config, sim::BoxWorld& world, std::string& error);

// Runs one mission. Fails (with a message) only on a bad configuration or map file.
Result<MissionOutcome> run_mission(const MissionConfig& config, MissionTrace* trace = nullptr,
                                   std::string* error = nullptr);

// Completes an outcome whose UGVs have their id, reached, reach time, waiting time and support
// requests set: the ground truth from `world` (path length, clearance, collisions) and the
// paper's averages. Shared by colag_sim's missions and colag_world (SITL).
void summarise(const sim::SimWorld& world, MissionOutcome& out);

std::string to_json(const MissionOutcome& outcome, bool include_wall_time = true);

}  // namespace colag::mission
