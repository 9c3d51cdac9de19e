#pragma once
// The UGV's base on a CAN bus, whichever protocol it speaks: the WheelOdometry and Drive the
// task is given, the receive filters a SocketCAN bus should set, and one line of counters.
#include <cstdint>
#include <optional>

#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/hal/can/base_config.hpp"
#include "colag/hal/can/can_wheel_odometry.hpp"

namespace colag::hal::can {

struct IdFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;
  bool extended = false;
};
using IdFilters = StaticVector<IdFilter, 4>;

// The frames the base sends us (nothing else needs to wake the board up).
IdFilters base_filters(const BaseConfig& config);
// The frames we send the base: what an emulator of the device listens to.
IdFilters command_filters(const BaseConfig& config);

// What every protocol's driver counts, for the log at exit.
struct BaseCounters {
  std::uint64_t frames = 0;
  std::uint64_t samples = 0;
  std::uint64_t bad_frames = 0;   // malformed frames of the base's ids
  std::uint64_t lost = 0;         // gaps in alive counters, where the protocol has them
  std::uint64_t implausible = 0;  // wheel steps beyond the limits, or time not advancing
  std::uint64_t recoveries = 0;   // faults the driver cleared itself (an ODrive watchdog trip)
};

class CanBase {
 public:
  CanBase(CanBus& bus, const BaseConfig& config, const WheelGeometry& wheels);
  CanBase(const CanBase&) = delete;
  CanBase& operator=(const CanBase&) = delete;

  WheelOdometry& odometry() { return *odometry_; }
  Drive& drive() { return *drive_; }
  BaseCounters counters() const;

 private:
  std::optional<CanWheelOdometry> colag_odometry_;
  std::optional<CanDrive> colag_drive_;
  std::optional<OdriveBase> odrive_;
  std::optional<AgilexBase> agilex_;
  WheelOdometry* odometry_ = nullptr;
  Drive* drive_ = nullptr;
};

}  // namespace colag::hal::can
