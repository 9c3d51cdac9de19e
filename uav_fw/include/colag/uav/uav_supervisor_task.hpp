#pragma once
// The UAV supervisor task: mapping, map sharing, RPE relay, support scheduling and flight,
// driven by four loops of one executor table (their timing: UavSchedule):
//   control_loop()    50 Hz: odometry -> UavOdometry, camera -> RelativePose, flight setpoints
//   mapping_loop()    10 Hz: LiDAR scan -> 3-D map; the flight layer once a second
//   sharing_loop()    20 Hz: a map patch to each UGV whose 5 Hz slot is due
//   scheduling_loop() 10 Hz: support requests and UGV statuses -> schedule -> flight target,
//                            SupportPlan; each UGV's NearbyUgvs
// Pure task code: HAL and transport interfaces only; no heap, no exceptions, no OS calls in
// step(); malformed inputs are rejected and counted in health().
#include <array>
#include <cstdint>
#include <optional>

#include "colag/common/map_store.hpp"
#include "colag/common/map_window.hpp"
#include "colag/common/stamp_gate.hpp"
#include "colag/hal/flight_controller.hpp"
#include "colag/hal/lidar.hpp"
#include "colag/hal/odometry_source.hpp"
#include "colag/hal/relative_pose_sensor.hpp"
#include "colag/msg/support_plan.hpp"
#include "colag/platform/fleet_clock.hpp"
#include "colag/platform/readers.hpp"
#include "colag/uav/camera_altitude.hpp"
#include "colag/uav/clock_server.hpp"
#include "colag/uav/edge_orbit.hpp"
#include "colag/uav/fleet_scheduler.hpp"
#include "colag/uav/flight_planner.hpp"
#include "colag/uav/map_sharer.hpp"
#include "colag/uav/mapper.hpp"
#include "colag/uav/nearby_relay.hpp"
#include "colag/uav/no_return_beams.hpp"
#include "colag/uav/scheduler.hpp"
#include "colag/uav/team_filter.hpp"
#include "colag/uav/uav_schedule.hpp"

namespace colag::uav {

struct UavSupervisorConfig {
  RobotId id = 0;
  UavSchedule schedule;  // the loops' rates, budgets and offsets
  FlightPlannerConfig flight;
  MapperConfig mapper;
  SharerConfig sharer;
  SchedulerConfig scheduler;
  TeamFilterConfig team;     // the UGVs' own returns, kept out of the map while they are alive
  NearbyRelayConfig nearby;  // which UGVs each UGV hears of, relayed every scheduling step
  // Several UAVs (beyond the paper): each hears the others' odometry and plans. The live
  // requests are split among the UAVs that fly the mission (FleetScheduler: a stop leaves the UAV
  // whose plan holds it only when that saves more than fleet_switch_cost_s of waiting; two plans
  // holding one UGV: the lower UAV id keeps it), each UAV flying its own share. A UAV not heard
  // for peer_timeout, or whose flight controller left the mission, is gone: its UGVs are taken
  // over. Alone, the single-UAV scheduler above plans as in the paper.
  FleetSchedulerConfig fleet;
  double fleet_switch_cost_s = 2.0;
  Duration peer_timeout = std::chrono::seconds(2);
  // A peer fallen silent flies on until its flight controller's own failsafe (PX4: offboard
  // loss after COM_OF_LOSS_T, 1 s by default), then brakes: it is kept clear of along that line.
  Duration peer_failsafe = std::chrono::seconds(1);
  // Fleet time: fleet_clock.time_server is the UAV whose clock it is; it answers clock requests.
  // Every other UAV learns fleet time from it as a UGV does (platform/fleet_clock.hpp) and
  // converts at its edges; until its first exchange it publishes nothing stamped and reads
  // nothing stamped; while it knows fleet time and has not heard the server for
  // fleet_clock.standby_after it answers in its stead.
  platform::FleetClockConfig fleet_clock;
  // The paper's fallback when no order meets every deadline: plan as if v_max were 1.5x, 2.25x,
  // ... higher until one does (up to 100 times). Off: minimise total lateness instead.
  bool vmax_escalation = false;
  Pose3 lidar_mount;               // LiDAR frame -> UAV body
  LidarBeamPattern lidar_pattern;  // its beams: those without a return are free space
  // Its camera's view of the UGVs' tags: it flies where it sees the widest disc of them, at
  // least at flight.altitude_m and at most where the LiDAR still maps the ground around the UGV
  // it supports (see camera_altitude.hpp).
  CameraView camera_view;
  // The LiDAR sees nothing steeper than its lowest beam: its blind disc under the UAV grows with
  // the altitude, and the ground around a UGV it supports goes unmapped (a 60 deg / 4 m camera
  // flying at 2.3 m over a -25.2 deg beam, a 4.6 m disc, left a UGV without a path for 200 s).
  // The UAV flies no higher than leaves this disc on the UGVs' body band (1.6 m for -25.2 deg),
  // nor ever above max_altitude_m; with the pattern unknown, at flight.altitude_m.
  double max_blind_radius_m = 3.2;
  double max_altitude_m = 3.0;
  double arrival_radius_m = 1.0;  // at a support point when this close (2-D)
  // At a support point the UAV circles it at this radius and speed instead of hovering still:
  // the LiDAR sees nothing steeper than -25 deg, so a still UAV leaves a ~1.7 m blind disc
  // exactly where it is meant to look. Circling, every cell near the point is seen from a side.
  double orbit_radius_m = 2.0;
  double orbit_speed_mps = 1.5;
  // A UGV whose collision point lies this close to it stands against its own edge (see
  // edge_orbit.hpp): the UAV circles the UGV itself instead, this far outside the LiDAR's blind
  // disc (within the camera's reach), starting in front of it.
  double edge_stop_m = 0.6;
  double edge_beyond_blind_m = 0.6;
  double lead_m = 3.0;  // idle: fly this far ahead of the UGV, towards its goal
  // Scouting (beyond the paper): with nothing requested, circle the point where a UGV's planned
  // path first comes near unknown cells soonest (UgvStatus::scout_point_m), so that it is mapped
  // before that UGV has to stop and ask. Requests always come first. Off: the paper's idle (lead
  // the UGV not seen for the longest).
  bool scouting = false;
  double scout_switch_s = 2.0;  // another UGV's point is taken only if sooner by this much
  // Circling one point this long without its UGV moving it on (a cell the LiDAR cannot see):
  // that UGV's points are left for scout_rest.
  Duration scout_timeout = std::chrono::seconds(6);
  Duration scout_rest = std::chrono::seconds(15);
  Duration hover_timeout = std::chrono::seconds(10);
  // A second of lateness at a UGV that has asked for this long costs 1 + age / lateness_aging:
  // with lateness alone, a far UGV already late is served last whenever a nearer one asks in
  // time, for ever (a corner UGV in an 8-UGV field stood 105 s while the UAV served others).
  Duration lateness_aging = std::chrono::seconds(10);
  double served_moved_m = 1.0;  // a timed-out request returns when its point moves this much
  Duration served_cooldown = std::chrono::seconds(20);  // ... or after this long
  Duration request_timeout = std::chrono::seconds(5);   // UGVs heartbeat every second
  Duration status_timeout = std::chrono::seconds(5);
  double commit_radius_m = 3.0;     // this close to the current stop, the schedule keeps it
  double uav_radius_m = 0.3;        // flight-layer inflation
  double flight_band_half_m = 0.5;  // flight layer: obstacles within +- this of the altitude
  // The 3-D map and the flight layer are windows of the site (limits.hpp) that move with the
  // UAV: once it is within a metre of an edge, by enough that it is 10 m inside.
  WindowPolicy map_window{.edge_m = 10.0, .hard_edge_m = 1.0};
  // Its odometry goes to every UGV (to place its relative poses: interpolated between samples,
  // extrapolated by the velocity past the newest) and to the other UAVs (by the velocity too):
  // 20 Hz serves both. Every 50 Hz sample was 5.5 kB/s of a UGV's 10 kB/s, per UAV.
  Duration odometry_period = std::chrono::milliseconds(50);
  // With several UAVs each UGV's nearby list comes from the nearest (see relays_to): every UAV
  // relaying every list made a UGV's 1.3 kB/s of lists K times that.
  double relay_overlap_m = 1.0;
  Duration flight_layer_period = std::chrono::seconds(1);
  Duration plan_publish_period = std::chrono::seconds(1);
  Duration max_future_skew = std::chrono::milliseconds(200);
  Duration max_input_age = std::chrono::seconds(2);  // odometry and camera frames older: refused
  // The odometry arrives late: its pose is moved on to the scan's stamp and to the control tick
  // by its velocity, up to this far (see state_prediction.hpp).
  Duration max_odometry_prediction = std::chrono::milliseconds(200);
};

// kScout: flying to or circling a scouting point (nothing requested).
enum class UavMode : std::uint8_t { kIdle, kTransit, kHover, kScout };

struct UavHealth {
  std::uint64_t odometry_rejected = 0;  // the UAV's own odometry: not finite, or its stamp
  std::uint64_t rpe_published = 0;
  std::uint64_t rpe_rejected = 0;
  std::uint64_t requests_rejected = 0;
  std::uint64_t statuses_rejected = 0;
  std::uint64_t patches_sent = 0;
  std::uint64_t nearby_sent = 0;  // NearbyUgvs lists
  std::uint64_t setpoint_errors = 0;
  std::uint64_t schedules = 0;
  std::uint64_t schedules_exact = 0;
  std::uint32_t plan_age_max = 0;  // most scheduling steps one plan stood unchanged (warm starts)
  std::uint64_t fleet_schedules = 0;  // schedules shared with other UAVs
  std::uint64_t peers_lost = 0;       // other UAVs gone (silent or out of the mission)
  std::uint64_t peer_messages_rejected = 0;
  std::uint64_t hover_timeouts = 0;
  // Scheduling steps spent in each UavMode (idle, transit, hover, scout): where its time goes.
  std::array<std::uint64_t, static_cast<std::size_t>(UavMode::kScout) + 1> mode_steps{};
  std::uint64_t scout_timeouts = 0;  // scouting points left unmapped (scout_timeout)
  std::uint64_t flight_lost = 0;     // times the flight controller left the mission
  // Stamped messages not sent, or not read, before this UAV knew fleet time (not the server).
  std::uint64_t unsynchronised = 0;
  std::uint64_t window_moves = 0;  // the maps' window moved with the UAV
  StampCounters stamps;            // every input stream's stamp checks, summed (scheduling loop)
};

class UavSupervisorTask {
 public:
  UavSupervisorTask(const UavSupervisorConfig& config, platform::Transport& transport,
                    hal::OdometrySource& odometry, hal::Lidar& lidar,
                    hal::RelativePoseSensor& camera, hal::FlightController& flight,
                    ForkJoin* fork_join = nullptr);  // optional: lets mapping use more cores
  UavSupervisorTask(const UavSupervisorTask&) = delete;
  UavSupervisorTask& operator=(const UavSupervisorTask&) = delete;

  platform::Task& control_loop() { return control_loop_; }
  platform::Task& mapping_loop() { return mapping_loop_; }
  platform::Task& sharing_loop() { return sharing_loop_; }
  platform::Task& scheduling_loop() { return scheduling_loop_; }
  // The task's rows of an executor table, timed by config().schedule.
  std::array<platform::TaskEntry, 4> rows(int lane = 0) {
    const UavSchedule& s = config_.schedule;
    return {platform::row(control_loop_, s.control, lane),
            platform::row(mapping_loop_, s.mapping, lane),
            platform::row(sharing_loop_, s.sharing, lane),
            platform::row(scheduling_loop_, s.scheduling, lane)};
  }

  const Mapper& mapper() const { return mapper_; }
  const MapSharer& sharer() const { return sharer_; }
  const TeamFilter& team_filter() const { return team_filter_; }
  const NoReturnBeams& no_return_beams() const { return no_returns_; }
  const ScheduleResult& schedule() const { return schedule_; }
  const msg::SupportPlan& plan() const { return plan_; }
  const msg::UavOdometry& last_odometry() const { return last_odometry_; }  // as last sent
  UavMode mode() const { return mode_; }
  const FlightPlanner& flight() const { return flight_; }
  const UavHealth& health() const { return health_; }
  // The flight controller's last word (UavFlight::kLost: the supervisor no longer commands it).
  const hal::FlightStatus& flight_status() const { return flight_status_; }
  const ClockServer& clock_server() const { return clock_server_; }
  // Fleet time on a UAV that is not the time server (unused on the server).
  const platform::UavFleetClock& fleet_clock() const { return fleet_time_; }
  const UavSupervisorConfig& config() const { return config_; }
  // How far from a UGV against its own edge the UAV circles it (edge_orbit.hpp); NaN: it does
  // not, no circle sees both its ground and its tag.
  double edge_orbit_radius_m() const { return edge_orbit_radius_; }

 private:
  using Loop = platform::MemberLoop<UavSupervisorTask>;
  struct Request {
    bool active = false;
    TimePoint since{};    // asking since (or since we last hovered there): its age weighs it
    bool served = false;  // hovered there until the timeout: skip for a while
    TimePoint served_until{};
    std::uint32_t seq = 0;
    TimePoint heard{};
    TimePoint deadline{};
    Vec2 asked = Vec2::Zero();      // the UGV's support point
    Vec2 collision = Vec2::Zero();  // and its collision point
    Vec2 served_at = Vec2::Zero();
    // Where the UAV flies for it, and the circle it flies there (place_stops).
    Vec2 support = Vec2::Zero();
    Vec2 centre = Vec2::Zero();
    double radius = 0.0;
    // A UGV that lost its estimate (its firmware restarted) asks us to where its mission starts;
    // we look where we last knew it to be first, and there only until we hovered in vain.
    bool at_last_fix = false;
    bool last_fix_tried = false;
  };
  struct Ugv {
    bool known = false;
    TimePoint heard{};
    TimePoint last_seen = kNever;  // last relative pose of it
    msg::UgvStatus status;
    TimePoint scout_rest_until{};  // its scouting points are not flown to before this
    // Where its last status with an estimate put it (its position and heading).
    bool fixed_before = false;
    Vec2 last_fix = Vec2::Zero();
    double last_fix_yaw_rad = 0.0;
  };

  Status init(TimePoint now);
  void control_step(TimePoint now);
  void mapping_step(TimePoint now);
  void sharing_step(TimePoint now);
  void scheduling_step(TimePoint now);

  void read_requests(TimePoint now);
  void place_stops();
  void read_statuses(TimePoint now);
  void read_peers(TimePoint now);
  void solve(TimePoint now);
  // The stops split with the live peers (`live`: their ids); this UAV's share into schedule_.
  void solve_with_peers(std::span<const RobotId> live);
  bool choose_target(TimePoint now, Vec2& target);
  bool choose_scout_point(TimePoint now, Vec2& target);
  void keep_map_window();
  void refresh_flight_layer();
  void filter_team(TimePoint now);
  void publish_plan(TimePoint now, bool changed);
  void relay_nearby(TimePoint now);
  // Whether this UAV relays UGV `id`'s nearby list: the nearest live UAV to it does, and any
  // within relay_overlap_m of the nearest (their views of each other lag a little: at a switch
  // two relay for a moment rather than none).
  bool relays_to(TimePoint now, RobotId id) const;

  UavSupervisorConfig config_;
  platform::Transport& transport_;
  hal::OdometrySource& odometry_;
  hal::Lidar& lidar_;
  hal::RelativePoseSensor& camera_;
  hal::FlightController& flight_out_;
  Loop control_loop_, mapping_loop_, sharing_loop_, scheduling_loop_;
  bool initialised_ = false;

  platform::QueueReader<msg::CollisionInfo, 4 * limits::kMaxUgvs> requests_in_;
  platform::QueueReader<msg::UgvStatus, 4 * limits::kMaxUgvs> statuses_in_;
  // Each input stream's stamp checks (requests and statuses: one per UGV).
  StampGate odometry_stamps_, camera_stamps_;
  std::array<StampGate, limits::kMaxUgvs> request_stamps_{}, status_stamps_{};

  ClockServer clock_server_;
  platform::UavFleetClock fleet_time_;
  // Fleet time <-> this UAV's clock (the identity on the time server).
  bool time_server() const { return config_.id == config_.fleet_clock.time_server; }
  bool knows_fleet_time() const { return time_server() || fleet_time_.has_estimate(); }
  TimePoint to_fleet(TimePoint t) const { return time_server() ? t : fleet_time_.to_fleet(t); }
  TimePoint to_local(TimePoint t) const { return time_server() ? t : fleet_time_.to_local(t); }
  std::optional<Duration> clock_service(TimePoint now) const;  // ClockServer::step's offset
  hal::FlightStatus flight_status_;
  msg::UavOdometry last_odometry_;  // the last sample sent, repeated for the flight state
  TimePoint odometry_sent_ = kNever;
  TimePoint odometry_due_ = kNever;  // the next sample goes out at or after this
  hal::UavState state_;
  bool have_state_ = false;
  TimePoint last_control_{};
  TimePoint flight_layer_at_ = kNever;
  Mapper mapper_;
  NoReturnBeams no_returns_;
  TeamFilter team_filter_;
  MapSharer sharer_;
  MapSharer flight_cutter_;  // cuts flight-altitude patches for the flight layer
  MapStore flight_layer_;
  FlightPlanner flight_;
  ExactLabels exact_labels_;  // the two schedulers' (both run in the scheduling loop)
  Scheduler scheduler_;
  ScheduleProblem problem_;
  ScheduleResult schedule_;
  StaticVector<RobotId, kMaxStops> stop_ugv_;             // schedule node k -> UGV id
  std::array<std::uint8_t, limits::kMaxUgvs> stop_of_{};  // and back: UGV id -> k (0: none)
  StaticVector<RobotId, kMaxStops> plan_ugv_;   // the last plan's order, as UGV ids (warm start)
  StaticVector<std::uint8_t, kMaxStops> warm_;  // that order in this step's stop numbers
  // The other UAVs: where they fly, whether they fly the mission, which UGVs their plans hold.
  struct Peer {
    bool known = false;
    bool live = false;  // as the last scheduling step found it
    TimePoint heard{};
    Vec2 p = Vec2::Zero(), v = Vec2::Zero();
    msg::UavFlight flight = msg::UavFlight::kInControl;
    StaticVector<RobotId, kMaxStops> claims;  // its last plan's UGVs, in its order
  };
  void read_peer_odometry(TimePoint now);
  Neighbours neighbours(TimePoint now) const;  // the peers to keep clear of
  // A peer heard within peer_timeout, and where it is now by its velocity (its last sample
  // carried on for half a second at most).
  bool heard_lately(const Peer& peer, TimePoint now) const {
    return peer.known && now - peer.heard <= config_.peer_timeout;
  }
  static Vec2 where_now(const Peer& peer, TimePoint now) {
    return peer.p + std::min(to_seconds(now - peer.heard), 0.5) * peer.v;
  }
  platform::QueueReader<msg::UavOdometry, 8 * limits::kMaxUavs> peer_odometry_in_;
  platform::QueueReader<msg::SupportPlan, 2 * limits::kMaxUavs> peer_plans_in_;
  std::array<Peer, limits::kMaxUavs> peers_{};
  FleetScheduler fleet_;
  FleetProblem fleet_problem_;
  FleetRoutes fleet_warm_;
  std::array<Request, limits::kMaxUgvs> requests_{};
  std::array<Ugv, limits::kMaxUgvs> ugvs_{};
  int target_ugv_ = -1;  // UGV whose support or scouting point we fly to, -1: none
  bool target_is_request_ = false;
  bool target_is_scout_ = false;
  int scout_ugv_ = -1;    // the UGV whose point we last scouted (hysteresis)
  bool at_stop_ = false;  // reached the current support or scouting point: circling it
  Vec2 stop_point_ = Vec2::Zero();
  double orbit_phase_ = 0.0;
  double edge_orbit_radius_ = 0.0;  // see UavSupervisorConfig::edge_stop_m
  double camera_reach_ = 0.0;       // from the point under it, at the flight altitude
  TimePoint hover_since_ = kNever;
  UavMode mode_ = UavMode::kIdle;
  msg::SupportPlan plan_;
  TimePoint plan_published_ = kNever;
  std::uint32_t patch_seq_ = 0;
  msg::NearbyUgvs nearby_;           // the list being sent (a member: ~1 kB off the stack)
  std::uint64_t nearby_passes_ = 0;  // of the relay (see nearby_radius)
  UavHealth health_;
};

}  // namespace colag::uav
