#pragma once
// A peer's clock as seen from this robot, estimated from NTP-style exchanges: we send at t1 (our
// clock), the peer receives at t2 and answers at t3 (its clock), we receive at t4 (ours). Each
// exchange gives an offset theta = ((t2 - t1) + (t3 - t4)) / 2 (peer minus ours) that is off by
// at most half the round trip delta = (t4 - t1) - (t3 - t2), whatever the network's asymmetry.
//
// The filter keeps, for each `bin` of time, the exchange with the shortest round trip (a delayed
// exchange says little), the last kWindow bins (~4 min at the defaults), uses only those whose
// round trip is close to the window's smallest, and fits offset = a + b * t through them: b is
// the peers' relative drift (crystals differ by tens of ppm), clamped to max_drift_ppm. The
// long window is what makes b good to a few ppm. The error bound it reports is half the best
// round trip, plus the fit's spread, plus what the drift's uncertainty (3 sigma of the fit, at
// least drift_margin_ppm) adds since the best exchange.
//
// A peer whose clock steps (a reboot, an operator setting the time) gives exchanges the fit
// cannot explain: each is dropped, and step_after consecutive ones in agreement with each other
// restart the filter from them. Pure, allocation-free; the caller does the messaging.
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/common/time.hpp"

namespace colag {

struct ClockExchange {
  TimePoint t1;  // request sent (our clock)
  TimePoint t2;  // request received (peer's clock)
  TimePoint t3;  // reply sent (peer's clock)
  TimePoint t4;  // reply received (our clock)
};

struct ClockFilterConfig {
  double max_drift_ppm = 500.0;       // a drift fitted beyond this is clamped (crystals: < 100 ppm)
  double drift_margin_ppm = 20.0;     // what a fitted drift may still be off by, for the bound
  double unfitted_drift_ppm = 100.0;  // the same before a drift could be fitted (a crystal's)
  Duration delay_margin = std::chrono::milliseconds(2);  // "close to the smallest round trip"
  Duration bin = std::chrono::seconds(8);                // one exchange kept per bin
  Duration min_fit_span = std::chrono::seconds(30);      // drift is fitted over at least this
  // Synchronised: the bound below this. Beyond it a stamp is too uncertain to match a relative
  // pose to the odometry at all; below it the UGV widens the measurement by what it drives in
  // that time (a slow network gives a wide bound even when its delays are symmetric).
  Duration max_error = std::chrono::seconds(1);
  int min_exchanges = 3;  // exchanges before the offset is trusted
  int step_after = 3;     // consecutive unexplained exchanges that mean the peer's clock stepped
};

struct ClockFilterCounters {
  std::uint64_t exchanges = 0;
  std::uint64_t invalid = 0;      // t4 before t1, t3 before t2, a round trip beyond 10 s
  std::uint64_t unexplained = 0;  // did not fit the estimate (dropped)
  std::uint64_t steps = 0;        // the peer's clock stepped: the filter restarted
};

class ClockOffsetFilter {
 public:
  static constexpr std::size_t kWindow = limits::kClockFilterBins;
  enum class Verdict : std::uint8_t { kAccepted, kUnexplained, kStepped, kInvalid };

  explicit ClockOffsetFilter(const ClockFilterConfig& config = {}) : config_(config) {}

  Verdict add(const ClockExchange& x);

  // Enough exchanges, and the error bound at `now` (ours) below max_error.
  bool synchronised(TimePoint now) const;
  // The peer's clock minus ours, at our time `t` (zero before the first exchange).
  Duration offset_at(TimePoint t) const;
  TimePoint to_peer(TimePoint ours) const { return ours + offset_at(ours); }
  TimePoint to_ours(TimePoint peer) const;
  // How far offset_at(now) may be from the truth (Duration::max() before the first exchange).
  Duration error_bound(TimePoint now) const;
  double drift_ppm() const { return drift_ * 1e6; }
  // Exchanges accepted since the filter (re)started.
  int exchanges_in_window() const { return accepted_; }
  const ClockFilterCounters& counters() const { return counters_; }

 private:
  struct Sample {
    TimePoint at;    // our time, middle of the exchange
    Duration theta;  // measured offset
    Duration delta;  // round trip
  };
  static Sample sample_of(const ClockExchange& x);
  bool explained(const Sample& s) const;
  void refit();

  ClockFilterConfig config_;
  RingBuffer<Sample, kWindow> window_;
  void keep(const Sample& s);
  RingBuffer<Sample, limits::kClockStepRun>
      unexplained_;  // the current run of exchanges the fit does not explain
  // The fit: offset(t) = base_ + fitted_ + drift_ * (t - t0_) (base_ keeps the doubles small).
  TimePoint t0_{};
  Duration base_{};
  double fitted_ = 0.0;  // ns
  double drift_ = 0.0;   // dimensionless (ns per ns)
  bool drift_fitted_ = false;
  double drift_sigma_ = 0.0;
  TimePoint bin_start_{};
  int accepted_ = 0;
  Duration best_delta_ = Duration::max();
  TimePoint best_at_{};
  double spread_ = 0.0;  // ns: the largest residual among the exchanges used
  ClockFilterCounters counters_;
};

}  // namespace colag
