#pragma once
// Fleet time on a robot that is not the time server: the server's clock, learned from clock
// exchanges (msg/clock_sync.hpp, ClockOffsetFilter). Every stamp that crosses between robots is
// fleet time; this is where a robot converts: incoming stamps to its own clock before any check
// or use, outgoing stamps to fleet time. Chrony or PTP on the boards make the offset small and
// the filter's job easy; without them, or when they are wrong, this keeps time-matched fusion
// honest.
//
// Asks 20 times a second until synchronised (and after an exchange that did not fit), then once
// a second. Only the time server's replies count, but for a robot that is not synchronised while
// the time server has been silent for `standby_after` (it started, or restarted, after the server
// was lost): then another UAV's, which answers with the fleet time it learnt while it has it and
// does not hear the server (uav::ClockServer). A synchronised robot keeps its own estimate rather
// than take a stand-in's (no two stand-ins feed each other). Allocation-free; step() runs in the
// control loop, so the reply's receive time is taken within one control period. A UGV asks on
// ClockRequest / ClockReply (UgvFleetClock), another UAV on UavClockRequest / UavClockReply
// (UavFleetClock): the same exchange.
#include <cstdint>

#include "colag/common/clock_offset_filter.hpp"
#include "colag/msg/clock_sync.hpp"
#include "colag/platform/readers.hpp"

namespace colag::platform {

struct FleetClockConfig {
  Duration fast_period = std::chrono::milliseconds(50);
  Duration period = std::chrono::seconds(1);
  Duration max_reply_age = std::chrono::seconds(5);  // an older exchange is not used
  // With several UAVs one clock is fleet time: this UAV's. Another's replies are taken only as a
  // stand-in's (see the top of the file).
  RobotId time_server = 0;
  Duration standby_after = std::chrono::seconds(3);
  ClockFilterConfig filter;
};

// Request: the message asking (its `stamp`, `seq` and the asker's id, `kAsker`); Reply: the
// answer (the same fields, the answering server's id `kServer`, `request_stamp`, `received`).
template <class Request, class Reply, RobotId Request::*kAsker, RobotId Reply::*kAskedBy,
          RobotId Reply::*kServer>
class FleetClock {
 public:
  explicit FleetClock(const FleetClockConfig& config = {})
      : config_(config), filter_(config.filter) {}

  Status attach(Transport& transport, RobotId id) {
    transport_ = &transport;
    id_ = id;
    return replies_.attach(transport, id);
  }
  // Takes the replies, and asks again when due.
  void step(TimePoint now) {
    if (transport_ == nullptr) return;
    Reply r;
    while (replies_.pop(r)) {
      // Ours, answering a request of this process (not a replay, not a predecessor's).
      const bool from_server = r.*kServer == config_.time_server;
      if (r.*kAskedBy != id_ || (!from_server && !takes_standby(now)) || r.request_stamp > now ||
          now - r.request_stamp > config_.max_reply_age) {
        ++replies_rejected_;
        continue;
      }
      if (from_server) {
        last_from_server_ = now;
      } else {
        ++standby_exchanges_;
      }
      const auto verdict = filter_.add({r.request_stamp, r.received, r.stamp, now});
      if (verdict == ClockOffsetFilter::Verdict::kInvalid) ++replies_rejected_;
      hurry_ = verdict != ClockOffsetFilter::Verdict::kAccepted || !filter_.synchronised(now);
    }
    if (!synchronised(now)) hurry_ = true;
    if (!elapsed(now, last_request_, hurry_ ? config_.fast_period : config_.period)) return;
    last_request_ = now;
    Request q;
    q.stamp = now;
    q.*kAsker = id_;
    q.seq = ++seq_;
    (void)transport_->publish(q);
  }

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
  std::uint64_t standby_exchanges() const { return standby_exchanges_; }  // from a stand-in
  // Whether the time server answered within `d` of `now`.
  bool heard_server_within(TimePoint now, Duration d) const {
    return !elapsed(now, last_from_server_, d);
  }

 private:
  bool takes_standby(TimePoint now) const {
    return !synchronised(now) && !heard_server_within(now, config_.standby_after);
  }

  FleetClockConfig config_;
  ClockOffsetFilter filter_;
  Transport* transport_ = nullptr;
  RobotId id_ = 0;
  QueueReader<Reply, 4> replies_;
  std::uint32_t seq_ = 0;
  TimePoint last_request_ = kNever;
  bool hurry_ = true;  // ask at the fast rate
  std::uint64_t replies_rejected_ = 0;
  TimePoint last_from_server_ = kNever;
  std::uint64_t standby_exchanges_ = 0;
};

using UgvFleetClock = FleetClock<msg::ClockRequest, msg::ClockReply, &msg::ClockRequest::ugv_id,
                                 &msg::ClockReply::ugv_id, &msg::ClockReply::uav_id>;
using UavFleetClock =
    FleetClock<msg::UavClockRequest, msg::UavClockReply, &msg::UavClockRequest::uav_id,
               &msg::UavClockReply::uav_id, &msg::UavClockReply::server_id>;

}  // namespace colag::platform
