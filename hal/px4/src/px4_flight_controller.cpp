#include "colag/hal/px4/px4_flight_controller.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "colag/common/frames.hpp"
#include "colag/hal/dds/take_one.hpp"
#include "px4_msgs.h"
#include "px4_msgs_v1_15.h"

namespace colag::hal::px4 {

namespace {

using dds::take_one;

const char* to_string(OffboardSequencer::State s) {
  using S = OffboardSequencer::State;
  switch (s) {
    case S::kWaitingForPx4:
      return "waiting for PX4";
    case S::kPriming:
      return "streaming offboard setpoints";
    case S::kModeRequested:
      return "asked for offboard mode";
    case S::kArmRequested:
      return "asked to arm";
    case S::kTakingOff:
      return "taking off";
    case S::kInControl:
      return "in control (offboard, armed)";
    case S::kLanding:
      return "landing";
    case S::kLanded:
      return "landed";
    case S::kLost:
      return "no longer in control";
  }
  return "unknown";
}

Px4Status status_of(std::uint8_t arming_state, std::uint8_t nav_state, bool failsafe) {
  return {arming_state == kArmingStateArmed, nav_state, failsafe};
}

}  // namespace

bool Px4FlightController::init(const Px4DriverConfig& config, std::string& error) {
  config_ = config;
  seq_ = OffboardSequencer(config.offboard);
  if (!dds_.init(config.dds_domain)) {
    error =
        "PX4 link on DDS domain " + std::to_string(config.dds_domain) + ": " + dds_.last_error();
    return false;
  }
  const Px4Release r = config.release;
  const std::string& ns = config.ns;
  offboard_writer_ = dds_.writer(px4_dds_topic(r, Px4Topic::kOffboardControlMode, ns),
                                 px4_msgs_msg_dds__OffboardControlMode__desc);
  setpoint_writer_ = dds_.writer(px4_dds_topic(r, Px4Topic::kTrajectorySetpoint, ns),
                                 px4_msgs_msg_dds__TrajectorySetpoint__desc);
  command_writer_ = dds_.writer(px4_dds_topic(r, Px4Topic::kVehicleCommand, ns),
                                px4_msgs_msg_dds__VehicleCommand__desc);
  ack_reader_ = dds_.reader(px4_dds_topic(r, Px4Topic::kVehicleCommandAck, ns),
                            px4_msgs_msg_dds__VehicleCommandAck__desc, 8);
  odometry_reader_ = dds_.reader(px4_dds_topic(r, Px4Topic::kVehicleOdometry, ns),
                                 px4_msgs_msg_dds__VehicleOdometry__desc, 8);
  // Both releases' VehicleStatus travel as px4_msgs::msg::dds_::VehicleStatus_; v1.15's layout
  // is declared under another module so that both link: its descriptor takes the wire name.
  status_reader_ = dds_.reader(px4_dds_topic(r, Px4Topic::kVehicleStatus, ns),
                               r == Px4Release::kV115 ? px4_msgs_v1_15_msg_dds__VehicleStatus__desc
                                                      : px4_msgs_msg_dds__VehicleStatus__desc,
                               4, "px4_msgs::msg::dds_::VehicleStatus_");
  if (!offboard_writer_ || !setpoint_writer_ || !command_writer_ || !ack_reader_ ||
      !odometry_reader_ || !status_reader_) {
    error = "PX4 link: " + dds_.last_error();
    return false;
  }
  publications_ =
      dds_create_reader(dds_.participant(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
  writer_ = std::thread([this] { write_loop(); });
  return true;
}

Px4FlightController::~Px4FlightController() {
  if (writer_.joinable()) {
    {
      const std::lock_guard lock(outbox_.mutex);
      outbox_.stop = true;
    }
    outbox_.wake.notify_one();
    writer_.join();
  }
}

Px4Counters Px4FlightController::counters() const {
  Px4Counters c = counters_;
  c.setpoints = setpoints_.load();
  c.heartbeats = heartbeats_.load();
  c.commands = commands_.load();
  c.write_errors = write_errors_.load();
  return c;
}

// The writer thread: whatever the control loop left in the outbox, to DDS.
void Px4FlightController::write_loop() {
  for (;;) {
    bool setpoint = false, heartbeat = false;
    std::array<float, 11> sp{};
    std::array<Px4Command, 4> commands{};
    std::size_t n = 0;
    {
      std::unique_lock lock(outbox_.mutex);
      outbox_.wake.wait(lock, [&] {
        return outbox_.stop || outbox_.setpoint_due || outbox_.heartbeat_due ||
               outbox_.command_count > 0;
      });
      if (outbox_.stop) return;
      setpoint = std::exchange(outbox_.setpoint_due, false);
      heartbeat = std::exchange(outbox_.heartbeat_due, false);
      sp = outbox_.setpoint;
      n = std::exchange(outbox_.command_count, 0);
      commands = outbox_.commands;
    }
    for (std::size_t i = 0; i < n; ++i) {
      px4_msgs_msg_dds__VehicleCommand_ m{};
      m.timestamp = 0;
      m.param1 = commands[i].param1;
      m.param2 = commands[i].param2;
      m.command = commands[i].command;
      m.target_system = config_.target_system;
      m.target_component = config_.target_component;
      m.source_system = config_.source_system;
      m.source_component = config_.source_component;
      m.from_external = true;
      ++(dds_write(command_writer_, &m) < 0 ? write_errors_ : commands_);
    }
    if (heartbeat) {
      px4_msgs_msg_dds__OffboardControlMode_ m{};
      m.timestamp = 0;
      m.position = true;  // position control; velocity and acceleration are its feed-forward
      ++(dds_write(offboard_writer_, &m) < 0 ? write_errors_ : heartbeats_);
    }
    if (setpoint) {
      px4_msgs_msg_dds__TrajectorySetpoint_ m{};
      m.timestamp = 0;  // PX4 stamps it on arrival: no clock of PX4's needed
      for (std::size_t i = 0; i < 3; ++i) {
        m.position[i] = sp[i];
        m.velocity[i] = sp[3 + i];
        m.acceleration[i] = sp[6 + i];
        m.jerk[i] = std::numeric_limits<float>::quiet_NaN();  // not controlled
      }
      m.yaw = sp[9];
      m.yawspeed = sp[10];
      ++(dds_write(setpoint_writer_, &m) < 0 ? write_errors_ : setpoints_);
    }
  }
}

Status Px4FlightController::send_setpoint(const FlightSetpoint& sp) {
  // The mission's world (ENU) -> PX4's local frame (ENU axes) -> NED.
  const Pose3 to_local = config_.origin.inverse();
  const Vec3 p = frames::enu_to_ned(to_local.transform(sp.position_m));
  const Vec3 v = frames::enu_to_ned(to_local.q * sp.velocity_mps);
  const Vec3 a = frames::enu_to_ned(to_local.q * sp.acceleration_mps2);
  if (!all_finite(p) || !all_finite(v) || !all_finite(a) || !std::isfinite(sp.yaw_rad))
    return {Errc::kInvalidArgument, "PX4: setpoint not finite"};
  seq_.on_setpoint(sp.stamp);
  if (!seq_.streaming(sp.stamp)) return Status::ok();  // held until PX4 is ours
  {
    const std::lock_guard lock(outbox_.mutex);
    for (std::size_t i = 0; i < 3; ++i) {
      outbox_.setpoint[i] = static_cast<float>(p[static_cast<int>(i)]);
      outbox_.setpoint[3 + i] = static_cast<float>(v[static_cast<int>(i)]);
      outbox_.setpoint[6 + i] = static_cast<float>(a[static_cast<int>(i)]);
    }
    outbox_.setpoint[9] =
        static_cast<float>(frames::enu_yaw_to_ned(sp.yaw_rad - yaw_of(config_.origin.q)));
    outbox_.setpoint[10] = std::numeric_limits<float>::quiet_NaN();
    outbox_.setpoint_due = true;
  }
  outbox_.wake.notify_one();
  return Status::ok();
}

FlightStatus Px4FlightController::update(TimePoint now) {
  read_px4(now);
  if (seq_.state() == OffboardSequencer::State::kWaitingForPx4 &&
      elapsed(now, last_release_check_, std::chrono::seconds(1))) {
    last_release_check_ = now;
    check_release();
  }
  Px4Command c;
  if (seq_.step(now, c)) send_command(c);
  const bool streaming = seq_.streaming(now);
  if (streaming && elapsed(now, last_heartbeat_, config_.heartbeat_period)) {
    last_heartbeat_ = now;
    {
      const std::lock_guard lock(outbox_.mutex);
      outbox_.heartbeat_due = true;
    }
    outbox_.wake.notify_one();
  } else if (!streaming && was_streaming_) {
    // The stream ends now: a heartbeat or setpoint the writer has not taken yet stays unsent,
    // so PX4's own failsafe is not held off by one more message.
    const std::lock_guard lock(outbox_.mutex);
    outbox_.heartbeat_due = false;
    outbox_.setpoint_due = false;
  }
  was_streaming_ = streaming;
  report();
  return seq_.status();
}

void Px4FlightController::land(TimePoint now) {
  seq_.land(now);
  Px4Command c;
  if (seq_.step(now, c)) send_command(c);
  report();
}

bool Px4FlightController::poll(UavState& out) {
  if (!odometry_fresh_) return false;
  odometry_fresh_ = false;
  out = odometry_;
  return true;
}

void Px4FlightController::read_px4(TimePoint now) {
  while (take_one<px4_msgs_msg_dds__VehicleCommandAck_>(ack_reader_, [&](const auto& a) {
    ++counters_.acks;
    seq_.on_ack(now, a.command, a.result);
  })) {
  }
  // Both layouts put arming_state, nav_state and failsafe at the same place in the struct
  // (the two fields v1.15 adds come after them), but read each as what it is.
  const bool v115 = config_.release == Px4Release::kV115;
  while (v115 ? take_one<px4_msgs_v1_15_msg_dds__VehicleStatus_>(
                    status_reader_,
                    [&](const auto& s) {
                      ++counters_.statuses;
                      seq_.on_status(now, status_of(s.arming_state, s.nav_state, s.failsafe));
                    })
              : take_one<px4_msgs_msg_dds__VehicleStatus_>(status_reader_, [&](const auto& s) {
                  ++counters_.statuses;
                  seq_.on_status(now, status_of(s.arming_state, s.nav_state, s.failsafe));
                })) {
  }
  while (take_one<px4_msgs_msg_dds__VehicleOdometry_>(odometry_reader_, [&](const auto& o) {
    seq_.heard(now);
    ++counters_.odometry;
    // Position and attitude in PX4's local NED frame (pose_frame 1); FRD-world (2, a heading
    // of its own choosing) is refused: nothing here knows its heading.
    const Vec3 p_ned(o.position[0], o.position[1], o.position[2]);
    const Quat q_ned(o.q[0], o.q[1], o.q[2], o.q[3]);
    if (o.pose_frame != 1 || !all_finite(p_ned) || !q_ned.coeffs().allFinite() ||
        q_ned.norm() < 0.5) {
      ++counters_.odometry_rejected;
      return;
    }
    const Pose3& origin = config_.origin;
    const Quat q_world = (origin.q * frames::ned_frd_to_enu_flu(q_ned.normalized())).normalized();
    Vec3 v = Vec3::Zero();
    const Vec3 v_raw(o.velocity[0], o.velocity[1], o.velocity[2]);
    if (all_finite(v_raw)) {
      if (o.velocity_frame == 1) v = origin.q * frames::ned_to_enu(v_raw);  // local NED
      if (o.velocity_frame == 3) v = q_world * frames::frd_to_flu(v_raw);   // body FRD
    }
    const Vec3 w(o.angular_velocity[0], o.angular_velocity[1], o.angular_velocity[2]);
    // Its age inside PX4 (both stamps are PX4's clock), then the link's.
    const std::uint64_t age_us =
        o.timestamp >= o.timestamp_sample && o.timestamp_sample > 0
            ? std::min<std::uint64_t>(o.timestamp - o.timestamp_sample, 500'000)
            : 0;
    odometry_.stamp = now - std::chrono::microseconds(age_us) - config_.odometry_latency;
    odometry_.pose = {origin.transform(frames::ned_to_enu(p_ned)), q_world};
    odometry_.velocity_mps = v;
    odometry_.yaw_rate_radps = all_finite(w) ? (q_world * frames::frd_to_flu(w)).z() : 0.0;
    odometry_fresh_ = true;
  })) {
  }
}

// While PX4 is not heard: is the other release on the bus? Its status topic has another name.
void Px4FlightController::check_release() {
  if (publications_ <= 0) return;
  void* samples[16] = {nullptr};
  dds_sample_info_t info[16];
  const dds_return_t n = dds_take(publications_, samples, info, 16, 16);
  for (dds_return_t i = 0; i < n; ++i) {
    if (!info[i].valid_data) continue;
    const auto* e = static_cast<const dds_builtintopic_endpoint_t*>(samples[i]);
    const Result<Px4Release> seen = release_of_status_topic(e->topic_name, config_.ns);
    if (seen && seen.value() != config_.release) {
      seq_.set_wrong_release(true);
      diagnosis_ = std::string("PX4 publishes ") + e->topic_name + " (release " +
                   to_string(seen.value()) + "), but px4.release is " + to_string(config_.release) +
                   ": set px4.release to " + to_string(seen.value());
    }
  }
  if (n > 0) dds_return_loan(publications_, samples, n);
}

void Px4FlightController::send_command(const Px4Command& c) {
  {
    const std::lock_guard lock(outbox_.mutex);
    if (outbox_.command_count == outbox_.commands.size()) {
      ++commands_dropped_;
      return;
    }
    outbox_.commands[outbox_.command_count++] = c;
  }
  outbox_.wake.notify_one();
}

// One line on every change of state or reason: what a user reads in the journal.
void Px4FlightController::report() {
  const FlightStatus s = seq_.status();
  if (seq_.state() == reported_ && s.fault == reported_fault_) return;
  reported_ = seq_.state();
  reported_fault_ = s.fault;
  std::fprintf(stderr, "px4: %s%s%s%s%s\n", to_string(seq_.state()),
               s.fault == msg::FlightFault::kNone ? "" : " (",
               s.fault == msg::FlightFault::kNone ? "" : msg::to_string(s.fault),
               s.fault == msg::FlightFault::kNone ? "" : ")",
               s.fault == msg::FlightFault::kWrongRelease ? (": " + diagnosis_).c_str() : "");
}

}  // namespace colag::hal::px4
