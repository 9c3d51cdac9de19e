#pragma once
// The stamp checks every input stream gets, one gate per stream (per sender, where samples are
// kept per robot). A stamp later than now + max_future_skew, or older than now - max_age, is
// refused. With `increasing`, so is a stamp at or before the last one accepted (a duplicate, or
// one overtaken on the network) — unless the sender's clock has evidently gone back (a restart,
// a clock step): kRestartAfter consecutive stamps, each later than the one before and all more
// than max_reorder behind the last one accepted, and the gate follows the new timeline (counted
// as a restart; the caller drops what it kept of the old one). A stamp from the future is never
// accepted, so one bad sample cannot lock a stream out. Pure, allocation-free.
#include <cstdint>

#include "colag/common/time.hpp"

namespace colag {

struct StampLimits {
  Duration max_future_skew = std::chrono::milliseconds(200);
  Duration max_age = std::chrono::seconds(2);
  bool increasing = false;
  Duration max_reorder = std::chrono::milliseconds(500);  // later than this behind: a restart?
};

struct StampCounters {
  std::uint64_t accepted = 0;
  std::uint64_t from_future = 0;
  std::uint64_t too_old = 0;
  std::uint64_t not_increasing = 0;  // duplicates and overtaken samples, dropped
  std::uint64_t restarts = 0;        // the stream's clock went back, and the gate followed
  StampCounters& operator+=(const StampCounters& o) {
    accepted += o.accepted;
    from_future += o.from_future;
    too_old += o.too_old;
    not_increasing += o.not_increasing;
    restarts += o.restarts;
    return *this;
  }
};

class StampGate {
 public:
  enum class Verdict : std::uint8_t {
    kAccepted,
    kRestarted,
    kFromTheFuture,
    kTooOld,
    kNotIncreasing
  };
  static constexpr int kRestartAfter = 3;

  StampGate() = default;
  explicit StampGate(const StampLimits& limits) : limits_(limits) {}
  Verdict check(TimePoint stamp, TimePoint now);
  static bool passed(Verdict v) { return v == Verdict::kAccepted || v == Verdict::kRestarted; }

  const StampCounters& counters() const { return counters_; }
  TimePoint last() const { return last_; }

 private:
  StampLimits limits_;
  StampCounters counters_;
  TimePoint last_ = kNever;    // last accepted stamp
  TimePoint behind_ = kNever;  // the last of the current run of stamps far behind last_
  int behind_run_ = 0;
};

}  // namespace colag
