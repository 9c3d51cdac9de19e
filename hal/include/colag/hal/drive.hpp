#pragma once
#include "colag/common/status.hpp"
#include "colag/common/time.hpp"

namespace colag::hal {

// Body-twist command for a differential-drive UGV; the driver converts it to wheel speeds
// (and CAN frames) and enforces the wheel-speed limits of the hardware.
struct DriveCommand {
  TimePoint stamp;
  double v_mps = 0.0;
  double omega_radps = 0.0;
};

class Drive {
 public:
  virtual ~Drive() = default;
  virtual Status command(const DriveCommand& cmd) = 0;
  // Commands zero speed; must work even after command() failed.
  virtual Status stop(TimePoint now) = 0;
};

}  // namespace colag::hal
