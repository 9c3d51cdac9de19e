#include "colag/ugv/ugv_nav_task.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace colag::ugv {

namespace {

// Largest 1-sigma extent of a 2-D covariance (square root of its largest eigenvalue).
double sigma_major(const Mat2& cov) {
  const double tr = cov(0, 0) + cov(1, 1);
  const double det = cov(0, 0) * cov(1, 1) - cov(0, 1) * cov(1, 0);
  const double l = 0.5 * tr + std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
  return std::sqrt(std::max(0.0, l));
}

// Faster than any UGV drives: a status claiming more is corrupt.
constexpr double kMaxPlausibleSpeed_mps = 5.0;
constexpr double kWindowGoalMargin_m = 1.0;                     // see replan()
constexpr Duration kRobotReleaseGap = std::chrono::seconds(2);  // see predict_and_request()

bool plausible(const msg::NearbyUgv& u) {
  if (!std::isfinite(u.position_m[0]) || !std::isfinite(u.position_m[1])) return false;
  // The velocity moves the UGV's disc in the collision prediction: a bad one would hide it.
  if (!std::isfinite(u.yaw_rad) || !(std::abs(u.velocity_mps) <= kMaxPlausibleSpeed_mps))
    return false;
  for (double c : u.covariance_xy) {
    if (!std::isfinite(c)) return false;
  }
  return u.ugv_id < limits::kMaxUgvs && std::isfinite(u.silent_s) && u.silent_s >= 0.0 &&
         static_cast<unsigned>(u.mode) <=
             static_cast<unsigned>(msg::EnumRange<msg::UgvMode>::kLast);
}

// What the UGV calls the UAV for when the map blocks its way.
SupportCause support_cause_of(MapCause cause) {
  switch (cause) {
    case MapCause::kNearObstacle:
      return SupportCause::kNearObstacle;
    case MapCause::kUncertainNow:
      return SupportCause::kUncertainNow;
    case MapCause::kNone:
    case MapCause::kUnknownGround:
      break;
  }
  return SupportCause::kUnknownGround;
}

}  // namespace

UgvNavTask::UgvNavTask(const UgvNavConfig& config, platform::Transport& transport,
                       hal::WheelOdometry& odometry, hal::Drive& drive)
    : config_(config),
      transport_(transport),
      odometry_(odometry),
      drive_(drive),
      control_loop_(*this, "ugv_control", &UgvNavTask::init, &UgvNavTask::control_step,
                    &UgvNavTask::on_overrun),
      planning_loop_(*this, "ugv_planning", &UgvNavTask::init, &UgvNavTask::planning_step,
                     &UgvNavTask::on_overrun),
      fleet_(config.fleet_clock),
      ekf_(config.ekf),
      map_(config.map),
      planner_(config.planner),
      controller_(config.controller, config.limits),
      predictor_(config.predictor, config.ekf.noise, config.ekf.calibration,
                 config.ekf.frame_walk_m_per_sqrt_s),
      support_(config.support),
      blocked_(config.blocked) {
  // Wheel samples are stamped by this board's clock (their order is the EKF's to check); the
  // UAV's odometry must increase (the history interpolates along it); relative poses may come
  // late and out of order within the EKF's history; the nearby-UGV lists must increase.
  wheel_stamps_ = StampGate(stamp_limits(false));
  for (Uav& u : uavs_)
    u.stamps = StampGate(stamp_limits(true));
  rpe_stamps_ = StampGate(stamp_limits(false));
  patch_stamps_ = StampGate(stamp_limits(false));
  nearby_stamps_ = StampGate(stamp_limits(true));
}

Status UgvNavTask::init(TimePoint now) {
  if (initialised_) return Status::ok();  // both loops call init; the first one does the work
  if (config_.id >= limits::kMaxUgvs) return {Errc::kInvalidArgument, "UGV id out of range"};
  if (Status s = uav_odometry_in_.attach(transport_); !s) return s;
  if (Status s = rpe_in_.attach(transport_, config_.id); !s) return s;
  if (Status s = patches_in_.attach(transport_, config_.id); !s) return s;
  if (Status s = nearby_in_.attach(transport_, config_.id); !s) return s;
  if (Status s = fleet_.attach(transport_, config_.id); !s) return s;
  started_ = last_control_ = now;
  last_plan_ = kNever;
  initialised_ = true;
  return Status::ok();
}

// --- control loop (50 Hz)
// -------------------------------------------------------------------------

void UgvNavTask::control_step(TimePoint now) {
  const double dt = std::clamp(to_seconds(now - last_control_), 0.0, 0.1);
  last_control_ = now;
  fleet_.step(now);
  read_odometry(now);
  read_relative_poses(now);
  drive(now, dt);
  // Standing still before the goal is waiting, whatever the reason (see waiting.hpp): by the
  // wheels, which brake and pull away as the robot does (the command leads them).
  if (!arrived_ && (still_speed_ < kStillSpeed_mps || faulty())) {
    const WaitPart part = wait_part(mode_, blocked_reason_, health_.plans > health_.plan_failures,
                                    !trajectory_.empty());
    waiting_parts_[static_cast<std::size_t>(part)] += seconds(dt);
    if (part == WaitPart::kSupport)
      support_causes_[static_cast<std::size_t>(support_cause_)] += seconds(dt);
  }
}

void UgvNavTask::read_odometry(TimePoint now) {
  hal::WheelOdometrySample s;
  while (odometry_.poll(s)) {
    if (!StampGate::passed(wheel_stamps_.check(s.stamp, now)) ||
        !ekf_.predict(s.stamp, s.v_mps, s.omega_radps)) {
      ++health_.odometry_rejected;
      continue;
    }
    wheel_speed_ = s.v_mps;
    wheel_omega_ = s.omega_radps;
    // Averaged over ~4 samples for the standing-still test: one sample's noise (3 cm/s) would
    // count a robot creeping at 6 cm/s as standing.
    still_speed_ += 0.25 * (std::abs(s.v_mps) - still_speed_);
  }
  // Watchdog: a blind robot without odometry does not know where it is going.
  const TimePoint last = odometry_.last_sample_time();
  const bool silent = last == TimePoint{} ? now - started_ > config_.odometry_startup_grace
                                          : now - last > config_.odometry_timeout;
  if (silent && !faulty()) ++health_.watchdog_trips;
  // The base's own faults (e-stop, motor errors, bus-off, ...): the same safe stop.
  const hal::DriveHealth base = drive_.health();
  if (base.fault != msg::BaseFault::kNone && base.fault != drive_fault_seen_) ++health_.base_faults;
  drive_fault_seen_ = base.fault;
  base_fault_ = silent ? hal::DriveHealth{msg::BaseFault::kOdometrySilent, 0} : base;
}

void UgvNavTask::read_relative_poses(TimePoint now) {
  // Matching a relative pose to the UAV's odometry and to our odometry history needs their stamps
  // on our clock: nothing is fused before fleet time is known.
  const bool synchronised = fleet_.synchronised(now);
  msg::UavOdometry od;
  while (uav_odometry_in_.pop(od)) {
    if (od.uav_id >= limits::kMaxUavs) {
      ++health_.uav_odometry_rejected;
      continue;
    }
    Uav& uav = uavs_[od.uav_id];
    // Whether the UAV flies the mission needs no clock: it is read from every sample.
    if (od.flight != uav.flight && od.flight != msg::UavFlight::kInControl)
      ++health_.uav_unavailable;
    uav.flight = od.flight;
    uav.heard = true;
    // A repeat (the UAV without fresh odometry) carries the flight state alone.
    if (od.stamp == uav.last_stamp) continue;
    uav.last_stamp = od.stamp;
    if (!synchronised) {
      ++health_.unsynchronised;
      continue;
    }
    od.stamp = fleet_.to_local(od.stamp);
    // A sample from the future would otherwise become the history's newest and lock out every
    // genuine one after it; a UAV whose clock went back starts a new history.
    const StampGate::Verdict v = uav.stamps.check(od.stamp, now);
    if (v == StampGate::Verdict::kRestarted) uav.history.clear();
    if (!StampGate::passed(v) || !uav.history.push(od)) ++health_.uav_odometry_rejected;
  }
  msg::RelativePose rpe;
  while (rpe_in_.pop(rpe)) {
    if (!synchronised) {
      ++health_.unsynchronised;
      continue;
    }
    rpe.stamp = fleet_.to_local(rpe.stamp);
    if (rpe.ugv_id != config_.id || rpe.uav_id >= limits::kMaxUavs ||
        !StampGate::passed(rpe_stamps_.check(rpe.stamp, now))) {
      ++health_.rpe_rejected;
      continue;
    }
    // Placed by the odometry of the UAV that measured it.
    Pose3 uav;
    if (!uavs_[rpe.uav_id].history.pose_at(rpe.stamp, config_.rpe_match_tolerance, uav)) {
      ++health_.rpe_unmatched;
      continue;
    }
    Result<PoseMeasurement> z = world_measurement(rpe, uav);
    if (!z) {
      ++health_.rpe_rejected;
      continue;
    }
    // Its stamp on our clock is only as good as fleet time: what we drove in that much time is
    // added to its uncertainty (the bound taken as a uniform error's half-width).
    const double st = fleet_.error_s(now) / std::sqrt(3.0);
    const double yaw = ekf_.pose().yaw_rad;
    const Vec2 h(std::cos(yaw), std::sin(yaw));
    z.value().covariance.topLeftCorner<2, 2>() +=
        (wheel_speed_ * st) * (wheel_speed_ * st) * h * h.transpose();
    z.value().covariance(2, 2) += (wheel_omega_ * st) * (wheel_omega_ * st);
    if (ekf_.initialized() && !config_.use_rpe_updates) {
      ++health_.rpe_ignored;
      continue;
    }
    switch (ekf_.update(z.value())) {
      case UgvEkf::Update::kInitialized:
      case UgvEkf::Update::kReset:
        replan_requested_ = true;
        break;
      case UgvEkf::Update::kApplied:
      case UgvEkf::Update::kHeld:  // at the start or after a gap: the next confirms it
        break;
      case UgvEkf::Update::kRejectedGate:
        ++health_.rpe_outliers;
        break;
      case UgvEkf::Update::kRejectedStale:
      case UgvEkf::Update::kRejectedInvalid:
        ++health_.rpe_rejected;
        break;
    }
  }
}

bool UgvNavTask::no_uav_in_control() const {
  bool heard = false;
  for (const Uav& u : uavs_) {
    if (u.heard && u.flight == msg::UavFlight::kInControl) return false;
    heard = heard || u.heard;
  }
  return heard;
}

void UgvNavTask::command(TimePoint now, double v, double omega) {
  v_cmd_ = v;
  omega_cmd_ = omega;
  const Status s = (v == 0.0 && omega == 0.0) ? drive_.stop(now) : drive_.command({now, v, omega});
  if (!s) ++health_.drive_errors;
}

void UgvNavTask::drive(TimePoint now, double dt) {
  // A relative pose came: it is sure enough now, or it learnt that it is not there yet.
  if (awaiting_fix_ && sure_of_position()) awaiting_fix_ = false;
  if (faulty()) {
    mode_ = msg::UgvMode::kFault;
  } else if (paused_) {
    mode_ = msg::UgvMode::kPaused;
  } else if (aborted_) {
    mode_ = msg::UgvMode::kAborted;
  } else if (no_uav_in_control() && ekf_.initialized() && !arrived_) {
    // Its flight controller failed safe, was taken over or lands: no support is coming and the
    // UAV itself may come down anywhere.
    mode_ = msg::UgvMode::kUavUnavailable;
  } else if (blocked_.blocked()) {
    mode_ = msg::UgvMode::kBlocked;
  } else if (!ekf_.initialized()) {
    mode_ = msg::UgvMode::kWaitingForInit;
  } else if (arrived_) {
    mode_ = msg::UgvMode::kArrived;
  } else if (stopped_for_support_ || awaiting_fix_) {
    mode_ = msg::UgvMode::kWaitingForSupport;
  } else if (no_path_) {
    mode_ = msg::UgvMode::kNoPath;
  } else if (stopped_for_robot_) {
    mode_ = msg::UgvMode::kWaitingForRobot;
  } else {
    mode_ = msg::UgvMode::kDriving;
  }
  blocked_reason_ = mode_ == msg::UgvMode::kBlocked ? blocked_.reason() : msg::BlockedReason::kNone;
  if (mode_ != msg::UgvMode::kDriving || trajectory_.empty()) {
    controller_.hold();
    command(now, 0.0, 0.0);
    return;
  }
  if (vias_left_ > 0 && (ekf_.pose().p - target()).norm() <= config_.via_pass_radius_m) {
    --vias_left_;  // passed: on to the next, without stopping
    replan_requested_ = true;
  }
  const ControlOutput out = controller_.step(ekf_.pose(), trajectory_, dt);
  cross_track_m_ = out.cross_track_m;
  if (out.at_goal && vias_left_ == 0 &&
      (ekf_.pose().p - goal_).norm() <= config_.controller.goal_tolerance_m) {
    if (sure_of_position()) {
      arrived_ = true;
      mode_ = msg::UgvMode::kArrived;
    } else {
      awaiting_fix_ = true;
      mode_ = msg::UgvMode::kWaitingForSupport;
      controller_.hold();
    }
    command(now, 0.0, 0.0);
    return;
  }
  if (out.at_goal) replan_requested_ = true;  // the end of a cut plan: plan the rest
  command(now, out.v_mps, out.omega_radps);
}

// --- planning loop (10 Hz)
// ------------------------------------------------------------------------

void UgvNavTask::on_overrun(Duration) {
  governor_.on_overrun();
  ++health_.overruns;
}

void UgvNavTask::planning_step(TimePoint now) {
  // Persistent overruns (either loop): predict less far ahead rather than fall behind.
  health_.degradation = governor_.update();
  predictor_.set_horizon_scale(1.0 - 0.25 * health_.degradation);
  keep_map_window();
  read_map_patches(now);
  read_other_ugvs(now);
  sum_stamp_counters();
  if (!fleet_.has_estimate()) {
    // Nothing we would publish can be stamped in fleet time yet: wait for the first exchange.
    blocked_.update(now, msg::BlockedReason::kNotLocalised);
    return;
  }
  if (!ekf_.initialized()) {
    // Not localised yet: ask the UAV to come to where the mission plan says we are.
    blocked_.update(now, msg::BlockedReason::kNotLocalised);
    SupportNeed need;
    need.needed = config_.has_start_guess && !blocked_.blocked();
    need.collision_point = need.support_point = config_.start_guess.p;
    msg::CollisionInfo ci;
    if (support_.update(now, config_.id, need, ci)) publish_request(ci);
    publish_status(now);
    return;
  }
  if (!start_) start_ = ekf_.pose().p;
  if (ekf_.counters().resets != ekf_resets_seen_) {
    ekf_resets_seen_ = ekf_.counters().resets;
    replan_requested_ = true;
  }
  // The UAV cannot see the ground under this robot (its body hides it): it is free, since the
  // robot stands on it.
  (void)map_.free_under(ekf_.pose().p, config_.body_radius_m);
  track_uncertainty();
  collect_others(now);
  if (!arrived_ && !aborted_ && !faulty() && replan_needed(now)) replan(now);
  predict_and_request(now);
  publish_status(now);
}

void UgvNavTask::sum_stamp_counters() {
  StampCounters sum;
  for (const StampGate* g : {&wheel_stamps_, &rpe_stamps_, &patch_stamps_, &nearby_stamps_})
    sum += g->counters();
  for (const Uav& u : uavs_)
    sum += u.stamps.counters();
  health_.stamps = sum;
}

// The map is a window of the site (limits.hpp) that moves with the robot: ahead towards the goal
// when the robot nears its edge. Before the estimator starts, where the mission plan says the
// robot is, so that the first patches land in it.
void UgvNavTask::keep_map_window() {
  Vec2 at;
  if (ekf_.initialized()) {
    at = ekf_.pose().p;
  } else if (config_.has_start_guess) {
    at = config_.start_guess.p;
  } else {
    return;
  }
  const std::optional<Vec2> origin =
      window_move(map_.geometry(), at, std::optional<Vec2>(target()), config_.map_window);
  if (!origin || !map_.move_to(*origin).is_ok()) return;
  ++health_.window_moves;
  replan_requested_ = true;  // the plan was cut at the old window's edge
}

void UgvNavTask::read_map_patches(TimePoint now) {
  msg::MapPatch patch;
  while (patches_in_.pop(patch)) {
    patch.stamp = fleet_.to_local(patch.stamp);
    if (patch.ugv_id != config_.id || !StampGate::passed(patch_stamps_.check(patch.stamp, now)) ||
        !map_.apply(patch)) {
      ++health_.patches_rejected;
    }
  }
  // New obstacles on the remaining path => replan.
  if (map_.counters().plan_cells_blocked != plan_blocked_seen_) {
    plan_blocked_seen_ = map_.counters().plan_cells_blocked;
    for (std::size_t i = controller_.progress(); i < trajectory_.size(); ++i) {
      if (map_.plan_blocked(trajectory_[i].p)) {
        replan_requested_ = true;
        break;
      }
    }
  }
}

// The UAV's list of the UGVs near us replaces what we knew within its radius: one not in it is
// farther. What we knew of those farther stays for a while (the lists between full ones have a
// smaller radius: see nearby_relay.hpp). Without lists (the UAV silent) the last ones age: see
// collect_others.
void UgvNavTask::read_other_ugvs(TimePoint now) {
  msg::NearbyUgvs m;
  while (nearby_in_.pop(m)) {
    if (m.ugv_id != config_.id || m.ugvs.size() > m.ugvs.capacity() ||
        !(m.radius_m >= 0.0 && m.radius_m <= 1e6)) {
      ++health_.statuses_rejected;
      continue;
    }
    const StampGate::Verdict v = nearby_stamps_.check(fleet_.to_local(m.stamp), now);
    if (v == StampGate::Verdict::kNotIncreasing) continue;  // duplicate or overtaken: dropped
    if (!StampGate::passed(v)) {
      ++health_.statuses_rejected;
      continue;
    }
    std::array<bool, limits::kMaxUgvs> in_list{};
    for (const msg::NearbyUgv& u : m.ugvs) {
      if (!plausible(u)) {
        ++health_.statuses_rejected;
        continue;
      }
      if (u.ugv_id == config_.id) continue;  // ourselves: never planned around
      OtherUgv& o = others_[u.ugv_id];
      o.known = true;
      o.listed = now;
      in_list[u.ugv_id] = true;
      o.heard = now - std::chrono::duration_cast<Duration>(
                          std::chrono::duration<double>(std::min(double{u.silent_s}, 1e6)));
      o.state = u;
      o.state.stamp = fleet_.to_local(u.stamp);
    }
    const Vec2 me = ekf_.pose().p;
    for (std::size_t id = 0; id < others_.size(); ++id) {
      OtherUgv& o = others_[id];
      if (!o.known || in_list[id]) continue;
      const double d = (Vec2(o.state.position_m[0], o.state.position_m[1]) - me).norm();
      if (!(d > m.radius_m - config_.nearby_margin_m) ||
          elapsed(now, o.listed, config_.nearby_keep))
        o.known = false;
    }
  }
}

void UgvNavTask::collect_others(TimePoint now) {
  others_predict_.clear();
  others_plan_.clear();
  const Vec2 me = ekf_.pose().p;
  const GridGeometry2d& g = map_.geometry();
  const double map_diagonal = std::hypot(g.cells_x(), g.cells_y()) * g.resolution();
  for (const OtherUgv& o : others_) {
    if (!o.known) continue;
    // Where it is now, having kept its reported velocity since its status was stamped (for half
    // a second at most: a silent robot may have stopped).
    const msg::NearbyUgv& u = o.state;
    const double speed = u.velocity_mps, yaw = u.yaw_rad;
    const Vec2 v = speed * Vec2(std::cos(yaw), std::sin(yaw));
    const double age = std::clamp(to_seconds(now - u.stamp), 0.0, 0.5);
    const Vec2 p = Vec2(u.position_m[0], u.position_m[1]) + age * v;
    Mat2 cov;
    const double cxx = u.covariance_xy[0], cxy = u.covariance_xy[1], cyy = u.covariance_xy[2];
    cov << cxx, cxy, cxy, cyy;
    // Its own 3 sigma (capped: a robot lost on its own is not a wall), then as far as it can
    // have driven since it was last heard (our clock: another board's stamps do not tell).
    const double silent_s = std::max(to_seconds(now - o.heard), 0.0);
    const double extent =
        std::min(3.0 * sigma_major(cov), 2.0) + config_.other_ugv_max_speed_mps * silent_s;
    if (extent > map_diagonal) continue;  // it could be anywhere: no obstacle says anything
    if ((p - me).norm() - extent > config_.other_ugv_range_m) continue;
    (void)others_predict_.push_back(
        {p, config_.map.predict_inflation_m + config_.body_radius_m + extent, v});
    (void)others_plan_.push_back(
        {p, config_.map.plan_inflation_m + config_.body_radius_m + extent});
  }
}

bool UgvNavTask::replan_needed(TimePoint now) const {
  if (no_path_) return elapsed(now, last_plan_, config_.no_path_retry);
  return replan_requested_ || trajectory_.empty() ||
         elapsed(now, last_plan_, config_.replan_period) ||
         cross_track_m_ > config_.replan_cross_track_m;
}

void UgvNavTask::replan(TimePoint now) {
  last_plan_ = now;
  replan_requested_ = false;
  ++health_.plans;
  // A goal beyond the map's window: plan to where the straight line to it leaves the window (a
  // metre inside); the window moves on before the robot gets there.
  const Vec2 here = ekf_.pose().p;
  const Vec2 to = clip_into(map_.geometry(), here, target(), kWindowGoalMargin_m);
  // Room for the uncertainty it has had lately, beyond what the P-Map's inflation leaves.
  const double room = config_.map.plan_inflation_m - config_.map.predict_inflation_m;
  const double band = config_.map.clearance_m - config_.map.plan_inflation_m;
  planner_.set_clearance_share(band > 0.0 ? (recent_3sigma_m_ - room) / band : 0.0);
  const PlanResult r = planner_.plan(map_, here, to, others_plan_, path_);
  if (r != PlanResult::kOk || !trajectory_.build(path_, controller_.last_v(), config_.limits)) {
    ++health_.plan_failures;
    no_path_ = true;
    trajectory_.clear();
    return;
  }
  no_path_ = false;
  controller_.reset();
  cross_track_m_ = 0.0;
}

void UgvNavTask::predict_and_request(TimePoint now) {
  SupportNeed need;
  if (arrived_ || trajectory_.empty()) {
    prediction_ = Prediction{};
  } else {
    predictor_.predict(ekf_.state(), ekf_.state_covariance(), trajectory_, controller_.progress(),
                       map_, others_predict_, prediction_);
  }
  // The first colliding ellipse was sampled up to one step after the true first contact.
  const double t_soonest = prediction_.time_s - predictor_.config().dt_s;
  const bool was_stopped = stopped_for_support_ || stopped_for_robot_;
  switch (prediction_.kind) {
    case CollisionKind::kMap:
      support_cause_ = support_cause_of(prediction_.cause);
      need.needed = true;
      need.collision_point = prediction_.point;
      need.support_point = prediction_.support_point;
      need.time_to_collision_s = prediction_.time_s;
      stopped_for_support_ =
          t_soonest < config_.stop_time_s + (stopped_for_support_ ? config_.resume_margin_s : 0.0);
      stopped_for_robot_ = false;
      break;
    case CollisionKind::kRobot:
      // The UAV cannot move the other UGV: replan around it and wait if it is close.
      stopped_for_support_ = false;
      stopped_for_robot_ = t_soonest < config_.robot_stop_time_s;
      replan_requested_ = true;
      break;
    case CollisionKind::kNone:
      stopped_for_support_ = stopped_for_robot_ = false;
      break;
  }
  if (was_stopped && !stopped_for_support_ && !stopped_for_robot_) replan_requested_ = true;
  // Held by another UGV for long (short releases, a replanned step or two, do not count as
  // leaving): a fix where it stands shrinks its own part of the distance kept.
  if (stopped_for_robot_) {
    if (!robot_held_ || now - robot_held_last_ > kRobotReleaseGap) robot_stop_since_ = now;
    robot_held_ = true;
    robot_held_last_ = now;
  }
  const bool held_lately = robot_held_ && now - robot_held_last_ <= kRobotReleaseGap;
  if (held_lately && !need.needed && config_.robot_fix_after_s > 0.0 &&
      now - robot_stop_since_ >= seconds(config_.robot_fix_after_s)) {
    support_cause_ = SupportCause::kUncertainNow;
    need.needed = true;
    need.collision_point = prediction_.point;
    need.support_point = ekf_.pose().p;
    need.time_to_collision_s = 0.0;
  }
  if (awaiting_fix_) {  // the UAV to come to the goal and see it there
    support_cause_ = SupportCause::kGoalFix;
    need.needed = true;
    need.collision_point = goal_;
    need.support_point = ekf_.pose().p;
    need.time_to_collision_s = 0.0;
  }
  blocked_.update(now, standing_reason());
  if (blocked_.blocked()) need = SupportNeed{};   // let the UAV serve the others for a while
  if (paused_ || aborted_) need = SupportNeed{};  // held: it will not drive into anything
  msg::CollisionInfo ci;
  if (support_.update(now, config_.id, need, ci)) publish_request(ci);
}

void UgvNavTask::track_uncertainty() {
  const double dt = std::chrono::duration<double>(config_.schedule.planning.period).count();
  const double fade =
      config_.clearance_memory_s > 0.0 ? std::exp(-dt / config_.clearance_memory_s) : 0.0;
  recent_3sigma_m_ = std::max(three_sigma_m(), recent_3sigma_m_ * fade);
}

double UgvNavTask::three_sigma_m() const {
  return sigma_ellipse(ekf_.pose().p, ekf_.covariance().topLeftCorner<2, 2>(), 3.0).axes().a_m;
}

bool UgvNavTask::sure_of_position() const {
  return three_sigma_m() <= config_.arrival_max_uncertainty_m;
}

msg::BlockedReason UgvNavTask::standing_reason() const {
  if (arrived_ || faulty() || paused_ || aborted_)
    return msg::BlockedReason::kNone;  // done, or its own mode
  if (no_path_ || trajectory_.empty()) return msg::BlockedReason::kNoPath;
  if (stopped_for_support_ || awaiting_fix_) return msg::BlockedReason::kNotCleared;
  if (stopped_for_robot_) return msg::BlockedReason::kRobotInTheWay;
  return msg::BlockedReason::kNone;
}

void UgvNavTask::publish_request(msg::CollisionInfo& ci) {
  ci.stamp = fleet_.to_fleet(ci.stamp);
  if (transport_.publish(ci)) ++health_.support_messages;
}

GoalResult UgvNavTask::request_goal(const Vec2& goal) {
  if (!all_finite(goal)) return GoalResult::kNotFinite;
  if (goal.cwiseAbs().maxCoeff() > limits::kMaxSiteHalf_m) return GoalResult::kOutsideMap;
  // Beyond the map's window its cells are unknown (state() says so): not refused.
  if (map_.state(map_.geometry().cell_of(goal)) == CellState::kOccupied)
    return GoalResult::kInObstacle;
  goal_ = goal;
  vias_left_ = 0;
  arrived_ = false;
  aborted_ = false;
  awaiting_fix_ = false;
  replan_requested_ = true;
  return GoalResult::kAccepted;
}

CommandResult UgvNavTask::request_command(std::uint8_t command) {
  switch (command) {
    case static_cast<std::uint8_t>(UgvCommand::kPause):
      paused_ = true;
      return CommandResult::kAccepted;
    case static_cast<std::uint8_t>(UgvCommand::kResume):
      if (!paused_) return CommandResult::kNotPaused;
      paused_ = false;
      replan_requested_ = true;  // from where it stands now
      return CommandResult::kAccepted;
    case static_cast<std::uint8_t>(UgvCommand::kAbort):
      aborted_ = true;
      awaiting_fix_ = false;
      trajectory_.clear();
      prediction_ = Prediction{};
      return CommandResult::kAccepted;
    case static_cast<std::uint8_t>(UgvCommand::kReturnToStart):
      if (!start_) return CommandResult::kNoStart;
      return request_goal(*start_) == GoalResult::kAccepted ? CommandResult::kAccepted
                                                            : CommandResult::kStartRefused;
    default:
      return CommandResult::kUnknown;
  }
}

void UgvNavTask::publish_status(TimePoint now) {
  msg::UgvStatus s;
  s.stamp = fleet_.to_fleet(now);
  s.ugv_id = config_.id;
  s.mode = mode_;
  if (ekf_.initialized()) {
    const Pose2 p = ekf_.pose();
    s.position_m[0] = p.p.x();
    s.position_m[1] = p.p.y();
    s.yaw_rad = p.yaw_rad;
    const Mat3 P = ekf_.covariance();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c)
        s.covariance[3 * r + c] = P(r, c);
    }
  } else if (config_.has_start_guess) {
    s.position_m[0] = config_.start_guess.p.x();
    s.position_m[1] = config_.start_guess.p.y();
    s.yaw_rad = config_.start_guess.yaw_rad;
    const double var = config_.start_guess_sigma_m * config_.start_guess_sigma_m;
    s.covariance[0] = s.covariance[4] = var;
    s.covariance[8] = M_PI * M_PI;
  }
  s.velocity_mps = v_cmd_;
  s.yaw_rate_radps = omega_cmd_;
  s.goal_m[0] = goal_.x();
  s.goal_m[1] = goal_.y();
  s.waiting_time_s = waiting_time_s();
  s.blocked_reason = blocked_reason_;
  s.clock_error_s = fleet_.error_s(now);
  s.rejected_inputs = static_cast<std::uint32_t>(health_.rejected_inputs());
  s.overruns = static_cast<std::uint32_t>(health_.overruns);
  s.degradation = static_cast<std::uint8_t>(health_.degradation);
  s.base_fault = base_fault_.fault;
  s.base_error = base_fault_.code;
  fill_scout_point(s);
  (void)transport_.publish(s);
  last_status_ = s;
}

// The first trajectory sample ahead whose CP-Map cell is blocked by an unknown cell: the stop
// the UGV will have to ask support for unless the UAV maps there first.
void UgvNavTask::fill_scout_point(msg::UgvStatus& s) const {
  s.scout_in_s = -1.0;
  if (config_.scout_range_m <= 0.0 || trajectory_.empty() || arrived_ ||
      mode_ == msg::UgvMode::kAborted)
    return;
  const std::size_t from = std::min(controller_.progress(), trajectory_.size() - 1);
  const TrajectorySample& here = trajectory_[from];
  const GridGeometry2d& g = map_.geometry();
  for (std::size_t i = from; i < trajectory_.size(); ++i) {
    const TrajectorySample& q = trajectory_[i];
    if (q.s_m - here.s_m > config_.scout_range_m) return;
    const CellIndex c = g.cell_of(q.p);
    if (g.contains(c) && !map_.near_unknown_at(g.index(c))) continue;
    s.scout_point_m[0] = q.p.x();
    s.scout_point_m[1] = q.p.y();
    s.scout_in_s = std::max(0.0, q.t_s - here.t_s);
    return;
  }
}

}  // namespace colag::ugv
