#pragma once
// What a simulated mission is: the map, the fleet, the seed, the method (ablations, the
// self-perception baseline) and the faults injected; checked before anything is built. The
// paper's layout of starts and goals lives here too (shared with colag_world).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "colag/common/geometry.hpp"
#include "colag/hal/can/base_config.hpp"
#include "colag/sim/world/box_world.hpp"
#include "colag/sim/world/room_world.hpp"
#include "colag/sim/world/world_profile.hpp"

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
bool parse_window(const std::string& s, TimeWindow& out);       // "T0:T1" in seconds
bool parse_kill(const std::string& s, int& ugv, double& at_s);  // "I@T": UGV I at T seconds

// Fault injection: network faults on every topic of the loopback transport, outages of every
// robot (every topic), of the UAV (all its topics) or of its relative poses alone, and a
// wheel-encoder scale error.
struct FaultConfig {
  double loss = 0.0;  // share of samples dropped, 0..1
  double latency_ms = 0.0, jitter_ms = 0.0;
  TimeWindow blackout;      // every topic of every robot lost
  TimeWindow uav_blackout;  // odometry, relative poses, map patches and plans all lost
  TimeWindow rpe_blackout;  // relative poses lost
  double odom_bias = 0.0;   // the encoders report (1 + bias) x the true motion
  // UGV 0's base reports its own fault at this mission time (< 0: never): an ODrive axis's motor
  // error, an AgileX e-stop, our controller falling silent (what --ugv-base emulates).
  double base_fault_at_s = -1.0;
  // UAV uav_lost_id's board (< 0: the last UAV's) dies at this mission time (< 0: never): it
  // stops where it is and falls silent; the other UAVs take its UGVs over (with several UAVs).
  // UAV 0 is the time server: the others and the UGVs fly on with their last fleet time.
  double uav_lost_at_s = -1.0;
  int uav_lost_id = -1;
  // UGV kill_ugv's firmware process dies at kill_ugv_at_s (< 0: never) and starts again from its
  // configuration restart_after_s later (< 0: never), as `scripts/sitl.sh --kill-ugv I@T
  // --restart-after S` does with ugv_fw: its readers, its state and its CAN socket go with the
  // process; the world keeps its body where the base's watchdog stopped it.
  int kill_ugv = -1;
  double kill_ugv_at_s = -1.0;
  double restart_after_s = -1.0;
  bool any() const {
    return loss > 0.0 || latency_ms > 0.0 || jitter_ms > 0.0 || !blackout.empty() ||
           !uav_blackout.empty() || !rpe_blackout.empty() || odom_bias != 0.0;
  }
};

// Every robot has its own clock (as boards do). UAV 0's is fleet time; each other robot's (every
// UGV's, UAV 1's, ...) reads offset_s + U(-offset_s, offset_s) more than UAV 0's at the start (so
// none reads negative), and each robot's crystal runs U(-drift_ppm, drift_ppm) fast. Optionally
// UAV 0's clock steps once.
struct ClockConfig {
  double offset_s = 0.0;
  double drift_ppm = 0.0;
  double step_at_s = -1.0;  // mission time of the UAV clock's step; < 0: none
  double step_s = 0.0;
  bool any() const { return offset_s != 0.0 || drift_ppm != 0.0 || step_at_s >= 0.0; }
};

// Where a UGV starts (pose) and where it drives.
struct UgvPlacement {
  Pose2 start;
  Vec2 goal = Vec2::Zero();
  std::vector<Vec2> via;  // passed in order before the goal (at most limits::kMaxRouteVias)
};

struct MissionConfig {
  // "sparse" (40 boxes), "dense" (80 boxes), "pillars" (80), "rooms" (walls with doorways and
  // furniture: `rooms`), or "file"
  std::string scenario = "dense";
  std::string map_file;      // PCD, when scenario == "file"
  std::size_t boxes = 0;     // boxes or pillars of a generated field; 0: the scenario's number
  sim::RoomGenConfig rooms;  // "rooms" (its seed is the mission's)
  // A generated site of W x H m (--site; zero: the paper's 27 m arena and layout): the field
  // fills it but for 5 m at each end in y, where the UGVs start side by side (north) and arrive
  // (south). Counts of boxes, rooms and furniture are per 27 x 27 m and scale with the field.
  Vec2 site = Vec2::Zero();
  int ugvs = 3;  // 1 .. limits::kMaxUgvs
  // Each UGV's start and goal (a scenario file's), `ugvs` of them; empty: the paper's layout.
  std::vector<UgvPlacement> placements;
  Vec3 uav_start = Vec3(0.0, 15.0, 1.0);
  // UAVs (beyond the paper: several split the support), 1 .. limits::kMaxUavs. With more than
  // one they start spread over the UGVs' start line at uav_start's height and y, in one map frame
  // and on one clock (their boards synchronised among themselves).
  int uavs = 1;
  std::string scenario_file;  // where the above came from, if from a file (for the JSON)
  std::uint64_t seed = 1;
  Ablation ablation = Ablation::kNone;
  bool self_perception = false;  // the paper's S.P. baseline: own LiDAR + true pose, no UAV
  double max_time_s = 400.0;
  int lidar_columns = 1200;  // horizontal resolution of the simulated LiDARs (0.3 deg)
  double goal_tolerance_m =
      0.5;  // "reached": stopped at the goal with the true position this close
  double predict_horizon_m = 2.0;  // UGV collision-prediction horizon (straight-line distance)
  bool scouting = false;           // the UAV maps the UGVs' paths ahead when nothing is requested
  int threads = 2;  // cores the simulation may use (1..8); the results do not depend on it
  FaultConfig faults;
  ClockConfig clocks;       // none set: the world profile's
  sim::WorldProfile world;  // ideal (the paper's) or field
  hal::can::BaseProtocol ugv_base = hal::can::BaseProtocol::kColag;  // the UGVs' CAN protocol
  std::function<void(double fraction)> progress;  // called every simulated second (optional)
  std::function<void(const std::string&)> warn;   // each warning about the map (optional)
};

// False with `error` naming the option when a value is out of range.
bool check(const MissionConfig& cfg, std::string& error);

// The paper's layout (Sec. V): UGV i starts at (x_i, 16) heading -y and drives to (x_i, -16),
// x = 0, -2, 2, -4, 4, ...; the UAV starts at (0, 15, 1). Shared with colag_world (SITL).
Pose2 ugv_start(int i);
Vec2 ugv_goal(int i);
Vec3 uav_start();
// Whether the mission has a generated site (MissionConfig::site), and whether a site's size is
// one the generators take: at least 10 x 20 m, within limits::kMaxSiteHalf_m.
bool has_site(const MissionConfig& cfg);
bool site_size_ok(const Vec2& site);
// With a site and no placements: the site's layout (above) as placements, and the UAV's start
// behind the middle of the line.
void lay_out_site(MissionConfig& cfg);
// The time limit a mission gets unless told: 400 s (the paper's arena: a 32 m drive, up to 16
// UGVs); on a generated site, 400 s per 32 m of the drive from edge to edge, times the UGVs per
// UAV beyond 4 (one UAV serves a fleet in turn: on a 200 x 200 m site each UGV waited ~1900 s
// for four UAVs with 32 UGVs). The mission ends as soon as every UGV is done: the limit only
// bounds the ones that never are.
double default_max_time_s(const MissionConfig& cfg);
// The half extents of the generated field (the paper's 13.5 m without a site).
Vec2 field_half(const MissionConfig& cfg);
// This mission's: its placements, or the paper's layout.
Pose2 ugv_start(const MissionConfig& cfg, int i);
Vec2 ugv_goal(const MissionConfig& cfg, int i);
const std::vector<Vec2>& ugv_via(const MissionConfig& cfg, int i);  // before the goal
// The generated maps (colag_sim --scenario, a scenario file's map.generator), and which of them
// are fields of boxes or pillars (`boxes` sets how many).
inline const std::vector<std::string> kGeneratedScenarios{"sparse", "dense", "pillars", "rooms"};
bool is_box_field(const std::string& scenario);
// The scenario's obstacles: generated from the seed (sparse / dense) or loaded (file: checked
// against the layout, see map_checks.hpp; what it warns about is added to `warnings`).
bool build_world(const MissionConfig& cfg, sim::BoxWorld& world, std::string& error,
                 std::vector<std::string>* warnings = nullptr);

}  // namespace colag::mission
