#include "colag/platform/monotonic_clock.hpp"

#include <ctime>

namespace colag::platform {

TimePoint MonotonicClock::now() const {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  const std::int64_t ns = std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
  if (scale_ == 1.0) return TimePoint{Duration{ns}};
  return TimePoint{Duration{static_cast<std::int64_t>(static_cast<double>(ns) * scale_)}};
}

std::int64_t MonotonicClock::monotonic_ns(TimePoint t) const {
  const std::int64_t ns = to_nanoseconds(t);
  return scale_ == 1.0 ? ns : static_cast<std::int64_t>(static_cast<double>(ns) / scale_);
}

}  // namespace colag::platform
