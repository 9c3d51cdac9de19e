#include "colag/common/clock_offset_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colag {

namespace {

constexpr Duration kMaxRoundTrip = std::chrono::seconds(10);

// a - b in nanoseconds, saturated (a peer's stamp may be anything).
std::int64_t difference_ns(TimePoint a, TimePoint b) {
  std::int64_t out = 0;
  if (__builtin_sub_overflow(to_nanoseconds(a), to_nanoseconds(b), &out)) {
    return to_nanoseconds(a) < to_nanoseconds(b) ? std::numeric_limits<std::int64_t>::min()
                                                 : std::numeric_limits<std::int64_t>::max();
  }
  return out;
}

TimePoint plus_ns(TimePoint t, double ns) {
  const double limit = 9.0e18;
  const double clamped = std::clamp(std::round(ns), -limit, limit);
  std::int64_t out = 0;
  if (__builtin_add_overflow(to_nanoseconds(t), static_cast<std::int64_t>(clamped), &out)) {
    return clamped < 0 ? TimePoint::min() : TimePoint::max();
  }
  return time_at_nanoseconds(out);
}

}  // namespace

ClockOffsetFilter::Sample ClockOffsetFilter::sample_of(const ClockExchange& x) {
  const Duration out = x.t2 - x.t1;   // forward delay + offset
  const Duration back = x.t3 - x.t4;  // offset - backward delay
  return {x.t1 + (x.t4 - x.t1) / 2, (out + back) / 2, (x.t4 - x.t1) - (x.t3 - x.t2)};
}

ClockOffsetFilter::Verdict ClockOffsetFilter::add(const ClockExchange& x) {
  // Our two stamps come from our clock (trusted); the peer's may be anything: check before any
  // arithmetic that could overflow.
  const std::int64_t ours = difference_ns(x.t4, x.t1);
  const std::int64_t peers = difference_ns(x.t3, x.t2);
  const std::int64_t out = difference_ns(x.t2, x.t1);
  const std::int64_t back = difference_ns(x.t3, x.t4);
  constexpr std::int64_t kLimit = std::int64_t{1} << 61;
  if (ours < 0 || ours > kMaxRoundTrip.count() || peers < 0 || peers > ours || out < -kLimit ||
      out > kLimit || back < -kLimit || back > kLimit) {
    ++counters_.invalid;
    return Verdict::kInvalid;
  }
  ++counters_.exchanges;
  const Sample s = sample_of(x);
  if (window_.empty() || explained(s)) {
    unexplained_.clear();
    keep(s);
    refit();
    return Verdict::kAccepted;
  }
  ++counters_.unexplained;
  // A run of unexplained exchanges means a step only when they agree with each other.
  if (!unexplained_.empty()) {
    const Sample& prev = unexplained_.back();
    const double moved = static_cast<double>((s.theta - prev.theta).count()) -
                         drift_ * static_cast<double>((s.at - prev.at).count());
    const double allowed = static_cast<double>((s.delta / 2 + prev.delta / 2).count()) +
                           static_cast<double>(config_.delay_margin.count());
    if (std::abs(moved) > allowed) unexplained_.clear();
  }
  unexplained_.push_overwrite(s);
  if (static_cast<int>(unexplained_.size()) < config_.step_after) return Verdict::kUnexplained;
  window_.clear();
  accepted_ = 0;
  for (std::size_t i = 0; i < unexplained_.size(); ++i)
    keep(unexplained_[i]);
  unexplained_.clear();
  ++counters_.steps;
  refit();
  return Verdict::kStepped;
}

void ClockOffsetFilter::keep(const Sample& s) {
  ++accepted_;
  if (!window_.empty() && s.at - bin_start_ < config_.bin) {
    if (s.delta < window_.back().delta) window_.back() = s;  // the bin's best so far
    return;
  }
  window_.push_overwrite(s);
  bin_start_ = s.at;
}

bool ClockOffsetFilter::explained(const Sample& s) const {
  const double predicted = static_cast<double>((offset_at(s.at)).count());
  const double allowed = static_cast<double>((s.delta / 2).count()) +
                         static_cast<double>(error_bound(s.at).count()) +
                         static_cast<double>(config_.delay_margin.count());
  return std::abs(static_cast<double>(s.theta.count()) - predicted) <= allowed;
}

void ClockOffsetFilter::refit() {
  Duration least = Duration::max();
  for (std::size_t i = 0; i < window_.size(); ++i)
    least = std::min(least, window_[i].delta);
  const Duration keep = least + std::max(config_.delay_margin, least / 2);
  // The newest good exchange is the origin of the fit.
  std::size_t newest = 0;
  for (std::size_t i = 0; i < window_.size(); ++i)
    if (window_[i].delta <= keep) newest = i;
  t0_ = window_[newest].at;
  base_ = window_[newest].theta;
  double n = 0.0, sx = 0.0, sy = 0.0;
  TimePoint first = t0_;
  best_delta_ = Duration::max();
  for (std::size_t i = 0; i < window_.size(); ++i) {
    const Sample& s = window_[i];
    if (s.delta > keep) continue;
    n += 1.0;
    sx += static_cast<double>((s.at - t0_).count());
    sy += static_cast<double>((s.theta - base_).count());
    first = std::min(first, s.at);
    if (s.delta < best_delta_) {
      best_delta_ = s.delta;
      best_at_ = s.at;
    }
  }
  const double mx = sx / n, my = sy / n;
  double fit_sxx = -1.0;  // >= 0 when this refit fitted the drift
  if (n >= 3.0 && t0_ - first >= config_.min_fit_span) {
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t i = 0; i < window_.size(); ++i) {
      const Sample& s = window_[i];
      if (s.delta > keep) continue;
      const double dx = static_cast<double>((s.at - t0_).count()) - mx;
      sxy += dx * (static_cast<double>((s.theta - base_).count()) - my);
      sxx += dx * dx;
    }
    const double limit = config_.max_drift_ppm * 1e-6;
    drift_ = std::clamp(sxx > 0.0 ? sxy / sxx : 0.0, -limit, limit);
    drift_fitted_ = sxx > 0.0;
    fit_sxx = sxx;
  }
  fitted_ = my - drift_ * mx;
  // The residuals: their largest is the spread; with a fitted drift, they give its standard error.
  double rss = 0.0;
  spread_ = 0.0;
  for (std::size_t i = 0; i < window_.size(); ++i) {
    const Sample& s = window_[i];
    if (s.delta > keep) continue;
    const double r = static_cast<double>((s.theta - base_).count()) -
                     (fitted_ + drift_ * static_cast<double>((s.at - t0_).count()));
    rss += r * r;
    spread_ = std::max(spread_, std::abs(r));
  }
  if (fit_sxx >= 0.0) {
    drift_sigma_ = n > 2.0 && fit_sxx > 0.0 ? std::sqrt(rss / (n - 2.0) / fit_sxx)
                                            : config_.max_drift_ppm * 1e-6;
  }
}

Duration ClockOffsetFilter::offset_at(TimePoint t) const {
  if (window_.empty()) return Duration::zero();
  const double ns = fitted_ + drift_ * static_cast<double>(difference_ns(t, t0_));
  return base_ + Duration{static_cast<std::int64_t>(std::round(ns))};
}

TimePoint ClockOffsetFilter::to_ours(TimePoint peer) const {
  if (window_.empty()) return peer;
  // peer = t + base + fitted + drift * (t - t0)  =>  t - t0 = (peer - t0 - base - fitted) / (1 +
  // drift)
  const double rel = static_cast<double>(difference_ns(peer, t0_ + base_)) - fitted_;
  return plus_ns(t0_, rel / (1.0 + drift_));
}

Duration ClockOffsetFilter::error_bound(TimePoint now) const {
  if (window_.empty()) return Duration::max();
  const double rate = drift_fitted_ ? std::max(config_.drift_margin_ppm * 1e-6, 3.0 * drift_sigma_)
                                    : config_.unfitted_drift_ppm * 1e-6;
  const double age = std::abs(static_cast<double>(difference_ns(now, best_at_)));
  const double ns = static_cast<double>(best_delta_.count()) / 2.0 + spread_ + rate * age;
  return Duration{static_cast<std::int64_t>(std::min(ns, 9.0e18))};
}

bool ClockOffsetFilter::synchronised(TimePoint now) const {
  return accepted_ >= config_.min_exchanges && error_bound(now) <= config_.max_error;
}

}  // namespace colag
