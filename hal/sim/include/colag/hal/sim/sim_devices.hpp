#pragma once
// The robots' "sim" HAL (SITL): the same HAL interfaces the firmware uses on a board, backed by
// colag_world over the sim link. Only the UGV's CAN bus is simulated for a UGV — its wheel
// odometry and drive are the real CAN drivers on top — and the UAV gets its flight controller,
// odometry, LiDAR and relative-pose device. Buffers are sized at construction; poll()/receive()
// copy from Cyclone's loaned samples and allocate nothing of ours.
#include <memory>
#include <vector>

#include "colag/common/limits.hpp"
#include "colag/hal/can_bus.hpp"
#include "colag/hal/flight_controller.hpp"
#include "colag/hal/lidar.hpp"
#include "colag/hal/odometry_source.hpp"
#include "colag/hal/relative_pose_sensor.hpp"
#include "colag/hal/sim/sim_link.hpp"

namespace colag::hal::sim {

// A UGV's CAN bus: frames from the world's motor controller in, the robot's commands out.
class SimCanBus final : public hal::CanBus {
 public:
  SimCanBus(SimLink& link, RobotId robot) : link_(link), robot_(robot) {}
  Status send(const hal::CanFrame& frame, TimePoint deadline) override;
  bool receive(hal::CanFrame& out) override;
  hal::CanBusStats stats() const override { return stats_; }

 private:
  SimLink& link_;
  RobotId robot_;
  hal::CanBusStats stats_;
};

class SimUavDevices final : public hal::FlightController,
                            public hal::OdometrySource,
                            public hal::Lidar,
                            public hal::RelativePoseSensor {
 public:
  explicit SimUavDevices(SimLink& link);

  Status send_setpoint(const hal::FlightSetpoint& sp) override;
  bool poll(hal::UavState& out) override;
  bool poll(hal::LidarScanView& out) override;
  std::size_t poll(std::span<hal::RelativePoseDetection> out) override;

  std::uint64_t malformed() const { return malformed_; }

 private:
  SimLink& link_;
  std::vector<hal::LidarPoint> points_, misses_;  // capacity kMaxLidarPoints each, at construction
  std::uint64_t malformed_ = 0;
};

}  // namespace colag::hal::sim
