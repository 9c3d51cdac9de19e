#pragma once
#include "colag/hal/clock.hpp"

namespace colag::platform {

// The board's clock: CLOCK_MONOTONIC (never jumps, unaffected by NTP steps).
class MonotonicClock final : public hal::Clock {
 public:
  TimePoint now() const override;
};

}  // namespace colag::platform
