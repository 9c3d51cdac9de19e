#include "colag/ugv/support_protocol.hpp"

#include <cmath>

namespace colag::ugv {

void SupportProtocol::fill(TimePoint now, RobotId ugv_id, const SupportNeed& need, bool cancel,
                           msg::CollisionInfo& out) {
  out = {};
  out.stamp = now;
  out.ugv_id = ugv_id;
  out.seq = ++seq_;
  out.cancel = cancel;
  if (!cancel) {
    out.collision_point_m[0] = need.collision_point.x();
    out.collision_point_m[1] = need.collision_point.y();
    out.support_point_m[0] = need.support_point.x();
    out.support_point_m[1] = need.support_point.y();
    out.time_to_collision_s = need.time_to_collision_s;
    sent_point_ = need.collision_point;
    sent_collision_at_ = now + seconds(need.time_to_collision_s);
  }
  last_sent_ = now;
}

bool SupportProtocol::update(TimePoint now, RobotId ugv_id, const SupportNeed& need,
                             msg::CollisionInfo& out) {
  const bool heartbeat_due = now - last_sent_ >= config_.heartbeat;
  if (need.needed) {
    bool send = !active_ || heartbeat_due;
    if (active_ && !send) {
      const double moved = (need.collision_point - sent_point_).norm();
      const double dt =
          std::abs(to_seconds(now + seconds(need.time_to_collision_s) - sent_collision_at_));
      send = (moved > config_.resend_moved_m && dt > config_.resend_time_change_s) ||
             dt > config_.resend_time_jump_s;
    }
    active_ = true;
    cancels_left_ = 0;
    if (send) fill(now, ugv_id, need, false, out);
    return send;
  }
  if (active_) {
    active_ = false;
    cancels_left_ = config_.cancel_repeats - 1;
    fill(now, ugv_id, need, true, out);
    return true;
  }
  if (cancels_left_ > 0 && heartbeat_due) {
    --cancels_left_;
    fill(now, ugv_id, need, true, out);
    return true;
  }
  return false;
}

}  // namespace colag::ugv
