#pragma once
#include "colag/common/time.hpp"

namespace colag::hal {

// Body twist of a differential-drive UGV measured by its wheel encoders.
struct WheelOdometrySample {
  TimePoint stamp;
  double v_mps = 0.0;        // forward speed
  double omega_radps = 0.0;  // yaw rate, counter-clockwise positive
};

class WheelOdometry {
 public:
  virtual ~WheelOdometry() = default;
  // Returns the next sample not yet read (oldest first); false when there is none.
  virtual bool poll(WheelOdometrySample& out) = 0;
  // Time of the newest sample ever received; the task's watchdog compares it with now.
  virtual TimePoint last_sample_time() const = 0;
};

}  // namespace colag::hal
