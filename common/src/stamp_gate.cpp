#include "colag/common/stamp_gate.hpp"

namespace colag {

StampGate::Verdict StampGate::check(TimePoint stamp, TimePoint now) {
  if (stamp > now + limits_.max_future_skew) {
    ++counters_.from_future;
    return Verdict::kFromTheFuture;
  }
  if (stamp < now - limits_.max_age) {
    ++counters_.too_old;
    return Verdict::kTooOld;
  }
  if (limits_.increasing && last_ != kNever && stamp <= last_) {
    // Far behind, and later than the previous such stamp: the sender's clock may have gone back.
    if (last_ - stamp > limits_.max_reorder && (behind_run_ == 0 || stamp > behind_)) {
      behind_ = stamp;
      if (++behind_run_ >= kRestartAfter) {
        behind_run_ = 0;
        last_ = stamp;
        ++counters_.restarts;
        ++counters_.accepted;
        return Verdict::kRestarted;
      }
    } else {
      behind_run_ = 0;
    }
    ++counters_.not_increasing;
    return Verdict::kNotIncreasing;
  }
  behind_run_ = 0;
  last_ = stamp;
  ++counters_.accepted;
  return Verdict::kAccepted;
}

}  // namespace colag
