#pragma once
// Flies the UAV to a target at the flight altitude: a path around whatever the UAV's own map
// shows at that altitude (A* on a 2-D "flight layer" kept from the 3-D map, obstacles inflated
// by the UAV's radius, unknown = free: the UAV sees for itself), followed by acceleration-
// limited guidance towards a lookahead point with a braking profile, sent as full-state
// setpoints (position, velocity, acceleration, yaw) through the FlightController HAL.
#include "colag/common/map_store.hpp"
#include "colag/common/planner.hpp"
#include "colag/hal/flight_controller.hpp"
#include "colag/hal/odometry_source.hpp"
#include "colag/uav/separation.hpp"
#include "colag/uav/time_cost.hpp"

namespace colag::uav {

struct FlightPlannerConfig {
  FlightLimits limits;
  double altitude_m = 1.0;
  double lookahead_m = 1.5;
  double altitude_gain = 1.5;  // vertical speed per metre of altitude error
  double max_climb_mps = 1.0;
  double retarget_m = 0.5;  // a target moved further than this is replanned
  Duration replan_period = std::chrono::seconds(2);
  // The setpoints ramp from the last one, not from the measured velocity: the odometry arrives
  // late, and a ramp restarted from a velocity one update old accelerates at a fraction of the
  // limit. Restarted from the measurement when the vehicle is this far from the last setpoint
  // (a gust, a flight controller that held it).
  double resync_mps = 0.5;
  SeparationConfig separation;  // from the other UAVs of the fleet
};

class FlightPlanner {
 public:
  explicit FlightPlanner(const FlightPlannerConfig& config) : config_(config) {}

  // `others`: a UAV that does not cooperate (dead, landing) is planned round, its whole
  // keep-out; the ones that fly the mission move, and only the separation filter minds them.
  void set_target(const Vec2& target, TimePoint now, const Vec2& from, const MapStore& flight_layer,
                  const Neighbours& others = {});
  // One guidance step: the setpoint that brings the UAV along the path, kept clear of the
  // other UAVs of the fleet (none: the paper's single UAV).
  hal::FlightSetpoint step(const hal::UavState& state, TimePoint now, double dt_s,
                           const MapStore& flight_layer, const Neighbours& others = {});
  bool has_target() const { return has_target_; }
  const Vec2& target() const { return target_; }
  const Path& path() const { return path_; }
  std::uint64_t plan_failures() const { return plan_failures_; }

 private:
  void plan(const Vec2& from, TimePoint now, const MapStore& flight_layer,
            const Neighbours& others);

  FlightPlannerConfig config_;
  Planner planner_;
  Path path_;
  Vec2 target_ = Vec2::Zero();
  bool has_target_ = false;
  TimePoint planned_at_{};
  std::uint64_t plan_failures_ = 0;
  Vec2 last_cmd_ = Vec2::Zero();
  bool have_cmd_ = false;
};

}  // namespace colag::uav
