// Two DDS participants in one process (two robots on one host): every message type crosses
// Cyclone's serialiser and arrives equal; keys filter per robot; QoS from the topic table.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "allocation_counter.hpp"
#include "colag/platform/dds/dds_transport.hpp"
#include "colag/platform/readers.hpp"
#include "dds_test_env.hpp"

using namespace colag;
using namespace colag::platform;
using namespace std::chrono_literals;

namespace {

class DdsPair : public ::testing::Test {
 protected:
  void SetUp() override {
    test::confine_dds_to_loopback();
    dds::DdsConfig cfg;
    cfg.domain_id = test::private_domain_id();
    ASSERT_TRUE(a.init(cfg)) << dds_strretcode(a.last_error());
    ASSERT_TRUE(b.init(cfg)) << dds_strretcode(b.last_error());
  }
  // Publishes from A (again and again: best-effort topics may lose samples sent before
  // discovery) until `done` holds at B, or 10 s pass.
  bool exchange(const std::function<void()>& publish, const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (std::chrono::steady_clock::now() < deadline) {
      publish();
      for (int i = 0; i < 4; ++i) {
        std::this_thread::sleep_for(5ms);
        b.poll(TimePoint{});
        if (done()) return true;
      }
    }
    return false;
  }
  template <class Msg>
  void expect_round_trip(const Msg& sent, RobotId key) {
    LatestReader<Msg> reader;
    ASSERT_TRUE(reader.attach(b, key));
    ASSERT_TRUE(
        exchange([&] { ASSERT_TRUE(a.publish(sent)); }, [&] { return reader.has_value(); }));
    EXPECT_TRUE(reader.value() == sent);
  }
  dds::DdsTransport a, b;
};

}  // namespace

TEST_F(DdsPair, EveryMessageTypeArrivesEqual) {
  msg::UavOdometry od;
  od.stamp = TimePoint{123456789ns};
  od.position_m[0] = 1.5;
  od.orientation_wxyz[3] = 0.25;
  od.velocity_mps[1] = -2.0;
  expect_round_trip(od, kAnyRobot);

  msg::RelativePose rp;
  rp.stamp = TimePoint{5s};
  rp.ugv_id = 4;
  for (int i = 0; i < 16; ++i)
    rp.covariance[i] = i * 0.01;
  expect_round_trip(rp, 4);

  msg::MapPatch mp;
  mp.ugv_id = 2;
  mp.seq = 77;
  mp.resolution_m = 0.1;
  mp.origin_x_m = -3.2;
  mp.width_cells = 50;
  mp.height_cells = 50;
  mp.encoding = msg::MapPatchEncoding::kRunLength;
  mp.data.count = 321;
  for (int i = 0; i < 321; ++i)
    mp.data[i] = static_cast<std::uint8_t>(i * 7);
  expect_round_trip(mp, 2);

  msg::CollisionInfo ci;
  ci.ugv_id = 9;
  ci.seq = 3;
  ci.collision_point_m[0] = 4.0;
  ci.support_point_m[1] = -7.0;
  ci.time_to_collision_s = 2.5;
  expect_round_trip(ci, 9);

  msg::UgvStatus st;
  st.ugv_id = 1;
  st.mode = msg::UgvMode::kWaitingForSupport;
  st.covariance[4] = 0.3;
  st.waiting_time_s = 12.0;
  expect_round_trip(st, 1);

  msg::SupportPlan sp;
  sp.seq = 8;
  sp.stops.count = 3;
  for (int i = 0; i < 3; ++i) {
    sp.stops[i].ugv_id = static_cast<RobotId>(i + 1);
    sp.stops[i].point_m[0] = i;
    sp.stops[i].eta_s = 2.0 * i;
    sp.stops[i].deadline_s = 3.0 * i;
  }
  expect_round_trip(sp, kAnyRobot);
  EXPECT_EQ(b.dds_stats().malformed, 0u);
}

TEST_F(DdsPair, KeyFilterDeliversOnlyThatRobotsSamples) {
  QueueReader<msg::MapPatch, 64> for3;
  ASSERT_TRUE(for3.attach(b, 3));
  msg::MapPatch p2, p3;
  p2.ugv_id = 2;
  p3.ugv_id = 3;
  std::size_t got3 = 0, got_other = 0;
  ASSERT_TRUE(exchange(
      [&] {
        ASSERT_TRUE(a.publish(p2));
        ASSERT_TRUE(a.publish(p3));
      },
      [&] {
        msg::MapPatch m;
        while (for3.pop(m))
          (m.ugv_id == 3 ? got3 : got_other)++;
        return got3 >= 3;
      }));
  EXPECT_EQ(got_other, 0u);
}

// A UGV's participant joins only its own partition: the UAV's patches for other UGVs never
// reach it (not filtered on arrival: never sent to it), and it can publish only as itself.
TEST_F(DdsPair, AUgvParticipantReceivesOnlyItsOwnPartitionAndSpeaksOnlyAsItself) {
  dds::DdsTransport ugv3;
  dds::DdsConfig cfg;
  cfg.domain_id = test::private_domain_id();
  cfg.ugvs = {3, 1};
  cfg.publish_only<msg::UgvStatus>();
  ASSERT_TRUE(ugv3.init(cfg));
  QueueReader<msg::MapPatch, 64> any;  // every key it can see
  ASSERT_TRUE(any.attach(ugv3));
  QueueReader<msg::MapPatch, 4> for2;
  EXPECT_EQ(for2.attach(ugv3, 2).code(), Errc::kInvalidArgument);
  msg::MapPatch p2, p3;
  p2.ugv_id = 2;
  p3.ugv_id = 3;
  std::size_t got3 = 0, got_other = 0;
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (got3 < 3 && std::chrono::steady_clock::now() < deadline) {
    ASSERT_TRUE(a.publish(p2));
    ASSERT_TRUE(a.publish(p3));
    std::this_thread::sleep_for(10ms);
    ugv3.poll(TimePoint{});
    msg::MapPatch m;
    while (any.pop(m))
      (m.ugv_id == 3 ? got3 : got_other)++;
  }
  EXPECT_GE(got3, 3u);
  EXPECT_EQ(got_other, 0u);

  msg::UgvStatus as_other;
  as_other.ugv_id = 1;
  EXPECT_EQ(ugv3.publish(as_other).code(), Errc::kInvalidArgument);
  msg::UgvStatus as_itself;
  as_itself.ugv_id = 3;
  EXPECT_TRUE(ugv3.publish(as_itself));
  cfg.ugvs = {30, 5};  // past kMaxUgvs
  dds::DdsTransport bad;
  EXPECT_EQ(bad.init(cfg).code(), Errc::kInvalidArgument);
}

TEST_F(DdsPair, WriterOnlyForTopicsTheRobotPublishes) {
  dds::DdsTransport ugv;
  dds::DdsConfig cfg;
  cfg.domain_id = test::private_domain_id();
  cfg.publish_only<msg::UgvStatus>();
  ASSERT_TRUE(ugv.init(cfg));
  EXPECT_EQ(ugv.publish(msg::MapPatch{}).code(), Errc::kInvalidArgument);
  EXPECT_TRUE(ugv.publish(msg::UgvStatus{}));
  EXPECT_EQ(ugv.stats().rejected, 1u);
}

// The board's publish path allocates nothing on the publishing thread (a task's): publish()
// copies into the outbox, and the transport's writer thread hands the sample to Cyclone, which
// allocates for every write (it did so on the task's thread before: 2 allocations per status, 5
// per map patch). Counted on the publishing thread only: Cyclone's own threads allocate by design.
TEST_F(DdsPair, PublishAllocatesNothingOnThePublishingThread) {
  LatestReader<msg::UgvStatus> statuses;
  ASSERT_TRUE(statuses.attach(b));
  msg::UgvStatus st;
  st.ugv_id = 4;
  msg::MapPatch patch;
  patch.ugv_id = 4;
  patch.data.count = 300;
  for (int i = 0; i < 20; ++i) {  // warm-up: writers matched, first samples through
    ASSERT_TRUE(a.publish(st));
    ASSERT_TRUE(a.publish(patch));
  }
  a.flush();
  {
    test::AllocationCounter counter(test::AllocationCounter::Threads::kThisOne);
    for (int i = 0; i < 30; ++i) {
      st.waiting_time_s = i;
      ASSERT_TRUE(a.publish(st));
      ASSERT_TRUE(a.publish(patch));
    }
    EXPECT_EQ(counter.count(), 0u);
  }
  a.flush();
  EXPECT_EQ(a.stats().published, 100u);  // every sample reached DDS, in spite of the queue
  EXPECT_EQ(a.stats().overflowed, 0u);
  // The samples really go out: the last one arrives (the reader keeps the last 4 per UGV).
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (!(statuses.has_value() && statuses.value().waiting_time_s == 29.0) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(5ms);
    b.poll(TimePoint{});
  }
  ASSERT_TRUE(statuses.has_value());
  EXPECT_EQ(statuses.value().waiting_time_s, 29.0);
}
