#pragma once
// Fleet time on a UGV: the UAV's clock, learned from clock exchanges (msg::ClockRequest /
// ClockReply, see ClockOffsetFilter). Every stamp that crosses between robots is fleet time;
// this is where a UGV converts: incoming stamps to its own clock before any check or use,
// outgoing stamps to fleet time. Chrony or PTP on the boards make the offset small and the
// filter's job easy; without them, or when they are wrong, this keeps time-matched fusion honest.
//
// Asks 20 times a second until synchronised (and after an exchange that did not fit), then once
// a second. Allocation-free; step() runs in the control loop, so the reply's receive time is taken
// within one control period.
#include <cstdint>

#include "colag/common/clock_offset_filter.hpp"
#include "colag/msg/clock_sync.hpp"
#include "colag/platform/readers.hpp"

namespace colag::ugv {

struct FleetClockConfig {
  Duration fast_period = std::chrono::milliseconds(50);
  Duration period = std::chrono::seconds(1);
  Duration max_reply_age = std::chrono::seconds(5);  // an older exchange is not used
  // With several UAVs one clock is fleet time: this UAV's. Replies of any other are not used.
  RobotId time_server = 0;
  ClockFilterConfig filter;
};

class FleetClock {
 public:
  explicit FleetClock(const FleetClockConfig& config = {})
      : config_(config), filter_(config.filter) {}

  Status attach(platform::Transport& transport, RobotId id);
  // Takes the replies, and asks again when due.
  void step(TimePoint now);

  bool synchronised(TimePoint now) const { return filter_.synchronised(now); }
  bool has_estimate() const { return filter_.exchanges_in_window() > 0; }
  // Before the first exchange both are the identity (and synchronised() is false).
  TimePoint to_local(TimePoint fleet) const { return filter_.to_ours(fleet); }
  TimePoint to_fleet(TimePoint local) const { return filter_.to_peer(local); }
  // Seconds the conversion may be off by; negative while not synchronised.
  double error_s(TimePoint now) const {
    return synchronised(now) ? to_seconds(filter_.error_bound(now)) : -1.0;
  }
  const ClockOffsetFilter& filter() const { return filter_; }
  std::uint64_t replies_rejected() const { return replies_rejected_; }

 private:
  FleetClockConfig config_;
  ClockOffsetFilter filter_;
  platform::Transport* transport_ = nullptr;
  RobotId id_ = 0;
  platform::QueueReader<msg::ClockReply, 4> replies_;
  std::uint32_t seq_ = 0;
  TimePoint last_request_ = kNever;
  bool hurry_ = true;  // ask at the fast rate
  std::uint64_t replies_rejected_ = 0;
};

}  // namespace colag::ugv
