#pragma once
// Time in ColAG-fw: signed 64-bit nanoseconds everywhere (~292 years of range).
// Durations and time points are std::chrono types, so units are checked by the compiler;
// the epoch of a TimePoint is whatever the robot's Clock HAL says (monotonic on a board,
// zero at the start of a simulated run).
#include <chrono>
#include <cstdint>

namespace colag {

using Duration = std::chrono::duration<std::int64_t, std::nano>;

// Tag type standing in for "the robot's clock"; only the HAL Clock produces TimePoints.
struct RobotClockTag {
  using duration = Duration;
  using rep = Duration::rep;
  using period = Duration::period;
};
using TimePoint = std::chrono::time_point<RobotClockTag, Duration>;

// "Never happened": the initial value of a last-time-something-happened field. Never subtract
// from it (signed overflow); ask elapsed() instead.
inline constexpr TimePoint kNever = TimePoint::min();

// True when at least `d` has passed since `since`, or `since` is kNever.
constexpr bool elapsed(TimePoint now, TimePoint since, Duration d) {
  return since == kNever || now - since >= d;
}

constexpr double to_seconds(Duration d) {
  return static_cast<double>(d.count()) * 1e-9;
}
constexpr double to_seconds(TimePoint t) {
  return to_seconds(t.time_since_epoch());
}

// Rounds to the nearest nanosecond.
constexpr Duration seconds(double s) {
  const double ns = s * 1e9;
  return Duration{static_cast<std::int64_t>(ns < 0 ? ns - 0.5 : ns + 0.5)};
}
constexpr TimePoint time_at_seconds(double s) {
  return TimePoint{seconds(s)};
}
constexpr Duration period_of_hz(double hz) {
  return seconds(1.0 / hz);
}
// A TimePoint as the int64 nanoseconds that message fields carry, and back (exact).
constexpr std::int64_t to_nanoseconds(TimePoint t) {
  return t.time_since_epoch().count();
}
constexpr TimePoint time_at_nanoseconds(std::int64_t ns) {
  return TimePoint{Duration{ns}};
}

}  // namespace colag
