// The real-time executor on the real clock. These tests assert counts and ordering that hold
// however loaded the machine is; they never assert how fast anything ran.
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/mman.h>

#include <thread>
#include <vector>

#include "colag/platform/realtime_executor.hpp"

using namespace colag;
using namespace colag::platform;
using namespace std::chrono_literals;

namespace {

class RecordingTask final : public Task {
 public:
  RecordingTask(const char* name, std::vector<std::pair<char, TimePoint>>& log, Duration busy = {},
                const hal::Clock* clock = nullptr)
      : name_(name), log_(log), busy_(busy), clock_(clock) {}
  const char* name() const override { return name_; }
  void on_overrun(Duration) override { ++reported_overruns; }
  std::uint64_t reported_overruns = 0;
  void step(TimePoint now) override {
    log_.emplace_back(name_[0], now);
    if (clock_ != nullptr) {
      const TimePoint until = clock_->now() + busy_;
      while (clock_->now() < until) {
      }
    }
  }

 private:
  const char* name_;
  std::vector<std::pair<char, TimePoint>>& log_;
  Duration busy_;
  const hal::Clock* clock_;
};

// Every release before the row's next pending one was either run or skipped.
std::uint64_t releases_before(TimePoint start, Duration period, TimePoint next_release) {
  return static_cast<std::uint64_t>((next_release - start) / period);
}

}  // namespace

TEST(RealtimeExecutor, ReleasesOnTheGridInTableOrderWithEveryActivationAccounted) {
  std::vector<std::pair<char, TimePoint>> log;
  log.reserve(1000);
  RealtimeExecutor ex;
  RecordingTask a("a", log), b("b", log);
  ASSERT_TRUE(ex.add({&a, 5ms, 2ms}));
  ASSERT_TRUE(ex.add({&b, 10ms, 2ms}));
  ASSERT_TRUE(ex.init());
  const TimePoint start = ex.schedule().release_of(0);
  const TimePoint end = start + 200ms;
  ex.run_until(end);

  const TaskStats& sa = ex.schedule().stats(0);
  const TaskStats& sb = ex.schedule().stats(1);
  EXPECT_EQ(sa.steps + sa.skipped, releases_before(start, 5ms, ex.schedule().release_of(0)));
  EXPECT_EQ(sb.steps + sb.skipped, releases_before(start, 10ms, ex.schedule().release_of(1)));
  EXPECT_GT(ex.schedule().release_of(0), end);
  EXPECT_GT(ex.schedule().release_of(1), end);
  EXPECT_GE(ex.clock().now(), end);

  TimePoint last_a = TimePoint::min(), last_b = TimePoint::min();
  for (std::size_t i = 0; i < log.size(); ++i) {
    const auto& [who, t] = log[i];
    EXPECT_EQ((t - start) % (who == 'a' ? 5ms : 10ms), Duration::zero()) << "off the release grid";
    TimePoint& last = who == 'a' ? last_a : last_b;
    EXPECT_GT(t, last);
    last = t;
    // When both are released at the same instant, the table order (a first) holds.
    if (who == 'b' && i > 0 && log[i - 1].second == t) {
      EXPECT_EQ(log[i - 1].first, 'a');
    }
  }
}

TEST(RealtimeExecutor, CountsAStepLongerThanItsBudgetAsAnOverrun) {
  std::vector<std::pair<char, TimePoint>> log;
  log.reserve(100);
  RealtimeExecutor ex;
  RecordingTask slow("slow", log, 3ms, &ex.clock());
  ASSERT_TRUE(ex.add({&slow, 10ms, 1ms}));
  ASSERT_TRUE(ex.init());
  ex.run_until(ex.schedule().release_of(0) + 100ms);
  const TaskStats& st = ex.schedule().stats(0);
  EXPECT_GT(st.steps, 0u);
  EXPECT_EQ(st.overruns, st.steps);  // busy-waiting 3 ms always exceeds a 1 ms budget
  EXPECT_GE(st.longest_step, 3ms);
  EXPECT_EQ(slow.reported_overruns, st.overruns);  // and the task heard of each
}

TEST(RealtimeExecutor, ATaskLongerThanItsPeriodSkipsActivationsInsteadOfBursting) {
  std::vector<std::pair<char, TimePoint>> log;
  log.reserve(100);
  RealtimeExecutor ex;
  RecordingTask hog("hog", log, 25ms, &ex.clock());
  ASSERT_TRUE(ex.add({&hog, 10ms, 20ms}));
  ASSERT_TRUE(ex.init());
  const TimePoint start = ex.schedule().release_of(0);
  const TimePoint end = start + 200ms;
  ex.run_until(end);
  const TaskStats& st = ex.schedule().stats(0);
  EXPECT_GT(st.skipped, 0u);
  EXPECT_EQ(st.steps + st.skipped, releases_before(start, 10ms, ex.schedule().release_of(0)));
  EXPECT_GT(ex.schedule().release_of(0), end);
  EXPECT_EQ(st.overruns, st.steps);
  for (std::size_t i = 1; i < log.size(); ++i) {
    // Each step takes 25 ms, so consecutive activations are at least 2 periods apart.
    EXPECT_GE(log[i].second - log[i - 1].second, 20ms);
  }
}

TEST(RealtimeExecutor, StopsOnRequestFromAnotherThread) {
  std::vector<std::pair<char, TimePoint>> log;
  log.reserve(10000);
  RealtimeExecutor ex;
  RecordingTask t("t", log);
  ASSERT_TRUE(ex.add({&t, 1ms, 1ms}));
  ASSERT_TRUE(ex.init());
  std::thread stopper([&] {
    std::this_thread::sleep_for(50ms);
    ex.request_stop();
  });
  const auto n = ex.run();  // would run forever without the stop request
  stopper.join();
  EXPECT_GT(n, 0u);
}

TEST(RealtimeExecutor, RealtimeRequestsSucceedOrReportPermission) {
  RealtimeExecutor ex;
  const RealtimeSetup none = ex.apply({});
  EXPECT_FALSE(none.fifo_requested);
  EXPECT_FALSE(none.memory_lock_requested);

  const RealtimeSetup rt = ex.apply({10, true});
  EXPECT_TRUE(rt.fifo || rt.fifo.code() == Errc::kPermissionDenied) << rt.fifo.message();
  EXPECT_TRUE(rt.memory_lock || rt.memory_lock.code() == Errc::kPermissionDenied);
  if (rt.fifo) {
    EXPECT_EQ(sched_getscheduler(0), SCHED_FIFO);
    sched_param sp{};
    sched_setscheduler(0, SCHED_OTHER, &sp);  // leave the test process as we found it
  }
  if (rt.memory_lock) munlockall();
}

// Software-in-the-loop time: every process scales CLOCK_MONOTONIC alike.
TEST(MonotonicClock, AScaledClockRunsFasterAndMapsBackToTheMonotonicClock) {
  const MonotonicClock real, fast(3.0);
  const TimePoint r = real.now();
  const TimePoint f = fast.now();
  const TimePoint r2 = real.now();
  const double ratio = static_cast<double>(f.time_since_epoch().count()) /
                       static_cast<double>(r.time_since_epoch().count());
  EXPECT_NEAR(ratio, 3.0,
              3.0 * static_cast<double>((r2 - r).count() + 1000) /
                  static_cast<double>(r.time_since_epoch().count()));
  EXPECT_NEAR(static_cast<double>(fast.monotonic_ns(f)),
              static_cast<double>(r.time_since_epoch().count()),
              static_cast<double>((r2 - r).count()) + 10.0);
  EXPECT_EQ(real.monotonic_ns(r), r.time_since_epoch().count());
}

TEST(RealtimeExecutor, AScaledExecutorReleasesOnItsOwnClock) {
  std::vector<std::pair<char, TimePoint>> log;
  log.reserve(100);
  RealtimeExecutor ex(4.0);
  RecordingTask t("t", log);
  ASSERT_TRUE(ex.add({&t, 40ms, 40ms}));
  ASSERT_TRUE(ex.init());
  const TimePoint start = ex.schedule().release_of(0);
  const MonotonicClock wall;
  const TimePoint wall_start = wall.now();
  ex.run_until(start + 400ms);               // 400 ms of scaled time: 100 ms of wall time
  EXPECT_GE(wall.now() - wall_start, 90ms);  // it did wait (a lower bound: never flaky)
  ASSERT_EQ(log.size(), 11u);                // every scaled release ran
  for (std::size_t i = 0; i < log.size(); ++i)
    EXPECT_EQ(log[i].second, start + i * 40ms);
}
