#include "colag/uav/clock_server.hpp"

namespace colag::uav {

Status ClockServer::attach(platform::Transport& transport, RobotId uav_id) {
  transport_ = &transport;
  uav_id_ = uav_id;
  return requests_.attach(transport);
}

void ClockServer::step(TimePoint now) {
  if (transport_ == nullptr) return;
  msg::ClockRequest q;
  while (requests_.pop(q)) {
    msg::ClockReply r;
    r.received = now;
    r.uav_id = uav_id_;
    r.ugv_id = q.ugv_id;
    r.seq = q.seq;
    r.request_stamp = q.stamp;
    r.stamp = now;
    if (transport_->publish(r)) ++answered_;
  }
}

}  // namespace colag::uav
