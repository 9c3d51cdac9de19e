#pragma once
// The schedule table both executors share: the rows {task, period, budget, offset}, each
// row's next release, and its run-time statistics. Which executor drives it decides only how
// time passes (simulated or real).
#include <cstdint>
#include <span>

#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/platform/task.hpp"

namespace colag::platform {

struct TaskStats {
  const char* name = "";
  std::uint64_t steps = 0;
  std::uint64_t overruns = 0;  // steps that took longer than the budget
  std::uint64_t skipped = 0;   // activations dropped because the task fell behind
  Duration longest_step{};
  Duration total_step{};
  Duration max_release_delay{};  // latest start after the scheduled release
};

class Schedule {
 public:
  Status add(const TaskEntry& entry);
  // Adds the rows in order; stops at the first one refused.
  Status add(std::span<const TaskEntry> entries);
  // Sets every row's first release and calls each task's init() in table order.
  Status init(TimePoint start);

  // Earliest pending release over all rows.
  TimePoint next_release() const;
  std::size_t size() const { return rows_.size(); }
  const TaskEntry& entry(std::size_t i) const { return rows_[i].entry; }
  TimePoint release_of(std::size_t i) const { return rows_[i].next_release; }
  const TaskStats& stats(std::size_t i) const { return rows_[i].stats; }

  // Book-keeping after row i ran the activation released at its next_release:
  // `started` is when the step began, `step_time` how long it took, `after` the time now.
  // True when the step overran its budget or activations had to be skipped.
  bool complete(std::size_t i, TimePoint started, Duration step_time, TimePoint after);

 private:
  struct Row {
    TaskEntry entry;
    TimePoint next_release{};
    TaskStats stats;
  };
  StaticVector<Row, limits::kMaxTasksPerExecutor> rows_;
};

}  // namespace colag::platform
