#include "colag/ugv/fleet_clock.hpp"

namespace colag::ugv {

Status FleetClock::attach(platform::Transport& transport, RobotId id) {
  transport_ = &transport;
  id_ = id;
  return replies_.attach(transport, id);
}

void FleetClock::step(TimePoint now) {
  if (transport_ == nullptr) return;
  msg::ClockReply r;
  while (replies_.pop(r)) {
    // Ours, answering a request of this process (not a replay, not a predecessor's).
    if (r.ugv_id != id_ || r.uav_id != config_.time_server || r.request_stamp > now ||
        now - r.request_stamp > config_.max_reply_age) {
      ++replies_rejected_;
      continue;
    }
    const auto verdict = filter_.add({r.request_stamp, r.received, r.stamp, now});
    if (verdict == ClockOffsetFilter::Verdict::kInvalid) ++replies_rejected_;
    hurry_ = verdict != ClockOffsetFilter::Verdict::kAccepted || !filter_.synchronised(now);
  }
  if (!synchronised(now)) hurry_ = true;
  if (!elapsed(now, last_request_, hurry_ ? config_.fast_period : config_.period)) return;
  last_request_ = now;
  msg::ClockRequest q;
  q.stamp = now;
  q.ugv_id = id_;
  q.seq = ++seq_;
  (void)transport_->publish(q);
}

}  // namespace colag::ugv
