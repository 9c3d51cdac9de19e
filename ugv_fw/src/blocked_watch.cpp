#include "colag/ugv/blocked_watch.hpp"

namespace colag::ugv {

void BlockedWatch::update(TimePoint now, msg::BlockedReason standing) {
  if (standing == msg::BlockedReason::kNone) {
    still_since_ = kNever;
    reason_ = msg::BlockedReason::kNone;
    return;
  }
  if (still_since_ == kNever) still_since_ = now;
  if (blocked()) {
    if (now < retry_at_) return;
    reason_ = msg::BlockedReason::kNone;  // try again, with a fresh allowance
    still_since_ = now;
    return;
  }
  if (now - still_since_ >= config_.after) {
    reason_ = standing;
    retry_at_ = now + config_.retry;
    ++times_blocked_;
  }
}

}  // namespace colag::ugv
