#include "colag/platform/monotonic_clock.hpp"

#include <ctime>

namespace colag::platform {

TimePoint MonotonicClock::now() const {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return TimePoint{Duration{std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec}};
}

}  // namespace colag::platform
