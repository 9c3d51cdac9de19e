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
  // The real-time executor reports a step that took longer than its budget (or activations it
  // had to skip), so that the task can shed work. Simulation does not report: a seeded run must
  // not depend on the speed of the host.
  virtual void on_overrun(Duration /*step_time*/) {}
};

// A Task that runs one member function of an owner object, so that one robot task can offer
// several loops at different rates to the same executor table (e.g. a 50 Hz control loop and a
// 10 Hz planning loop). init() is forwarded to the owner's init, which must tolerate being
// called once per loop.
template <class Owner>
class MemberLoop final : public Task {
 public:
  using Step = void (Owner::*)(TimePoint);
  using Init = Status (Owner::*)(TimePoint);
  using Overrun = void (Owner::*)(Duration);
  MemberLoop(Owner& owner, const char* name, Init init_fn, Step step_fn,
             Overrun overrun_fn = nullptr)
      : owner_(owner), name_(name), init_(init_fn), step_(step_fn), overrun_(overrun_fn) {}
  const char* name() const override { return name_; }
  Status init(TimePoint now) override { return (owner_.*init_)(now); }
  void step(TimePoint now) override { (owner_.*step_)(now); }
  void on_overrun(Duration step_time) override {
    if (overrun_ != nullptr) (owner_.*overrun_)(step_time);
  }

 private:
  Owner& owner_;
  const char* name_;
  Init init_;
  Step step_;
  Overrun overrun_;
};

// When a loop runs: a row of a robot's schedule table before it is bound to a task (each robot
// declares its loops' timings once, e.g. ugv::UgvSchedule, and every program that runs the robot
// builds its executor table from them).
struct LoopTiming {
  Duration period{};
  Duration budget{};  // a step longer than this is an overrun
  Duration offset{};  // first release at start + offset
  // The same loop at another rate: the budget keeps its share of the period.
  LoopTiming at_period(Duration p) const {
    if (period.count() <= 0) return {p, budget, offset};
    const double share = static_cast<double>(p.count()) / static_cast<double>(period.count());
    return {p, Duration(static_cast<Duration::rep>(static_cast<double>(budget.count()) * share)),
            offset};
  }
};

// One row of an executor's schedule table.
struct TaskEntry {
  Task* task = nullptr;
  Duration period{};
  Duration budget{};  // a step longer than this is an overrun
  Duration offset{};  // first release at start + offset
  // Simulation only: a robot simulated beside others runs in its own lane (see
  // LockstepExecutor). 0, the default, is the lane of everything else. The real-time executor
  // runs one robot and ignores lanes.
  int lane = 0;
};

// The row that runs `task` with `timing`, in `lane`.
inline TaskEntry row(Task& task, const LoopTiming& timing, int lane = 0) {
  return {&task, timing.period, timing.budget, timing.offset, lane};
}

}  // namespace colag::platform
