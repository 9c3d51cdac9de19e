#pragma once
#include "colag/common/status.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/ugv_status.hpp"

namespace colag::hal {

// Body-twist command for a differential-drive UGV; the driver converts it to wheel speeds
// (and CAN frames) and enforces the wheel-speed limits of the hardware.
struct DriveCommand {
  TimePoint stamp;
  double v_mps = 0.0;
  double omega_radps = 0.0;
};

// Whether the base takes commands, and why not: the task stops (kFault) while it does not.
struct DriveHealth {
  msg::BaseFault fault = msg::BaseFault::kNone;
  std::uint32_t code = 0;  // the base's own error code, when it reports one
};

class Drive {
 public:
  virtual ~Drive() = default;
  virtual Status command(const DriveCommand& cmd) = 0;
  // Commands zero speed; must work even after command() failed.
  virtual Status stop(TimePoint now) = 0;
  // Read every control period (after the odometry was polled): the base's faults as the driver
  // last heard them. A driver that cannot know any reports none.
  virtual DriveHealth health() const { return {}; }
  // The program ends: zero speed, then whatever leaves the base safe unattended (e.g. motor
  // controllers to idle).
  virtual void shutdown(TimePoint now) {
    (void)stop(now);
    (void)stop(now);
  }
};

}  // namespace colag::hal
