#pragma once
// Degrades a task's workload when its steps persistently overrun their budget, and restores it
// once they have stopped: a task that cannot keep its rate does less (e.g. a shorter collision
// prediction) instead of falling further behind. Level 0 = full work .. kMaxLevel.
#include <algorithm>
#include <cstdint>

namespace colag {

struct OverrunGovernorConfig {
  int window_steps = 10;            // overruns are counted over this many steps (1 s at 10 Hz)
  int overruns_to_degrade = 3;      // this many in one window: one level down
  int clean_steps_to_recover = 50;  // this many steps without one: one level back up
};

class OverrunGovernor {
 public:
  static constexpr int kMaxLevel = 2;

  explicit OverrunGovernor(const OverrunGovernorConfig& config = {}) : config_(config) {}

  // The executor reports a step that exceeded its budget.
  void on_overrun() {
    ++overruns_in_window_;
    ++total_;
    overran_ = true;
  }
  // Once per step, before its work: updates and returns the level.
  int update() {
    if (++steps_in_window_ >= config_.window_steps ||
        overruns_in_window_ >= config_.overruns_to_degrade) {
      if (overruns_in_window_ >= config_.overruns_to_degrade) {
        level_ = std::min(level_ + 1, kMaxLevel);
        clean_steps_ = 0;
      }
      steps_in_window_ = 0;
      overruns_in_window_ = 0;
    }
    clean_steps_ = overran_ ? 0 : clean_steps_ + 1;
    overran_ = false;
    if (level_ > 0 && clean_steps_ >= config_.clean_steps_to_recover) {
      --level_;
      clean_steps_ = 0;
    }
    return level_;
  }
  int level() const { return level_; }
  std::uint64_t total() const { return total_; }

 private:
  OverrunGovernorConfig config_;
  int level_ = 0;
  int steps_in_window_ = 0;
  int overruns_in_window_ = 0;
  int clean_steps_ = 0;
  bool overran_ = false;
  std::uint64_t total_ = 0;
};

}  // namespace colag
