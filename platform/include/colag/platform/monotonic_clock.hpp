#pragma once
#include "colag/hal/clock.hpp"

namespace colag::platform {

// The board's clock: CLOCK_MONOTONIC (never jumps, unaffected by NTP steps). Software-in-the-
// loop runs may scale it: now = CLOCK_MONOTONIC x scale, which every process on the host computes
// alike, so the world and the robots agree on the time without exchanging it.
class MonotonicClock final : public hal::Clock {
 public:
  explicit MonotonicClock(double scale = 1.0) : scale_(scale) {}
  TimePoint now() const override;
  double scale() const { return scale_; }
  // The CLOCK_MONOTONIC reading at which this clock reads `t`.
  std::int64_t monotonic_ns(TimePoint t) const;

 private:
  double scale_;
};

}  // namespace colag::platform
