#pragma once
#include "colag/common/status.hpp"
#include "colag/common/time.hpp"

namespace colag::platform {

// A unit of periodic work. step() must not block, own threads, throw, or allocate; it gets the
// scheduled release time of this activation (exact multiples of its period from the start),
// which is also what the robot's Clock says to within the executor's release delay.
class Task {
 public:
  virtual ~Task() = default;
  virtual const char* name() const = 0;
  // Called once, in table order, before the first step; may allocate.
  virtual Status init(TimePoint /*now*/) { return Status::ok(); }
  virtual void step(TimePoint now) = 0;
};

// One row of an executor's schedule table.
struct TaskEntry {
  Task* task = nullptr;
  Duration period{};
  Duration budget{};  // a step longer than this is an overrun
  Duration offset{};  // first release at start + offset
};

}  // namespace colag::platform
