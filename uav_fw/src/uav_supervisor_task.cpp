#include "colag/uav/uav_supervisor_task.hpp"

#include <algorithm>
#include <cmath>

#include "colag/uav/rpe_relay.hpp"
#include "colag/uav/state_prediction.hpp"
#include "colag/uav/time_cost.hpp"

namespace colag::uav {

namespace {

MapStoreConfig flight_layer_config(const UavSupervisorConfig& c) {
  MapStoreConfig m;
  m.plan_inflation_m = c.uav_radius_m;
  m.predict_inflation_m = 0.0;  // unused: the UAV plans, it does not predict collisions here
  return m;
}

SharerConfig flight_cutter_config(const UavSupervisorConfig& c) {
  SharerConfig s;
  s.band_low_m = c.flight.altitude_m - c.flight_band_half_m;
  s.band_high_m = c.flight.altitude_m + c.flight_band_half_m;
  s.half_box_m = 0.5 * limits::kMaxPatchSideCells * limits::kGridResolution_m - 0.1;
  s.shift_ahead_m = 0.0;
  return s;
}

// The mapper traces nothing above the highest layer that is read: the top of the flight layer
// or of the UGVs' body band.
MapperConfig mapper_config(const UavSupervisorConfig& c) {
  MapperConfig m = c.mapper;
  m.ceiling_m = std::min(
      m.ceiling_m, std::max(c.flight.altitude_m + c.flight_band_half_m, c.sharer.band_high_m));
  return m;
}

// See UavSupervisorConfig::edge_stop_m (c: with its camera altitude).
double edge_orbit_radius_of(const UavSupervisorConfig& c) {
  return edge_orbit_radius(blind_cone_elevation_deg(c.lidar_pattern, c.lidar_mount.q),
                           c.flight.altitude_m, c.sharer.band_low_m, c.camera_view,
                           c.edge_beyond_blind_m, c.orbit_radius_m);
}

UavSupervisorConfig with_camera_altitude(UavSupervisorConfig c) {
  const double lowest_beam = blind_cone_elevation_deg(c.lidar_pattern, c.lidar_mount.q);
  const double highest =
      lidar_altitude_limit(lowest_beam, c.sharer.band_low_m, c.max_blind_radius_m,
                           c.flight.altitude_m, c.max_altitude_m);
  c.flight.altitude_m = camera_altitude(c.camera_view, c.flight.altitude_m, highest);
  return c;
}

// A status whose position is its estimator's (not the start its mission plan gives it).
bool localised(const msg::UgvStatus& s) {
  return s.mode != msg::UgvMode::kWaitingForInit &&
         !(s.mode == msg::UgvMode::kBlocked &&
           s.blocked_reason == msg::BlockedReason::kNotLocalised);
}

}  // namespace

UavSupervisorTask::UavSupervisorTask(const UavSupervisorConfig& config,
                                     platform::Transport& transport, hal::OdometrySource& odometry,
                                     hal::Lidar& lidar, hal::RelativePoseSensor& camera,
                                     hal::FlightController& flight, ForkJoin* fork_join)
    : config_(with_camera_altitude(config)),
      transport_(transport),
      odometry_(odometry),
      lidar_(lidar),
      camera_(camera),
      flight_out_(flight),
      control_loop_(*this, "uav_control", &UavSupervisorTask::init,
                    &UavSupervisorTask::control_step),
      mapping_loop_(*this, "uav_mapping", &UavSupervisorTask::init,
                    &UavSupervisorTask::mapping_step),
      sharing_loop_(*this, "uav_sharing", &UavSupervisorTask::init,
                    &UavSupervisorTask::sharing_step),
      scheduling_loop_(*this, "uav_scheduling", &UavSupervisorTask::init,
                       &UavSupervisorTask::scheduling_step),
      fleet_time_(config_.fleet_clock),
      mapper_(mapper_config(config_), fork_join),
      no_returns_(config.lidar_pattern),
      team_filter_(config.team),
      sharer_(config.sharer),
      flight_cutter_(flight_cutter_config(config_)),
      flight_layer_(flight_layer_config(config_)),
      flight_(config_.flight),
      scheduler_(config.scheduler, &exact_labels_),
      fleet_(config.fleet, &exact_labels_),
      edge_orbit_radius_(edge_orbit_radius_of(config_)),
      camera_reach_(camera_reach(config_.camera_view, config_.flight.altitude_m)) {
  const Duration skew = config.max_future_skew;
  odometry_stamps_ = StampGate({skew, config.max_input_age, true});
  camera_stamps_ = StampGate({skew, config.max_input_age, false});
  request_stamps_.fill(StampGate({skew, config.request_timeout, true}));
  status_stamps_.fill(StampGate({skew, config.status_timeout, true}));
}

Status UavSupervisorTask::init(TimePoint now) {
  if (initialised_) return Status::ok();
  if (Status s = requests_in_.attach(transport_); !s) return s;
  if (Status s = statuses_in_.attach(transport_); !s) return s;
  if (Status s = peer_odometry_in_.attach(transport_); !s) return s;
  if (Status s = peer_plans_in_.attach(transport_); !s) return s;
  if (Status s = clock_server_.attach(transport_, config_.id); !s) return s;
  if (!time_server()) {
    if (Status s = fleet_time_.attach(transport_, config_.id); !s) return s;
  }
  last_control_ = now;
  initialised_ = true;
  return Status::ok();
}

// --- control loop (50 Hz)
// -------------------------------------------------------------------------

void UavSupervisorTask::control_step(TimePoint now) {
  const double dt = std::clamp(to_seconds(now - last_control_), 1e-3, 0.1);
  last_control_ = now;
  fleet_time_.step(now);
  clock_server_.step(now, clock_service(now));
  const bool stamping = knows_fleet_time();  // else nothing stamped goes out yet
  const hal::FlightStatus flight = flight_out_.update(now);
  if (flight.state == msg::UavFlight::kLost && flight_status_.state != msg::UavFlight::kLost)
    ++health_.flight_lost;
  flight_status_ = flight;
  hal::UavState s;
  bool fresh = false;
  msg::UavOdometry od;
  while (odometry_.poll(s)) {
    if (!all_finite(s.pose.p) || !s.pose.q.coeffs().allFinite() || !all_finite(s.velocity_mps) ||
        !StampGate::passed(odometry_stamps_.check(s.stamp, now))) {
      ++health_.odometry_rejected;
      continue;
    }
    state_ = s;
    have_state_ = true;
    fresh = true;
    od.stamp = to_fleet(s.stamp);
    od.uav_id = config_.id;
    for (int i = 0; i < 3; ++i) {
      od.position_m[i] = s.pose.p[i];
      od.velocity_mps[i] = s.velocity_mps[i];
    }
    const Quat q = s.pose.q.normalized();
    od.orientation_wxyz[0] = q.w();
    od.orientation_wxyz[1] = q.x();
    od.orientation_wxyz[2] = q.y();
    od.orientation_wxyz[3] = q.z();
    od.yaw_rate_radps = s.yaw_rate_radps;
    od.flight = flight.state;  // every UGV stops while the flight controller is not ours
    od.fault = flight.fault;
  }
  // The newest sample, at odometry_period on average (the control ticks need not divide it).
  if (fresh && !stamping) ++health_.unsynchronised;
  if (fresh && stamping && (odometry_due_ == kNever || now >= odometry_due_)) {
    const Duration period = config_.odometry_period;
    odometry_due_ = odometry_due_ == kNever || now - odometry_due_ >= period
                        ? now + period
                        : odometry_due_ + period;
    (void)transport_.publish(od);
    last_odometry_ = od;
    odometry_sent_ = now;
  }
  // Without fresh odometry the flight state still reaches the UGVs: the last sample again, at
  // once on a change, then 5 Hz while it is not in control (a UGV takes a repeated stamp for
  // the flight state alone).
  if (odometry_sent_ != kNever && now != odometry_sent_ &&
      (flight.state != last_odometry_.flight || flight.fault != last_odometry_.fault ||
       (flight.state != msg::UavFlight::kInControl &&
        now - odometry_sent_ >= std::chrono::milliseconds(200)))) {
    last_odometry_.flight = flight.state;
    last_odometry_.fault = flight.fault;
    (void)transport_.publish(last_odometry_);
    odometry_sent_ = now;
  }
  std::array<hal::RelativePoseDetection, limits::kMaxRpeDetectionsPerFrame> detections;
  const std::size_t n = camera_.poll(detections);
  for (std::size_t i = 0; i < n; ++i) {
    Result<msg::RelativePose> m = to_message(detections[i], config_.id);
    if (!m || !StampGate::passed(camera_stamps_.check(detections[i].stamp, now))) {
      ++health_.rpe_rejected;
      continue;
    }
    if (!stamping) {
      ++health_.unsynchronised;
      continue;
    }
    m.value().stamp = to_fleet(m.value().stamp);
    if (transport_.publish(m.value())) ++health_.rpe_published;
    ugvs_[detections[i].ugv_id].last_seen = detections[i].stamp;
  }
  // Lost or landing: the flight controller flies on its own; commanding it would fight a pilot
  // or its failsafe action.
  const bool commanding =
      flight.state == msg::UavFlight::kInControl || flight.state == msg::UavFlight::kStarting;
  read_peer_odometry(now);
  if (!have_state_ || !commanding) return;
  const hal::UavState here = predict_state(state_, now, config_.max_odometry_prediction);
  if (!flight_out_.send_setpoint(flight_.step(here, now, dt, flight_layer_, neighbours(now))))
    ++health_.setpoint_errors;
}

Neighbours UavSupervisorTask::neighbours(TimePoint now) const {
  Neighbours out;
  const double brake = std::max(config_.flight.limits.a_max_mps2, 0.1);
  for (const Peer& peer : peers_) {
    // On the ground too: one taking off beside us is in the air a moment later.
    if (!peer.known) continue;
    if (heard_lately(peer, now)) {
      const bool flies_mission =
          peer.flight == msg::UavFlight::kInControl || peer.flight == msg::UavFlight::kStarting;
      (void)out.push_back({where_now(peer, now), peer.v, flies_mission});
      continue;
    }
    // Silent (its board dead, its link lost): it flew on for up to peer_failsafe, until its flight
    // controller's own failsafe, then braked; nothing says it left the line between. That line
    // is kept clear of, for good.
    const double speed = peer.v.norm();
    Neighbour dead{peer.p, Vec2::Zero(), false};
    dead.p_end = peer.p + peer.v * (to_seconds(config_.peer_failsafe) + speed / (2.0 * brake));
    (void)out.push_back(dead);
  }
  return out;
}

// --- mapping loop (10 Hz)
// -------------------------------------------------------------------------

void UavSupervisorTask::mapping_step(TimePoint now) {
  if (have_state_) keep_map_window();
  hal::LidarScanView scan;
  if (lidar_.poll(scan) && have_state_) {
    const Pose3 sensor = predict_state(state_, scan.stamp, config_.max_odometry_prediction)
                             .pose.compose(config_.lidar_mount);
    filter_team(now);
    // Misses from the pattern first: a UGV's return the team filter drops is not free space.
    const double ground = mapper_.geometry().origin_z();
    mapper_.insert_scan(
        sensor, team_filter_.apply(no_returns_.complete(scan, sensor, ground), sensor, mapper_));
  }
  if (have_state_ && elapsed(now, flight_layer_at_, config_.flight_layer_period)) {
    flight_layer_at_ = now;
    refresh_flight_layer();
  }
}

// The map and the flight layer move together (the same lattice, the same place).
void UavSupervisorTask::keep_map_window() {
  const std::optional<Vec2> origin = window_move(
      mapper_.geometry().layer(), state_.pose.p.head<2>(), std::nullopt, config_.map_window);
  if (!origin || !mapper_.move_to(*origin).is_ok()) return;
  (void)flight_layer_.move_to(*origin);
  ++health_.window_moves;
}

// The UGVs as their fresh statuses say (if their estimators are initialised), for the team filter.
void UavSupervisorTask::filter_team(TimePoint now) {
  team_filter_.begin();
  for (std::size_t id = 0; id < ugvs_.size(); ++id) {
    const Ugv& u = ugvs_[id];
    if (!u.known || now - u.heard > config_.status_timeout || !localised(u.status)) continue;
    const double var = std::max({u.status.covariance[0], u.status.covariance[4], 0.0});
    (void)team_filter_.add(id, Vec2(u.status.position_m[0], u.status.position_m[1]),
                           3.0 * std::sqrt(var), now - u.heard, u.status.yaw_rad,
                           u.status.velocity_mps);
  }
}

void UavSupervisorTask::refresh_flight_layer() {
  // 3 x 3 patches around the UAV: what the map knows at flight altitude within ~10 m.
  const double step = limits::kMaxPatchSideCells * limits::kGridResolution_m - 0.2;
  msg::MapPatch patch;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const Vec2 centre = state_.pose.p.head<2>() + step * Vec2(dx, dy);
      if (flight_cutter_.make_patch(mapper_, centre, 0.0, 0.0, patch))
        (void)flight_layer_.apply(patch);
    }
  }
}

// --- sharing loop (20 Hz)
// -------------------------------------------------------------------------

void UavSupervisorTask::sharing_step(TimePoint now) {
  if (!knows_fleet_time()) return;
  msg::MapPatch patch;
  for (RobotId id = 0; id < limits::kMaxUgvs; ++id) {
    const Ugv& u = ugvs_[id];
    if (!u.known || now - u.heard > config_.status_timeout || !sharer_.due(id, now)) continue;
    const Vec2 p(u.status.position_m[0], u.status.position_m[1]);
    if (!sharer_.make_patch(mapper_, p, u.status.yaw_rad, u.status.velocity_mps, patch)) continue;
    if (!sharer_.should_send(id, now, patch)) continue;
    patch.stamp = to_fleet(now);
    patch.uav_id = config_.id;
    patch.ugv_id = id;
    patch.seq = ++patch_seq_;
    if (transport_.publish(patch)) ++health_.patches_sent;
  }
}

// --- scheduling loop (10 Hz)
// ----------------------------------------------------------------------

void UavSupervisorTask::read_requests(TimePoint now) {
  msg::CollisionInfo ci;
  while (requests_in_.pop(ci)) {
    const bool finite = std::isfinite(ci.time_to_collision_s) &&
                        std::isfinite(ci.support_point_m[0]) &&
                        std::isfinite(ci.support_point_m[1]);
    if (ci.ugv_id >= limits::kMaxUgvs ||
        (!ci.cancel && (!finite || ci.time_to_collision_s < 0.0))) {
      ++health_.requests_rejected;
      continue;
    }
    if (!knows_fleet_time()) {
      ++health_.unsynchronised;
      continue;
    }
    ci.stamp = to_local(ci.stamp);
    const StampGate::Verdict v = request_stamps_[ci.ugv_id].check(ci.stamp, now);
    if (v == StampGate::Verdict::kNotIncreasing) continue;  // old or duplicate: dropped
    if (!StampGate::passed(v)) {
      ++health_.requests_rejected;
      continue;
    }
    Request& r = requests_[ci.ugv_id];
    r.seq = ci.seq;
    r.heard = ci.stamp;
    if (ci.cancel) {
      r.active = r.served = false;
      continue;
    }
    if (!r.active) r.since = now;
    r.active = true;
    r.asked = Vec2(ci.support_point_m[0], ci.support_point_m[1]);
    r.collision = Vec2(ci.collision_point_m[0], ci.collision_point_m[1]);
    r.deadline = ci.stamp + seconds(ci.time_to_collision_s);
    if (r.served && (r.asked - r.served_at).norm() > config_.served_moved_m) r.served = false;
  }
  for (Request& r : requests_) {
    if (r.served && now >= r.served_until) r.served = false;  // its turn again
    if (!r.active) r.last_fix_tried = false;
    if (r.active && now - r.heard > config_.request_timeout)
      r.active = false;  // heartbeats stopped
  }
}

// Where the UAV flies for each request and what it circles there: the UGV's support point, or
// for a UGV against its own edge the UGV itself, from in front of it (see edge_orbit.hpp).
void UavSupervisorTask::place_stops() {
  for (RobotId id = 0; id < limits::kMaxUgvs; ++id) {
    Request& r = requests_[id];
    const Ugv& u = ugvs_[id];
    Vec2 p(u.status.position_m[0], u.status.position_m[1]), collision = r.collision;
    double yaw = u.status.yaw_rad;
    // Lost after we knew where it was (a restarted firmware asks where its mission starts): it
    // has not driven since, look there first.
    r.at_last_fix =
        r.active && u.known && u.fixed_before && !localised(u.status) && !r.last_fix_tried;
    if (r.at_last_fix) {
      p = collision = u.last_fix;
      yaw = u.last_fix_yaw_rad;
    }
    r.support = r.centre = r.at_last_fix ? p : r.asked;
    r.radius = config_.orbit_radius_m;
    if (!r.active || !u.known) continue;
    // A camera that sees less far than the orbit's radius (a narrow lens: 40 deg reaches 1.1 m
    // from 1.6 m up) would never see the tag of a UGV near the point it circles. Fly to the UGV
    // first, then circle through it: the ground round the point is still seen from every side,
    // and the tag once a turn.
    if (camera_reach_ < r.radius && localised(u.status)) {
      const Vec2 away = r.centre - p;
      const Vec2 dir =
          away.norm() > 1e-3 ? Vec2(away.normalized()) : Vec2(std::cos(yaw), std::sin(yaw));
      r.support = p;
      r.centre = p + r.radius * dir;
    }
    if (std::isnan(edge_orbit_radius_)) continue;
    if (!((collision - p).norm() <= config_.edge_stop_m)) continue;  // NaN: not at its edge
    r.centre = p;
    r.radius = edge_orbit_radius_;
    r.support = p + r.radius * Vec2(std::cos(yaw), std::sin(yaw));
  }
}

void UavSupervisorTask::read_statuses(TimePoint now) {
  msg::UgvStatus s;
  while (statuses_in_.pop(s)) {
    if (s.ugv_id >= limits::kMaxUgvs || !std::isfinite(s.position_m[0]) ||
        !std::isfinite(s.position_m[1]) || !std::isfinite(s.yaw_rad) ||
        !std::isfinite(s.velocity_mps)) {
      ++health_.statuses_rejected;
      continue;
    }
    if (!knows_fleet_time()) {
      ++health_.unsynchronised;
      continue;
    }
    // Checked on our clock; kept in fleet time (relayed as it came in the nearby lists).
    const StampGate::Verdict v = status_stamps_[s.ugv_id].check(to_local(s.stamp), now);
    if (v == StampGate::Verdict::kNotIncreasing) continue;  // duplicate or overtaken: dropped
    if (!StampGate::passed(v)) {
      ++health_.statuses_rejected;
      continue;
    }
    Ugv& u = ugvs_[s.ugv_id];
    u.known = true;
    u.heard = now;
    if (!std::isfinite(s.scout_point_m[0]) || !std::isfinite(s.scout_point_m[1]) ||
        !std::isfinite(s.scout_in_s))
      s.scout_in_s = -1.0;  // no scouting point: the rest of the status stands
    u.status = s;
    if (localised(s)) {
      u.fixed_before = true;
      u.last_fix = Vec2(s.position_m[0], s.position_m[1]);
      u.last_fix_yaw_rad = s.yaw_rad;
      requests_[s.ugv_id].last_fix_tried = false;
    }
  }
}

// Every control step: where the others fly (separation needs it fresh).
// The time server answers on its own clock; another UAV stands in while it knows fleet time and
// has not heard the server for a while (a robot starting after the server was lost can still
// learn fleet time; see platform/fleet_clock.hpp).
std::optional<Duration> UavSupervisorTask::clock_service(TimePoint now) const {
  if (time_server()) return Duration::zero();
  if (fleet_time_.synchronised(now) &&
      !fleet_time_.heard_server_within(now, config_.fleet_clock.standby_after)) {
    return to_fleet(now) - now;
  }
  return std::nullopt;
}

void UavSupervisorTask::read_peer_odometry(TimePoint now) {
  msg::UavOdometry od;
  while (peer_odometry_in_.pop(od)) {
    if (od.uav_id == config_.id) continue;  // our own
    if (od.uav_id >= limits::kMaxUavs || !std::isfinite(od.position_m[0]) ||
        !std::isfinite(od.position_m[1]) || !std::isfinite(od.position_m[2]) ||
        !std::isfinite(od.velocity_mps[0]) || !std::isfinite(od.velocity_mps[1])) {
      ++health_.peer_messages_rejected;
      continue;
    }
    Peer& peer = peers_[od.uav_id];
    peer.known = true;
    peer.heard = now;  // our clock: its stamps are its own (or fleet time)
    peer.p = Vec2(od.position_m[0], od.position_m[1]);
    peer.v = Vec2(od.velocity_mps[0], od.velocity_mps[1]);
    peer.flight = od.flight;
  }
}

void UavSupervisorTask::read_peers(TimePoint now) {
  msg::SupportPlan plan;
  while (peer_plans_in_.pop(plan)) {
    if (plan.uav_id == config_.id) continue;
    if (plan.uav_id >= limits::kMaxUavs || plan.stops.count > plan.stops.capacity()) {
      ++health_.peer_messages_rejected;
      continue;
    }
    Peer& peer = peers_[plan.uav_id];
    peer.claims.clear();
    for (std::size_t i = 0; i < plan.stops.count; ++i) {
      if (plan.stops[i].ugv_id < limits::kMaxUgvs)
        (void)peer.claims.push_back(plan.stops[i].ugv_id);
    }
  }
  for (Peer& peer : peers_) {
    const bool live = heard_lately(peer, now) && peer.flight == msg::UavFlight::kInControl;
    if (peer.live && !live) {
      ++health_.peers_lost;
      peer.claims.clear();  // what it held is free
    }
    peer.live = live;
  }
}

void UavSupervisorTask::solve(TimePoint now) {
  stop_ugv_.clear();
  stop_of_.fill(0);
  problem_ = ScheduleProblem{};
  for (RobotId id = 0; id < limits::kMaxUgvs; ++id) {
    const Request& r = requests_[id];
    if (r.active && !r.served && stop_ugv_.push_back(id))
      stop_of_[id] = static_cast<std::uint8_t>(stop_ugv_.size());
  }
  problem_.n = static_cast<int>(stop_ugv_.size());
  if (problem_.n == 0) {
    schedule_ = ScheduleResult{};
    plan_ugv_.clear();
    return;
  }
  const Vec2 p = state_.pose.p.head<2>(), v = state_.velocity_mps.head<2>();
  const auto build = [&](double speedup) {
    FlightLimits lim = config_.flight.limits;
    lim.v_max_mps *= speedup;
    for (int i = 0; i <= problem_.n; ++i) {
      const Vec2 from = i == 0 ? p : requests_[stop_ugv_[static_cast<std::size_t>(i - 1)]].support;
      for (int j = 1; j <= problem_.n; ++j) {
        const Vec2 to = requests_[stop_ugv_[static_cast<std::size_t>(j - 1)]].support;
        problem_.travel[i][j] =
            i == j ? 0.0
                   : (i == 0 ? first_leg_time_s(from, v, to, lim) : cruise_time_s(from, to, lim));
      }
      problem_.travel[i][0] = 0.0;  // open route
    }
    problem_.due[0] = 1e18;
    const double aging_s = std::max(to_seconds(config_.lateness_aging), 1e-3);
    for (int j = 1; j <= problem_.n; ++j) {
      const Request& r = requests_[stop_ugv_[static_cast<std::size_t>(j - 1)]];
      problem_.due[j] = to_seconds(r.deadline - now);
      problem_.weight[j] = 1.0 + std::max(0.0, to_seconds(now - r.since)) / aging_s;
    }
  };
  build(1.0);
  // The last plan, in this step's stop numbers: the scheduler continues improving it.
  warm_.clear();
  for (const RobotId id : plan_ugv_) {
    if (stop_of_[id] != 0) (void)warm_.push_back(stop_of_[id]);
  }
  StaticVector<RobotId, limits::kMaxUavs> live;
  for (RobotId id = 0; id < limits::kMaxUavs; ++id) {
    if (peers_[id].live) (void)live.push_back(id);
  }
  if (!live.empty()) {
    solve_with_peers({live.begin(), live.end()});
  } else {
    schedule_ = scheduler_.solve(problem_, {warm_.begin(), warm_.end()});
  }
  if (live.empty() && config_.vmax_escalation && !schedule_.cost.feasible) {
    double speedup = 1.0;
    for (int k = 0; k < 100 && !schedule_.cost.feasible; ++k) {
      speedup *= 1.5;
      build(speedup);
      schedule_ = scheduler_.solve(problem_, {warm_.begin(), warm_.end()});
    }
    build(1.0);  // report the order with the real speed
    const StaticVector<std::uint8_t, kMaxStops> order = schedule_.order;
    schedule_.cost = evaluate(problem_, {order.begin(), order.end()}, schedule_.arrival.data());
  }
  plan_ugv_.clear();
  for (const std::uint8_t k : schedule_.order)
    (void)plan_ugv_.push_back(stop_ugv_[k - 1u]);
  ++health_.schedules;
  health_.schedules_exact += schedule_.exact;
  health_.plan_age_max = std::max(health_.plan_age_max, schedule_.age_steps);
}

void UavSupervisorTask::solve_with_peers(std::span<const RobotId> live) {
  FleetProblem& f = fleet_problem_;
  const int n = problem_.n;
  f.n = n;
  f.vehicles = static_cast<int>(live.size()) + 1;  // vehicle 0: this UAV; then the peers by id
  f.switch_cost_s = config_.fleet_switch_cost_s;
  for (int i = 1; i <= n; ++i) {
    for (int j = 1; j <= n; ++j)
      f.travel[i][j] = problem_.travel[i][j];
    f.first[0][i] = problem_.travel[0][i];
    f.ready[i] = problem_.ready[i];
    f.due[i] = problem_.due[i];
    f.weight[i] = problem_.weight[i];
  }
  for (std::size_t v = 1; v <= live.size(); ++v) {
    const Peer& peer = peers_[live[v - 1]];
    for (int j = 1; j <= n; ++j) {
      const Vec2 to = requests_[stop_ugv_[static_cast<std::size_t>(j - 1)]].support;
      f.first[v][j] = first_leg_time_s(peer.p, peer.v, to, config_.flight.limits);
    }
  }
  // Who holds each stop: the plans that list it, the lowest UAV id first; each plan's order is
  // its vehicle's warm route.
  for (Route& r : fleet_warm_)
    r.clear();
  f.owner.fill(-1);
  std::array<RobotId, kMaxStops + 1> holder{};
  holder.fill(0xFFFF);
  const auto hold = [&](RobotId uav, std::size_t vehicle, std::span<const RobotId> ugvs) {
    for (const RobotId ugv : ugvs) {
      const std::uint8_t k = stop_of_[ugv];
      if (k == 0 || uav >= holder[k]) continue;
      holder[k] = uav;
      f.owner[k] = static_cast<std::int16_t>(vehicle);
    }
  };
  hold(config_.id, 0, {plan_ugv_.begin(), plan_ugv_.end()});
  for (std::size_t v = 1; v <= live.size(); ++v) {
    const Peer& peer = peers_[live[v - 1]];
    hold(live[v - 1], v, {peer.claims.begin(), peer.claims.end()});
  }
  for (std::size_t v = 0; v <= live.size(); ++v) {
    const auto& ugvs = v == 0 ? plan_ugv_ : peers_[live[v - 1]].claims;
    for (const RobotId ugv : ugvs) {
      const std::uint8_t k = stop_of_[ugv];
      if (k != 0 && f.owner[k] == static_cast<int>(v)) (void)fleet_warm_[v].push_back(k);
    }
  }
  const FleetResult& r = fleet_.solve(f, &fleet_warm_);
  const Route& mine = r.routes[0];
  const bool same = std::equal(mine.begin(), mine.end(), warm_.begin(), warm_.end());
  const std::uint32_t age = same ? schedule_.age_steps + 1 : 0;
  schedule_ = ScheduleResult{};
  schedule_.order = mine;
  schedule_.cost = evaluate_route(f, 0, {mine.begin(), mine.end()}, schedule_.arrival.data());
  schedule_.exact = r.exact;
  schedule_.age_steps = age;
  ++health_.fleet_schedules;
}

bool UavSupervisorTask::choose_target(TimePoint now, Vec2& target) {
  const Vec2 here = state_.pose.p.head<2>();
  // Keep the stop we are at or nearly at, if it still wants us.
  if (target_is_request_ && target_ugv_ >= 0) {
    const Request& r = requests_[static_cast<std::size_t>(target_ugv_)];
    if (r.active && !r.served &&
        (at_stop_ || (r.support - here).norm() <= config_.commit_radius_m)) {
      target = r.support;
      return true;
    }
  }
  if (!schedule_.order.empty()) {
    target_ugv_ = stop_ugv_[schedule_.order[0] - 1u];
    target_is_request_ = true;
    target = requests_[static_cast<std::size_t>(target_ugv_)].support;
    return true;
  }
  target_is_request_ = false;
  target_is_scout_ = false;
  if (config_.scouting && choose_scout_point(now, target)) return true;
  // Nothing requested: visit the UGV not seen for the longest (keep every estimator fed); a
  // blocked one only when no other needs a visit (it has said we cannot help it now).
  int best = -1;
  const auto before = [&](const Ugv& u, const Ugv& b) {
    const bool u_blocked = u.status.mode == msg::UgvMode::kBlocked;
    const bool b_blocked = b.status.mode == msg::UgvMode::kBlocked;
    return u_blocked != b_blocked ? !u_blocked : u.last_seen < b.last_seen;
  };
  for (RobotId id = 0; id < limits::kMaxUgvs; ++id) {
    const Ugv& u = ugvs_[id];
    if (!u.known || now - u.heard > config_.status_timeout ||
        u.status.mode == msg::UgvMode::kArrived)
      continue;
    if (best < 0 || before(u, ugvs_[static_cast<std::size_t>(best)])) best = id;
  }
  target_ugv_ = best;
  if (best < 0) return false;
  // Lead it: a little ahead towards its goal, mapping what it is about to drive into.
  const auto& s = ugvs_[static_cast<std::size_t>(best)].status;
  const Vec2 p(s.position_m[0], s.position_m[1]), goal(s.goal_m[0], s.goal_m[1]);
  const Vec2 to_goal = goal - p;
  target = p;
  if (to_goal.norm() > 1e-3)
    target += std::min(config_.lead_m, to_goal.norm()) * to_goal.normalized();
  return true;
}

// The UGV that will reach unknown ground soonest: its path's first unknown point. The one we are
// scouting for keeps it unless another is sooner by scout_switch_s (no dithering between two).
bool UavSupervisorTask::choose_scout_point(TimePoint now, Vec2& target) {
  int best = -1;
  double best_in = 0.0;
  for (RobotId id = 0; id < limits::kMaxUgvs; ++id) {
    const Ugv& u = ugvs_[id];
    if (!u.known || now - u.heard > config_.status_timeout || u.status.scout_in_s < 0.0 ||
        now < u.scout_rest_until || u.status.mode == msg::UgvMode::kArrived)
      continue;
    double in = u.status.scout_in_s;
    if (id == scout_ugv_) in -= config_.scout_switch_s;
    if (best < 0 || in < best_in) {
      best = id;
      best_in = in;
    }
  }
  scout_ugv_ = best;
  if (best < 0) return false;
  const msg::UgvStatus& s = ugvs_[static_cast<std::size_t>(best)].status;
  target_ugv_ = best;
  target_is_scout_ = true;
  target = Vec2(s.scout_point_m[0], s.scout_point_m[1]);
  return true;
}

void UavSupervisorTask::publish_plan(TimePoint now, bool changed) {
  if (!knows_fleet_time()) return;
  if (!changed && !elapsed(now, plan_published_, config_.plan_publish_period)) return;
  plan_ = msg::SupportPlan{};
  plan_.stamp = to_fleet(now);
  plan_.uav_id = config_.id;
  plan_.seq = static_cast<std::uint32_t>(health_.schedules);
  plan_.total_lateness_s = schedule_.cost.lateness_s;
  for (const std::uint8_t k : schedule_.order) {
    msg::SupportStop& stop = plan_.stops[plan_.stops.count++];
    stop.ugv_id = stop_ugv_[k - 1u];
    const Vec2 sp = requests_[stop.ugv_id].support;
    stop.point_m[0] = sp.x();
    stop.point_m[1] = sp.y();
    stop.point_m[2] = config_.flight.altitude_m;
    stop.eta_s = schedule_.arrival[k];
    stop.deadline_s = problem_.due[k];
  }
  plan_published_ = now;
  (void)transport_.publish(plan_);
}

void UavSupervisorTask::relay_nearby(TimePoint now) {
  nearby_.uav_id = config_.id;
  health_.nearby_sent += static_cast<std::uint64_t>(uav::relay_nearby(
      ugvs_, now, config_.status_timeout, config_.nearby, nearby_passes_++, nearby_,
      [&](RobotId id) { return relays_to(now, id); },
      [&](msg::NearbyUgvs& m) {
        m.stamp = to_fleet(m.stamp);
        return static_cast<bool>(transport_.publish(m));
      }));
}

bool UavSupervisorTask::relays_to(TimePoint now, RobotId id) const {
  if (!have_state_) return true;  // nowhere yet: relay rather than leave a UGV without
  const auto& s = ugvs_[id].status;
  const Vec2 ugv(s.position_m[0], s.position_m[1]);
  const double mine = (state_.pose.p.head<2>() - ugv).norm();
  for (const Peer& peer : peers_) {
    if (!heard_lately(peer, now)) continue;
    if ((where_now(peer, now) - ugv).norm() + config_.relay_overlap_m < mine) return false;
  }
  return true;
}

void UavSupervisorTask::scheduling_step(TimePoint now) {
  read_requests(now);
  read_statuses(now);
  place_stops();
  read_peers(now);
  if (knows_fleet_time()) relay_nearby(now);
  StampCounters stamps = odometry_stamps_.counters();
  stamps += camera_stamps_.counters();
  for (std::size_t i = 0; i < limits::kMaxUgvs; ++i) {
    stamps += request_stamps_[i].counters();
    stamps += status_stamps_[i].counters();
  }
  health_.stamps = stamps;
  if (!have_state_) return;
  const int previous_first = schedule_.order.empty() ? -1 : stop_ugv_[schedule_.order[0] - 1u];
  const StaticVector<RobotId, kMaxStops> held = plan_ugv_;
  solve(now);
  const int first = schedule_.order.empty() ? -1 : stop_ugv_[schedule_.order[0] - 1u];
  // With other UAVs, what this one holds is news at once (they plan around it).
  const bool peers =
      std::any_of(peers_.begin(), peers_.end(), [](const Peer& p) { return p.live; });
  const bool changed =
      previous_first != first ||
      (peers && !std::equal(held.begin(), held.end(), plan_ugv_.begin(), plan_ugv_.end()));
  Vec2 target;
  if (!choose_target(now, target)) {
    mode_ = UavMode::kIdle;
    ++health_.mode_steps[static_cast<std::size_t>(mode_)];
    publish_plan(now, changed);
    return;
  }
  const Vec2 here = state_.pose.p.head<2>();
  // A point over a UAV that does not keep its half of the separation (a dead one hovering
  // there): the edge of its keep-out instead, or the UAV would never arrive.
  const Neighbours others = neighbours(now);
  const SeparationConfig& sep = config_.flight.separation;
  target = clear_of(target, others, sep.min_m + sep.target_margin_m);
  // A different stop (or the same UGV's point moved): fly there first. Support points and
  // scouting points are circled once reached.
  const bool circled = target_is_request_ || target_is_scout_;
  if (!circled || (target - stop_point_).norm() > config_.served_moved_m) at_stop_ = false;
  stop_point_ = target;
  Vec2 centre = target;
  double radius = config_.orbit_radius_m;
  if (target_is_request_) {
    const Request& r = requests_[static_cast<std::size_t>(target_ugv_)];
    centre += r.centre - r.support;  // the same offset from where separation put the target
    radius = r.radius;
  }
  if (circled && !at_stop_ && (target - here).norm() <= config_.arrival_radius_m) {
    at_stop_ = true;
    hover_since_ = now;
    orbit_phase_ = std::atan2(here.y() - centre.y(), here.x() - centre.x());
  }
  if (at_stop_) {
    mode_ = target_is_scout_ ? UavMode::kScout : UavMode::kHover;
    orbit_phase_ +=
        config_.orbit_speed_mps / radius * to_seconds(config_.schedule.scheduling.period);
    const Vec2 orbit = centre + radius * Vec2(std::cos(orbit_phase_), std::sin(orbit_phase_));
    flight_.set_target(orbit, now, here, flight_layer_, others);
    if (target_is_scout_ && elapsed(now, hover_since_, config_.scout_timeout)) {
      // Its point stays where it was: a cell we do not see from here. Scout for the others.
      ugvs_[static_cast<std::size_t>(target_ugv_)].scout_rest_until = now + config_.scout_rest;
      ++health_.scout_timeouts;
      at_stop_ = false;
    } else if (!target_is_scout_ && elapsed(now, hover_since_, config_.hover_timeout)) {
      // The UGV keeps asking although we are there: give the others a turn.
      Request& r = requests_[static_cast<std::size_t>(target_ugv_)];
      if (r.at_last_fix) r.last_fix_tried = true;  // not there: where it asks next time
      r.served = true;
      r.since = now + config_.served_cooldown;  // we came: its age counts from its next turn
      r.served_at = r.asked;
      r.served_until = now + config_.served_cooldown;
      ++health_.hover_timeouts;
      at_stop_ = false;
    }
  } else {
    mode_ = target_is_request_ ? UavMode::kTransit
            : target_is_scout_ ? UavMode::kScout
                               : UavMode::kIdle;
    flight_.set_target(target, now, here, flight_layer_, others);
  }
  ++health_.mode_steps[static_cast<std::size_t>(mode_)];
  publish_plan(now, changed);
}

}  // namespace colag::uav
