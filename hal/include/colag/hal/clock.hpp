#pragma once
#include "colag/common/time.hpp"

namespace colag::hal {

// The only source of time for task code. Monotonic on a board; owned by the lock-step
// executor in simulation, so a simulated run is reproducible.
class Clock {
 public:
  virtual ~Clock() = default;
  virtual TimePoint now() const = 0;
};

}  // namespace colag::hal
