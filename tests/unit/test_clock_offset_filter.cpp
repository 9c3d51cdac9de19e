// A peer's clock from NTP-style exchanges: offsets of an hour either way, crystals 50 ppm apart,
// asymmetric and jittery delays, a peer whose clock steps, and exchanges that are nonsense.
#include <gtest/gtest.h>

#include <cmath>

#include "colag/common/clock_offset_filter.hpp"
#include "colag/common/random.hpp"

using namespace colag;
using namespace std::chrono_literals;
using V = ClockOffsetFilter::Verdict;

namespace {

// Our clock is true time; the peer's reads offset + (1 + drift) * t, plus `step` after step_at.
struct Peer {
  double offset_s = 0.0;
  double drift_ppm = 0.0;
  double step_at_s = 1e18;
  double step_s = 0.0;
  TimePoint at(double t) const {
    double s = t + offset_s + drift_ppm * 1e-6 * t;
    if (t >= step_at_s) s += step_s;
    return time_at_seconds(s);
  }
  Duration true_offset(double t) const { return at(t) - time_at_seconds(t); }
};

// One exchange sent at our time t: forward and backward delays drawn independently (1-40 ms, a
// few much longer), the peer answering within 0-20 ms.
ClockExchange exchange(const Peer& peer, double t, Rng& rng) {
  const auto delay = [&] {
    return rng.bernoulli(0.1) ? rng.uniform(0.1, 0.5) : rng.uniform(0.001, 0.04);
  };
  const double d1 = delay(), hold = rng.uniform(0.0, 0.02), d2 = delay();
  return {time_at_seconds(t), peer.at(t + d1), peer.at(t + d1 + hold),
          time_at_seconds(t + d1 + hold + d2)};
}

double error_s(const ClockOffsetFilter& f, const Peer& peer, double t) {
  return std::abs(to_seconds(f.offset_at(time_at_seconds(t)) - peer.true_offset(t)));
}

}  // namespace

TEST(ClockOffsetFilter, LearnsAnHourEitherWayAndFiftyPpmWithinMilliseconds) {
  for (const Peer peer : {Peer{3600.0, 50.0}, Peer{-3600.0, -50.0}, Peer{0.25, 0.0}}) {
    ClockOffsetFilter f;
    Rng rng(7);
    EXPECT_FALSE(f.synchronised(time_at_seconds(0.0)));
    double worst = 0.0, worst_late = 0.0, sum_late = 0.0;
    int out_of_bound = 0;
    for (int k = 0; k < 900; ++k) {  // 15 minutes at one exchange a second
      const double t = 100.0 + k;
      EXPECT_NE(f.add(exchange(peer, t, rng)), V::kInvalid);
      const double now = t + 0.5;
      if (k < 2) continue;
      ASSERT_TRUE(f.synchronised(time_at_seconds(now))) << k;
      const double e = error_s(f, peer, now);
      worst = std::max(worst, e);
      if (k > 60) {
        worst_late = std::max(worst_late, e);
        sum_late += e;
      }
      if (e > to_seconds(f.error_bound(time_at_seconds(now)))) ++out_of_bound;
      // The conversions are each other's inverse.
      const TimePoint ours = time_at_seconds(now);
      EXPECT_LE(std::abs(to_seconds(f.to_ours(f.to_peer(ours)) - ours)), 1e-6);
    }
    EXPECT_LT(worst, 0.025) << "offset " << peer.offset_s;  // the first exchanges: a few ms
    // Delays of 1-40 ms each way, drawn independently: each exchange alone can be off by 20 ms.
    EXPECT_LT(worst_late, 0.015) << "offset " << peer.offset_s;
    EXPECT_LT(sum_late / (900 - 61), 0.004) << "offset " << peer.offset_s;
    EXPECT_EQ(out_of_bound, 0) << "the reported bound must hold";
    EXPECT_NEAR(f.drift_ppm(), peer.drift_ppm, 10.0);
  }
}

TEST(ClockOffsetFilter, FollowsAPeerWhoseClockStepsAndIgnoresASingleBadReply) {
  Peer peer{1800.0, 30.0, 300.0, -7.5};
  ClockOffsetFilter f;
  Rng rng(3);
  int stepped = 0;
  for (int k = 0; k < 600; ++k) {
    const double t = k;
    ClockExchange x = exchange(peer, t, rng);
    if (k == 150) x.t2 = x.t3 = x.t3 + 2s;  // one reply with a wrong clock: not a step
    const V v = f.add(x);
    if (k == 150) {
      EXPECT_EQ(v, V::kUnexplained);
    }
    if (v == V::kStepped) {
      ++stepped;
      EXPECT_GE(t, 300.0);
      EXPECT_LE(t, 300.0 + ClockFilterConfig{}.step_after);  // within step_after exchanges
    }
    if (k > 3 && (t < 299.0 || t > 306.0)) {
      EXPECT_LT(error_s(f, peer, t + 0.5), 0.03) << "t " << t;
    }
  }
  EXPECT_EQ(stepped, 1);
  EXPECT_EQ(f.counters().steps, 1u);
}

TEST(ClockOffsetFilter, RefusesNonsenseWithoutOverflowing) {
  ClockOffsetFilter f;
  const TimePoint t = time_at_seconds(10.0);
  EXPECT_EQ(f.add({t, t, t, t - 1ms}), V::kInvalid);          // received before sent
  EXPECT_EQ(f.add({t, t + 5ms, t, t + 10ms}), V::kInvalid);   // replied before received
  EXPECT_EQ(f.add({t, t, t + 20ms, t + 10ms}), V::kInvalid);  // held longer than the trip
  EXPECT_EQ(f.add({t, TimePoint::min(), TimePoint::min(), t + 1ms}), V::kInvalid);
  EXPECT_EQ(f.add({t, TimePoint::max(), TimePoint::max(), t + 1ms}), V::kInvalid);
  EXPECT_EQ(f.add({t, t, t, t + 11s}), V::kInvalid);  // a round trip of 11 s says nothing
  EXPECT_EQ(f.counters().invalid, 6u);
  EXPECT_EQ(f.exchanges_in_window(), 0);
  EXPECT_FALSE(f.synchronised(t));
  EXPECT_EQ(f.to_ours(t), t);  // identity before the first exchange
  // A sane one afterwards is taken, and far-away stamps convert without overflow.
  EXPECT_EQ(f.add({t, t + 1h, t + 1h, t + 2ms}), V::kAccepted);
  (void)f.to_ours(TimePoint::min());
  (void)f.to_ours(TimePoint::max());
  EXPECT_NEAR(to_seconds(f.offset_at(t)), 3600.0 - 0.001, 1e-6);
}
