#pragma once
// The UAV's flight controller and (optionally) odometry on PX4, over DDS through PX4's uXRCE-DDS
// agent: the HAL's FlightController (setpoints, the offboard protocol of OffboardSequencer,
// landing) and OdometrySource (VehicleOdometry). Everything PX4 sees is in its own frames (NED
// world, FRD body) and its local frame; everything the firmware sees is ENU/FLU in the mission's
// world: converted here, by frames.hpp, and by `origin` (where PX4's local frame lies in the
// world). The control loop allocates nothing: fixed-size messages are taken on loan, and the
// writes (Cyclone allocates in dds_write) run on a thread of the driver's own, as the fleet
// transport's do: the loop leaves the newest setpoint and heartbeat, and its commands, in an
// outbox.
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "colag/common/geometry.hpp"
#include "colag/hal/dds/device_participant.hpp"
#include "colag/hal/flight_controller.hpp"
#include "colag/hal/odometry_source.hpp"
#include "colag/hal/px4/offboard_sequencer.hpp"
#include "colag/hal/px4/px4_release.hpp"

namespace colag::hal::px4 {

struct Px4DriverConfig {
  std::uint32_t dds_domain = 0;  // the agent's (ROS_DOMAIN_ID of the agent, 0 by default)
  std::string ns;                // the agent's namespace ("" -> rt/fmu/...)
  Px4Release release = Px4Release::kV116;
  std::uint8_t target_system = 1;  // PX4's MAV_SYS_ID
  std::uint8_t target_component = 1;
  std::uint8_t source_system = 1;
  std::uint16_t source_component = 1;
  // PX4's local frame in the mission's world: the pose of its origin, with x east and z up (its
  // NED axes turned to ENU). Identity when the mission's world is PX4's local frame.
  Pose3 origin;
  OffboardConfig offboard;
  Duration heartbeat_period = std::chrono::milliseconds(50);  // OffboardControlMode, 20 Hz
  // VehicleOdometry's stamp: when it arrived, less its age inside PX4 (timestamp -
  // timestamp_sample), less this (the agent and the link).
  Duration odometry_latency = Duration::zero();
};

struct Px4Counters {
  std::uint64_t setpoints = 0;
  std::uint64_t heartbeats = 0;
  std::uint64_t commands = 0;
  std::uint64_t acks = 0;
  std::uint64_t statuses = 0;
  std::uint64_t odometry = 0;
  std::uint64_t odometry_rejected = 0;  // not finite, an unsupported frame
  std::uint64_t write_errors = 0;
};

class Px4FlightController final : public FlightController, public OdometrySource {
 public:
  Px4FlightController() = default;
  ~Px4FlightController() override;
  Px4FlightController(const Px4FlightController&) = delete;
  Px4FlightController& operator=(const Px4FlightController&) = delete;
  // Creates the participant and the topics; false with `error` naming what failed.
  bool init(const Px4DriverConfig& config, std::string& error);

  // FlightController
  Status send_setpoint(const FlightSetpoint& sp) override;
  FlightStatus update(TimePoint now) override;
  void land(TimePoint now) override;
  // OdometrySource (PX4's estimate; FAST-LIO's is hal/ros2's Ros2Odometry)
  bool poll(UavState& out) override;

  const OffboardSequencer& sequencer() const { return seq_; }
  Px4Counters counters() const;  // a snapshot (the writer thread counts its writes)
  // Why it waits or failed, for the log: "" or a sentence (e.g. the release seen on the bus).
  const std::string& diagnosis() const { return diagnosis_; }
  const Px4DriverConfig& config() const { return config_; }

 private:
  // What the control loop hands the writer thread: the newest setpoint (NED, local) and
  // heartbeat, and the commands in order.
  struct Outbox {
    std::mutex mutex;
    std::condition_variable wake;
    bool stop = false;
    bool setpoint_due = false;
    std::array<float, 11> setpoint{};  // position, velocity, acceleration, yaw, yawspeed
    bool heartbeat_due = false;
    std::array<Px4Command, 4> commands{};
    std::size_t command_count = 0;
  };

  void read_px4(TimePoint now);
  void check_release();
  void send_command(const Px4Command& c);
  void report();
  void write_loop();

  Px4DriverConfig config_;
  dds::DeviceParticipant dds_;
  dds_entity_t offboard_writer_ = 0, setpoint_writer_ = 0, command_writer_ = 0;
  dds_entity_t status_reader_ = 0, ack_reader_ = 0, odometry_reader_ = 0;
  dds_entity_t publications_ = 0;  // the bus's writers, to name a release mismatch
  OffboardSequencer seq_;
  TimePoint last_heartbeat_ = kNever;
  bool was_streaming_ = false;
  TimePoint last_release_check_ = kNever;
  UavState odometry_;
  bool odometry_fresh_ = false;
  OffboardSequencer::State reported_ = OffboardSequencer::State::kWaitingForPx4;
  msg::FlightFault reported_fault_ = msg::FlightFault::kNone;
  Px4Counters counters_;  // what the control loop counts
  // What the writer thread counts.
  std::atomic<std::uint64_t> setpoints_{0}, heartbeats_{0}, commands_{0}, write_errors_{0};
  std::uint64_t commands_dropped_ = 0;  // the outbox full (never at 4 commands a protocol step)
  Outbox outbox_;
  std::thread writer_;
  std::string diagnosis_;
};

}  // namespace colag::hal::px4
