#pragma once
// When a UGV tells the UAV it needs support (CollisionInfo). A request goes out when a
// prediction appears; it is re-sent only when it changes materially (the predicted collision
// moved more than 0.7 m and its time changed more than 0.4 s, or the time changed more than
// 3 s; times compared as absolute instants, so steady driving towards the same point is not a
// change), plus a heartbeat while it lasts. When the prediction clears, a cancel goes out at
// once, never held back by the rate rules, and is repeated a few times at the heartbeat
// period so that a lossy link cannot leave the UAV serving a stale request.
#include <cstdint>

#include "colag/common/geometry.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/collision_info.hpp"

namespace colag::ugv {

struct SupportConfig {
  double resend_moved_m = 0.7;
  double resend_time_change_s = 0.4;
  double resend_time_jump_s = 3.0;
  Duration heartbeat = std::chrono::seconds(1);
  int cancel_repeats = 3;
};

struct SupportNeed {
  bool needed = false;
  Vec2 collision_point = Vec2::Zero();
  Vec2 support_point = Vec2::Zero();
  double time_to_collision_s = 0.0;
};

class SupportProtocol {
 public:
  explicit SupportProtocol(const SupportConfig& config = {}) : config_(config) {}

  // Call on every prediction; returns true when `out` must be published now.
  bool update(TimePoint now, RobotId ugv_id, const SupportNeed& need, msg::CollisionInfo& out);
  bool requesting() const { return active_; }
  std::uint32_t sent() const { return seq_; }

 private:
  void fill(TimePoint now, RobotId ugv_id, const SupportNeed& need, bool cancel,
            msg::CollisionInfo& out);

  SupportConfig config_;
  bool active_ = false;
  int cancels_left_ = 0;
  Vec2 sent_point_ = Vec2::Zero();
  TimePoint sent_collision_at_{};
  TimePoint last_sent_{};
  std::uint32_t seq_ = 0;
};

}  // namespace colag::ugv
