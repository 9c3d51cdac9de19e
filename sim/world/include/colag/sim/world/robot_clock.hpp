#pragma once
// Each simulated robot's own clock: the world's time, offset, running fast or slow by a few ppm
// (a crystal), and optionally stepped once (a clock set by hand, a time service correcting it).
// A robot's devices stamp with it and its tasks run on it, as on a board; the world and the
// executor keep one true time. Host-side only.
#include "colag/hal/clock.hpp"

namespace colag::sim {

struct ClockModel {
  double offset_s = 0.0;    // its reading when the world's time is 0
  double drift_ppm = 0.0;   // > 0: runs fast
  double step_at_s = -1.0;  // world time of the step; < 0: none
  double step_s = 0.0;

  TimePoint local(TimePoint world) const {
    const double w = to_seconds(world);
    double s = offset_s + drift_ppm * 1e-6 * w;
    if (step_at_s >= 0.0 && w >= step_at_s) s += step_s;
    return world + seconds(s);
  }
  bool identity() const { return offset_s == 0.0 && drift_ppm == 0.0 && step_s == 0.0; }
};

class RobotClock final : public hal::Clock {
 public:
  RobotClock(const hal::Clock& world, const ClockModel& model) : world_(world), model_(model) {}
  TimePoint now() const override { return model_.local(world_.now()); }
  const ClockModel& model() const { return model_; }

 private:
  const hal::Clock& world_;
  ClockModel model_;
};

}  // namespace colag::sim
