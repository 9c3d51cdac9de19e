#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <algorithm>
#include <mutex>

#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/platform/lane_outbox.hpp"
#include "colag/platform/lockstep_executor.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/platform/readers.hpp"
#include "colag/platform/worker_pool.hpp"

using namespace colag;
using namespace colag::platform;
using namespace std::chrono_literals;

namespace {

struct Event {
  std::string task;
  TimePoint at;
  bool operator==(const Event&) const = default;
};

class LoggingTask final : public Task {
 public:
  LoggingTask(std::string name, std::vector<Event>& log, const hal::Clock* clock = nullptr)
      : name_(std::move(name)), log_(log), clock_(clock) {}
  const char* name() const override { return name_.c_str(); }
  Status init(TimePoint) override {
    ++inits;
    return Status::ok();
  }
  void step(TimePoint now) override {
    log_.push_back({name_, now});
    if (clock_ != nullptr) clock_seen_now = clock_seen_now && clock_->now() == now;
  }
  int inits = 0;
  bool clock_seen_now = true;

 private:
  std::string name_;
  std::vector<Event>& log_;
  const hal::Clock* clock_;
};

}  // namespace

TEST(LockstepExecutor, RunsReleasesInTimeOrderAndTiesInTableOrder) {
  std::vector<Event> log;
  LockstepExecutor ex;
  LoggingTask a("a", log, &ex.clock()), b("b", log, &ex.clock()), c("c", log, &ex.clock());
  ASSERT_TRUE(ex.add({&b, 20ms, 1ms}));
  ASSERT_TRUE(ex.add({&a, 10ms, 1ms}));
  ASSERT_TRUE(ex.add({&c, 20ms, 1ms, 5ms}));
  ASSERT_TRUE(ex.init());
  EXPECT_EQ(a.inits, 1);
  ex.run_until(TimePoint{40ms});

  const std::vector<Event> expected = {
      {"b", TimePoint{0ms}},  {"a", TimePoint{0ms}},  {"c", TimePoint{5ms}},
      {"a", TimePoint{10ms}}, {"b", TimePoint{20ms}}, {"a", TimePoint{20ms}},
      {"c", TimePoint{25ms}}, {"a", TimePoint{30ms}}, {"b", TimePoint{40ms}},
      {"a", TimePoint{40ms}},
  };
  EXPECT_EQ(log, expected);
  EXPECT_EQ(ex.now(), TimePoint{40ms});
  EXPECT_TRUE(a.clock_seen_now && b.clock_seen_now && c.clock_seen_now);
  EXPECT_EQ(ex.schedule().stats(1).steps, 5u);
}

TEST(LockstepExecutor, RejectsBadRowsAndTooManyTasks) {
  std::vector<Event> log;
  LoggingTask t("t", log);
  LockstepExecutor ex;
  EXPECT_EQ(ex.add({nullptr, 10ms, 1ms}).code(), Errc::kInvalidArgument);
  EXPECT_EQ(ex.add({&t, 0ms, 1ms}).code(), Errc::kInvalidArgument);
  EXPECT_EQ(ex.add({&t, 10ms, 0ms}).code(), Errc::kInvalidArgument);
  for (std::size_t i = 0; i < limits::kMaxTasksPerExecutor; ++i)
    ASSERT_TRUE(ex.add({&t, 10ms, 1ms}));
  EXPECT_EQ(ex.add({&t, 10ms, 1ms}).code(), Errc::kCapacityExceeded);
}

TEST(LockstepExecutor, EmptyTableDoesNothing) {
  LockstepExecutor ex(TimePoint{5s});
  ASSERT_TRUE(ex.init());
  EXPECT_EQ(ex.step(), TimePoint{5s});
  ex.run_until(TimePoint{6s});
  EXPECT_EQ(ex.now(), TimePoint{6s});
}

namespace {
// A step that "takes" a scripted amount of host time, measured on a manual stopwatch.
class SlowTask final : public Task {
 public:
  SlowTask(hal::scripted::ManualClock& watch, Duration cost) : watch_(watch), cost_(cost) {}
  const char* name() const override { return "slow"; }
  void step(TimePoint) override { watch_.advance(cost_); }

 private:
  hal::scripted::ManualClock& watch_;
  Duration cost_;
};
}  // namespace

TEST(LockstepExecutor, CountsOverrunsFromTheStopwatchWithoutChangingTheSchedule) {
  hal::scripted::ManualClock watch;
  SlowTask slow(watch, 3ms);
  LockstepExecutor ex(TimePoint{}, &watch);
  ASSERT_TRUE(ex.add({&slow, 10ms, 1ms}));
  ASSERT_TRUE(ex.init());
  ex.run_until(TimePoint{95ms});
  const TaskStats& st = ex.schedule().stats(0);
  EXPECT_EQ(st.steps, 10u);  // 0, 10, ..., 90 ms: simulated time is not affected
  EXPECT_EQ(st.overruns, 10u);
  EXPECT_EQ(st.skipped, 0u);
  EXPECT_EQ(st.longest_step, 3ms);
  EXPECT_EQ(st.total_step, 30ms);
}

namespace {
// Publishes a counter and records everything it receives, to check that a faulty network under
// the lock-step executor still gives one exact outcome per seed.
class Chatter final : public Task {
 public:
  Chatter(Transport& t, RobotId id) : transport_(t), id_(id) {}
  const char* name() const override { return "chatter"; }
  Status init(TimePoint) override { return inbox_.attach(transport_); }
  void step(TimePoint now) override {
    msg::UgvStatus s;
    while (inbox_.pop(s))
      heard.push_back(s.ugv_id * 100000 + s.rejected_inputs);
    s = {};
    s.stamp = now;
    s.ugv_id = id_;
    s.rejected_inputs = counter_++;
    (void)transport_.publish(s);
  }
  std::vector<std::uint64_t> heard;

 private:
  Transport& transport_;
  RobotId id_;
  QueueReader<msg::UgvStatus, 64> inbox_;
  std::uint32_t counter_ = 0;
};

class FlushInOrder final : public LaneBarrier {
 public:
  void lanes_done(TimePoint) override {
    for (LaneOutbox* o : outboxes)
      o->flush();
  }
  std::vector<LaneOutbox*> outboxes;
};

// With `lanes`, each chatter is a lane of its own and publishes through an outbox.
std::vector<std::uint64_t> run_chatter(std::uint64_t seed, ForkJoin* lanes = nullptr) {
  auto bus = std::make_unique<LoopbackTransport>(seed);
  bus->set_faults({0.2, 15ms, 40ms, 0.1});
  TransportPump pump(*bus);
  LaneOutbox out_x(*bus), out_y(*bus);
  const bool laned = lanes != nullptr;
  Chatter x(laned ? static_cast<Transport&>(out_x) : *bus, 1);
  Chatter y(laned ? static_cast<Transport&>(out_y) : *bus, 2);
  FlushInOrder flush;
  flush.outboxes = {&out_x, &out_y};
  LockstepExecutor ex;
  if (laned) ex.set_lanes(lanes, &flush);
  EXPECT_TRUE(ex.add({&pump, 5ms, 1ms}));
  EXPECT_TRUE(ex.add({&x, 10ms, 1ms, 0ms, laned ? 1 : 0}));
  EXPECT_TRUE(ex.add({&y, 10ms, 1ms, 0ms, laned ? 2 : 0}));
  EXPECT_TRUE(ex.init());
  ex.run_until(TimePoint{3s});
  std::vector<std::uint64_t> all = x.heard;
  all.insert(all.end(), y.heard.begin(), y.heard.end());
  return all;
}
}  // namespace

TEST(LockstepExecutor, SameSeedSameRunThroughAFaultyNetwork) {
  const auto first = run_chatter(11);
  const auto second = run_chatter(11);
  const auto other = run_chatter(12);
  EXPECT_GT(first.size(), 500u);
  EXPECT_EQ(first, second);
  EXPECT_NE(first, other);
}

// Both chatters publish at the same instants, so the order in which their samples reach the
// network decides who hears what when: lanes running side by side, flushed in lane order, must
// give the same run (a flush in the other order does not: tried).
TEST(LockstepExecutor, LanesOnTwoThreadsSameRunAsTheTableInOrder) {
  const auto in_order = run_chatter(11);
  EXPECT_GT(in_order.size(), 500u);
  WorkerPool pool(1);
  EXPECT_EQ(run_chatter(11, &pool), in_order);
  SerialForkJoin serial;
  EXPECT_EQ(run_chatter(11, &serial), in_order);
}

namespace {
class LockedLog final : public Task {
 public:
  LockedLog(std::string name, std::vector<std::string>& log, std::mutex& m)
      : name_(std::move(name)), log_(log), mutex_(m) {}
  const char* name() const override { return name_.c_str(); }
  void step(TimePoint) override {
    const std::lock_guard lock(mutex_);
    log_.push_back(name_);
  }

 private:
  std::string name_;
  std::vector<std::string>& log_;
  std::mutex& mutex_;
};
class LoggingBarrier final : public LaneBarrier {
 public:
  LoggingBarrier(std::vector<std::string>& log, std::mutex& m) : log_(log), mutex_(m) {}
  void lanes_done(TimePoint) override {
    const std::lock_guard lock(mutex_);
    log_.push_back("|");
  }

 private:
  std::vector<std::string>& log_;
  std::mutex& mutex_;
};
}  // namespace

TEST(LockstepExecutor, LaneZeroFirstThenEachLaneInTableOrderThenTheBarrier) {
  std::vector<std::string> log;
  std::mutex m;
  LockedLog world("world", log, m), a1("a1", log, m), a2("a2", log, m), b1("b1", log, m),
      b2("b2", log, m);
  LoggingBarrier barrier(log, m);
  WorkerPool pool(1);
  LockstepExecutor ex;
  ex.set_lanes(&pool, &barrier);
  ASSERT_TRUE(ex.add({&world, 10ms, 1ms}));
  ASSERT_TRUE(ex.add({&a1, 10ms, 1ms, 0ms, 1}));
  ASSERT_TRUE(ex.add({&a2, 20ms, 1ms, 0ms, 1}));
  ASSERT_TRUE(ex.add({&b1, 10ms, 1ms, 0ms, 2}));
  ASSERT_TRUE(ex.add({&b2, 10ms, 1ms, 0ms, 2}));
  EXPECT_EQ(ex.add({&world, 10ms, 1ms, 0ms, 1}).code(), Errc::kInvalidArgument);  // decreasing
  EXPECT_EQ(ex.add({&world, 10ms, 1ms, 0ms, -1}).code(), Errc::kInvalidArgument);
  ASSERT_TRUE(ex.init());
  for (int instant = 0; instant < 4; ++instant) {
    log.clear();
    ex.step();
    ASSERT_EQ(log.size(), instant % 2 == 0 ? 6u : 5u) << instant;
    EXPECT_EQ(log.front(), "world");
    EXPECT_EQ(log.back(), "|");
    const auto at = [&](const std::string& n) { return std::find(log.begin(), log.end(), n); };
    EXPECT_LT(at("b1"), at("b2"));
    if (instant % 2 == 0) {
      EXPECT_LT(at("a1"), at("a2"));
    }
  }
}
