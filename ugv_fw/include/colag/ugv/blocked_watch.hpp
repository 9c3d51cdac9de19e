#pragma once
// When a UGV gives up asking for now. A robot that has stood still for `after` without a break
// (not localised, no path, the UAV's support did not clear the way, another UGV in the way) is
// blocked: it says so in its status with the reason, withdraws its support request so that the
// UAV serves the others, and after `retry` tries again (a fresh `after` of effort). Moving
// clears it at once: whatever held it has gone.
#include <cstdint>

#include "colag/common/time.hpp"
#include "colag/msg/ugv_status.hpp"

namespace colag::ugv {

struct BlockedConfig {
  Duration after = std::chrono::seconds(60);  // longer than any wait the UAV's queue causes
  Duration retry = std::chrono::seconds(30);
};

class BlockedWatch {
 public:
  explicit BlockedWatch(const BlockedConfig& config = {}) : config_(config) {}

  // Once per planning step: kNone when the robot is moving (or done), else why it stands.
  void update(TimePoint now, msg::BlockedReason standing);

  bool blocked() const { return reason_ != msg::BlockedReason::kNone; }
  msg::BlockedReason reason() const { return reason_; }
  std::uint64_t times_blocked() const { return times_blocked_; }

 private:
  BlockedConfig config_;
  TimePoint still_since_ = kNever;
  TimePoint retry_at_ = kNever;
  msg::BlockedReason reason_ = msg::BlockedReason::kNone;
  std::uint64_t times_blocked_ = 0;
};

}  // namespace colag::ugv
