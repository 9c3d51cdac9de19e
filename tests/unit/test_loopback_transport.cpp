#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "allocation_counter.hpp"
#include "colag/platform/lane_outbox.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/platform/readers.hpp"

using namespace colag;
using namespace colag::platform;
using namespace std::chrono_literals;

namespace {

msg::UgvStatus status(RobotId id, std::uint32_t n) {
  msg::UgvStatus s;
  s.ugv_id = id;
  s.rejected_inputs = n;  // used as a sequence number in these tests
  return s;
}

// Records the order of everything it receives.
class Recorder final : public SampleSink {
 public:
  void on_sample(msg::Topic, const void* sample, TimePoint) override {
    seen.push_back(static_cast<const msg::UgvStatus*>(sample)->rejected_inputs);
  }
  std::vector<std::uint32_t> seen;
};

class LoopbackTest : public ::testing::Test {
 protected:
  std::unique_ptr<LoopbackTransport> bus = std::make_unique<LoopbackTransport>(1);
};

}  // namespace

TEST_F(LoopbackTest, DeliversAtTheNextPollNotBefore) {
  LatestReader<msg::UgvStatus> reader;
  ASSERT_TRUE(reader.attach(*bus));
  bus->poll(TimePoint{0ms});
  ASSERT_TRUE(bus->publish(status(1, 42)));
  EXPECT_FALSE(reader.has_value());
  bus->poll(TimePoint{10ms});
  ASSERT_TRUE(reader.has_value());
  EXPECT_EQ(reader.value().rejected_inputs, 42u);
  EXPECT_EQ(reader.received_at(), TimePoint{10ms});
  msg::UgvStatus out;
  EXPECT_TRUE(reader.take(out));
  EXPECT_FALSE(reader.take(out));  // taken once
}

TEST_F(LoopbackTest, KeyFilterRoutesByRobot) {
  QueueReader<msg::MapPatch, 8> for3;
  QueueReader<msg::MapPatch, 8> for_all;
  ASSERT_TRUE(for3.attach(*bus, 3));
  ASSERT_TRUE(for_all.attach(*bus));
  for (RobotId id = 0; id < 5; ++id) {
    msg::MapPatch p;
    p.ugv_id = id;
    ASSERT_TRUE(bus->publish(p));
  }
  bus->poll(TimePoint{1ms});
  EXPECT_EQ(for3.size(), 1u);
  EXPECT_EQ(for_all.size(), 5u);
  msg::MapPatch got;
  ASSERT_TRUE(for3.pop(got));
  EXPECT_EQ(got.ugv_id, 3);
}

TEST_F(LoopbackTest, QueueReaderKeepsTheNewestAndCountsWhatItDropped) {
  QueueReader<msg::UgvStatus, 4> q;
  ASSERT_TRUE(q.attach(*bus));
  for (std::uint32_t i = 0; i < 6; ++i)
    ASSERT_TRUE(bus->publish(status(0, i)));
  bus->poll(TimePoint{1ms});
  EXPECT_EQ(q.received(), 6u);
  EXPECT_EQ(q.overflowed(), 2u);
  msg::UgvStatus s;
  for (std::uint32_t expect = 2; expect < 6; ++expect) {
    ASSERT_TRUE(q.pop(s));
    EXPECT_EQ(s.rejected_inputs, expect);
  }
  EXPECT_FALSE(q.pop(s));
}

TEST_F(LoopbackTest, LatencyHoldsSamplesBack) {
  bus->set_faults({0.0, 100ms, 0ms, 0.0});
  LatestReader<msg::UgvStatus> reader;
  ASSERT_TRUE(reader.attach(*bus));
  bus->poll(TimePoint{1s});
  ASSERT_TRUE(bus->publish(status(0, 1)));
  bus->poll(TimePoint{1s + 99ms});
  EXPECT_FALSE(reader.has_value());
  EXPECT_EQ(bus->in_flight(), 1u);
  bus->poll(TimePoint{1s + 100ms});
  EXPECT_TRUE(reader.has_value());
  EXPECT_EQ(bus->in_flight(), 0u);
}

TEST_F(LoopbackTest, PerTopicFaultsLeaveOtherTopicsAlone) {
  bus->set_faults(msg::topic_of<msg::UgvStatus>, {1.0, 0ms, 0ms, 0.0});
  LatestReader<msg::UgvStatus> st;
  LatestReader<msg::CollisionInfo> ci;
  ASSERT_TRUE(st.attach(*bus));
  ASSERT_TRUE(ci.attach(*bus));
  ASSERT_TRUE(bus->publish(status(0, 1)));
  ASSERT_TRUE(bus->publish(msg::CollisionInfo{}));
  bus->poll(TimePoint{1ms});
  EXPECT_FALSE(st.has_value());
  EXPECT_TRUE(ci.has_value());
  EXPECT_EQ(bus->stats(msg::topic_of<msg::UgvStatus>).dropped, 1u);
  EXPECT_EQ(bus->stats(msg::topic_of<msg::CollisionInfo>).dropped, 0u);
}

namespace {
std::vector<std::uint32_t> lossy_run(std::uint64_t seed, double drop, double dup, Duration jitter,
                                     TransportStats* stats_out = nullptr) {
  auto bus = std::make_unique<LoopbackTransport>(seed);
  bus->set_faults({drop, 5ms, jitter, dup});
  Recorder rec;
  EXPECT_TRUE(bus->subscribe(msg::topic_of<msg::UgvStatus>, kAnyRobot, rec));
  TimePoint t{};
  for (std::uint32_t i = 0; i < 10000; ++i) {
    bus->poll(t);
    EXPECT_TRUE(bus->publish(status(0, i)));
    t += 1ms;
  }
  bus->poll(t + 1s);
  if (stats_out != nullptr) *stats_out = bus->stats();
  return rec.seen;
}
}  // namespace

TEST(LoopbackFaults, DropRateMatchesAndIsExactlyReproducible) {
  TransportStats st;
  const auto a = lossy_run(99, 0.3, 0.0, 0ms, &st);
  // Binomial(10000, 0.7): sigma = 45.8; 4 sigma = 183.
  EXPECT_NEAR(static_cast<double>(a.size()), 7000.0, 183.0);
  EXPECT_EQ(st.published, 10000u);
  EXPECT_EQ(st.dropped + st.delivered, 10000u);
  EXPECT_EQ(a, lossy_run(99, 0.3, 0.0, 0ms));  // same seed: the very same samples survive
  EXPECT_NE(a, lossy_run(100, 0.3, 0.0, 0ms));
}

TEST(LoopbackFaults, DuplicatesAreCountedAndDelivered) {
  TransportStats st;
  const auto a = lossy_run(5, 0.0, 0.2, 0ms, &st);
  EXPECT_NEAR(static_cast<double>(st.duplicated), 2000.0, 160.0);  // 4 sigma
  EXPECT_EQ(a.size(), 10000u + st.duplicated);
  EXPECT_EQ(st.delivered, a.size());
}

TEST(LoopbackFaults, JitterReordersDeterministically) {
  const auto a = lossy_run(8, 0.0, 0.0, 20ms);
  ASSERT_EQ(a.size(), 10000u);
  std::size_t inversions = 0;
  for (std::size_t i = 1; i < a.size(); ++i)
    inversions += a[i] < a[i - 1];
  EXPECT_GT(inversions, 100u);
  EXPECT_EQ(a, lossy_run(8, 0.0, 0.0, 20ms));
}

TEST_F(LoopbackTest, FullInFlightPoolRefusesAndRecovers) {
  bus->set_faults({0.0, 1s, 0ms, 0.0});
  Recorder rec;
  ASSERT_TRUE(bus->subscribe(msg::topic_of<msg::UgvStatus>, kAnyRobot, rec));
  bus->poll(TimePoint{0s});
  std::size_t refused = 0;
  for (std::uint32_t i = 0; i < limits::kLoopbackMaxInFlight + 10; ++i) {
    refused += bus->publish(status(0, i)).code() == Errc::kCapacityExceeded;
  }
  EXPECT_EQ(refused, 10u);
  EXPECT_EQ(bus->stats().overflowed, 10u);
  bus->poll(TimePoint{2s});
  EXPECT_EQ(rec.seen.size(), limits::kLoopbackMaxInFlight);
  EXPECT_TRUE(bus->publish(status(0, 1)));  // slots came back
}

TEST_F(LoopbackTest, RejectsNullSamples) {
  EXPECT_EQ(bus->publish(msg::topic_of<msg::UgvStatus>, nullptr).code(), Errc::kInvalidArgument);
  EXPECT_EQ(bus->stats().rejected, 1u);
}

TEST_F(LoopbackTest, PublishAndPollAllocateNothing) {
  bus->set_faults({0.1, 5ms, 10ms, 0.1});
  QueueReader<msg::MapPatch, 4> patches;
  LatestReader<msg::UgvStatus> statuses;
  ASSERT_TRUE(patches.attach(*bus));
  ASSERT_TRUE(statuses.attach(*bus));
  msg::MapPatch p;
  p.data.count = 100;
  colag::test::AllocationCounter counter;
  TimePoint t{};
  for (int i = 0; i < 1000; ++i) {
    bus->poll(t);
    (void)bus->publish(p);
    (void)bus->publish(status(1, static_cast<std::uint32_t>(i)));
    msg::MapPatch out;
    while (patches.pop(out)) {
    }
    t += 2ms;
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(statuses.updates(), 800u);
}

TEST_F(LoopbackTest, LaneOutboxKeepsSamplesUntilFlushedThenPublishesThemInOrder) {
  LaneOutbox outbox(*bus);
  Recorder rec;
  ASSERT_TRUE(
      outbox.subscribe(msg::topic_of<msg::UgvStatus>, kAnyRobot, rec));  // on the shared bus
  for (std::uint32_t n = 0; n < limits::kLaneOutboxSamples; ++n)
    ASSERT_TRUE(outbox.publish(status(1, n)));
  EXPECT_EQ(outbox.publish(status(1, 99)).code(), Errc::kCapacityExceeded);
  EXPECT_EQ(outbox.publish(msg::topic_of<msg::UgvStatus>, nullptr).code(), Errc::kInvalidArgument);
  outbox.poll(TimePoint{1ms});  // polling is the pump's job
  bus->poll(TimePoint{1ms});
  EXPECT_TRUE(rec.seen.empty());
  EXPECT_EQ(bus->stats().published, 0u);

  outbox.flush();
  EXPECT_EQ(outbox.size(), 0u);
  bus->poll(TimePoint{2ms});
  std::vector<std::uint32_t> expected;
  for (std::uint32_t n = 0; n < limits::kLaneOutboxSamples; ++n)
    expected.push_back(n);
  EXPECT_EQ(rec.seen, expected);
  EXPECT_EQ(outbox.stats().published, limits::kLaneOutboxSamples);
  EXPECT_EQ(outbox.stats().overflowed, 1u);
  EXPECT_EQ(outbox.stats().rejected, 1u);
}

// Each robot's port: the network counts what it carries to each one as DDS would, with the
// per-UGV topics in their UGV's partition and the fleet topics to every reader.
TEST_F(LoopbackTest, EachParticipantReceivesItsOwnAndTheFleetsTopicsAndTheBytesAreCounted) {
  constexpr std::size_t kUav = limits::kMaxUgvs;
  QueueReader<msg::MapPatch, 8> patches0, patches1;
  QueueReader<msg::UavOdometry, 8> odometry0;
  QueueReader<msg::UavOdometry, 8> odometry1_of_uav5;  // a key filter: no delivery, same bytes
  QueueReader<msg::UgvStatus, 8> statuses_at_uav;
  QueueReader<msg::MapPatch, 8> observer;  // the simulator's instruments: not a robot
  ASSERT_TRUE(patches0.attach(bus->port(0), 0));
  ASSERT_TRUE(odometry0.attach(bus->port(0)));
  ASSERT_TRUE(patches1.attach(bus->port(1), 1));
  ASSERT_TRUE(odometry1_of_uav5.attach(bus->port(1), 5));
  ASSERT_TRUE(statuses_at_uav.attach(bus->port(kUav)));
  ASSERT_TRUE(observer.attach(*bus));

  msg::MapPatch to0, to1;
  to0.ugv_id = 0;
  to0.data.count = 100;
  to1.ugv_id = 1;
  to1.data.count = 7;
  msg::UavOdometry odo;
  Transport& uav = bus->port(kUav);
  ASSERT_TRUE(uav.publish(to0));
  ASSERT_TRUE(uav.publish(to1));
  ASSERT_TRUE(uav.publish(odo));
  ASSERT_TRUE(bus->port(0).publish(status(0, 1)));
  bus->poll(TimePoint{1ms});

  EXPECT_EQ(patches0.size(), 1u);
  EXPECT_EQ(patches1.size(), 1u);
  EXPECT_EQ(odometry0.size(), 1u);
  EXPECT_EQ(odometry1_of_uav5.size(), 0u);
  EXPECT_EQ(statuses_at_uav.size(), 1u);
  EXPECT_EQ(observer.size(), 2u);

  const std::size_t patch0 = msg::wire_bytes(to0), patch1 = msg::wire_bytes(to1);
  const std::size_t odometry = msg::wire_bytes(odo), st = msg::wire_bytes(status(0, 1));
  EXPECT_EQ(patch0 - patch1, 93u);  // only the used bytes cross
  EXPECT_EQ(bus->traffic(0).bytes_in, patch0 + odometry);
  EXPECT_EQ(bus->traffic(0).samples_in, 2u);
  EXPECT_EQ(bus->traffic(1).bytes_in, patch1 + odometry);
  // and by topic
  const auto& by_topic = bus->traffic(1).bytes_in_by_topic;
  EXPECT_EQ(by_topic[static_cast<std::size_t>(msg::topic_of<msg::MapPatch>)], patch1);
  EXPECT_EQ(by_topic[static_cast<std::size_t>(msg::topic_of<msg::UavOdometry>)], odometry);
  EXPECT_EQ(by_topic[static_cast<std::size_t>(msg::topic_of<msg::UgvStatus>)], 0u);
  EXPECT_EQ(bus->traffic(kUav).bytes_in, st);
  EXPECT_EQ(bus->traffic(kUav).bytes_out, patch0 + patch1 + odometry);
  EXPECT_EQ(bus->traffic(0).bytes_out, st);
  EXPECT_EQ(bus->traffic(2).bytes_in, 0u);  // nobody there
}
