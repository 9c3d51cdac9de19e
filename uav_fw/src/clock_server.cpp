#include "colag/uav/clock_server.hpp"

namespace colag::uav {

Status ClockServer::attach(platform::Transport& transport, RobotId uav_id) {
  transport_ = &transport;
  uav_id_ = uav_id;
  if (Status s = requests_.attach(transport); !s) return s;
  return uav_requests_.attach(transport);
}

namespace {

// The exchange's stamps (fleet time: `now` is when the request was read and the answer sent)
// and sequence number, for either kind of asker.
template <class Reply, class Request>
Reply answer(const Request& q, TimePoint now) {
  Reply r;
  r.received = now;
  r.seq = q.seq;
  r.request_stamp = q.stamp;
  r.stamp = now;
  return r;
}

}  // namespace

void ClockServer::step(TimePoint now, std::optional<Duration> fleet_minus_local) {
  if (transport_ == nullptr) return;
  const bool serving = fleet_minus_local.has_value();
  const TimePoint fleet = now + fleet_minus_local.value_or(Duration::zero());
  msg::ClockRequest q;
  while (requests_.pop(q)) {
    if (!serving) continue;
    auto r = answer<msg::ClockReply>(q, fleet);
    r.uav_id = uav_id_;
    r.ugv_id = q.ugv_id;
    if (transport_->publish(r)) ++answered_;
  }
  msg::UavClockRequest uq;
  while (uav_requests_.pop(uq)) {
    if (!serving || uq.uav_id == uav_id_) continue;  // our own
    auto r = answer<msg::UavClockReply>(uq, fleet);
    r.server_id = uav_id_;
    r.uav_id = uq.uav_id;
    if (transport_->publish(r)) ++answered_;
  }
}

}  // namespace colag::uav
