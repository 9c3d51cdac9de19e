#include "colag/platform/schedule.hpp"

#include <algorithm>

namespace colag::platform {

Status Schedule::add(const TaskEntry& entry) {
  if (entry.task == nullptr) return {Errc::kInvalidArgument, "task entry without a task"};
  if (entry.period <= Duration::zero()) return {Errc::kInvalidArgument, "task period must be > 0"};
  if (entry.budget <= Duration::zero()) return {Errc::kInvalidArgument, "task budget must be > 0"};
  if (entry.offset < Duration::zero()) return {Errc::kInvalidArgument, "task offset must be >= 0"};
  if (entry.lane < 0) return {Errc::kInvalidArgument, "task lane must be >= 0"};
  if (!rows_.empty() && entry.lane < rows_.back().entry.lane)
    return {Errc::kInvalidArgument, "task lanes must not decrease along the table"};
  Row row;
  row.entry = entry;
  row.stats.name = entry.task->name();
  if (!rows_.push_back(row)) return {Errc::kCapacityExceeded, "too many tasks for one executor"};
  return Status::ok();
}

Status Schedule::add(std::span<const TaskEntry> entries) {
  for (const TaskEntry& e : entries) {
    if (Status s = add(e); !s) return s;
  }
  return Status::ok();
}

Status Schedule::init(TimePoint start) {
  for (auto& row : rows_) {
    row.next_release = start + row.entry.offset;
    row.stats = TaskStats{row.entry.task->name()};
    if (Status s = row.entry.task->init(start); !s) return s;
  }
  return Status::ok();
}

TimePoint Schedule::next_release() const {
  TimePoint t = TimePoint::max();
  for (const auto& row : rows_)
    t = std::min(t, row.next_release);
  return t;
}

bool Schedule::complete(std::size_t i, TimePoint started, Duration step_time, TimePoint after) {
  Row& row = rows_[i];
  TaskStats& st = row.stats;
  ++st.steps;
  st.total_step += step_time;
  st.longest_step = std::max(st.longest_step, step_time);
  st.max_release_delay = std::max(st.max_release_delay, started - row.next_release);
  const bool overran = step_time > row.entry.budget;
  if (overran) ++st.overruns;

  row.next_release += row.entry.period;
  // Fell behind by whole periods: drop those activations instead of running them in a burst.
  if (after >= row.next_release + row.entry.period) {
    const auto missed = (after - row.next_release) / row.entry.period;
    row.next_release += missed * row.entry.period;
    st.skipped += static_cast<std::uint64_t>(missed);
    return true;
  }
  return overran;
}

}  // namespace colag::platform
