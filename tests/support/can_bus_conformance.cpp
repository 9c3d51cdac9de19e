#include "can_bus_conformance.hpp"

#include <array>

namespace colag::test {

bool receive_within(CanBusPair& pair, hal::CanBus& bus, hal::CanFrame& out, int ms) {
  for (int i = 0; i < ms; ++i) {
    if (bus.receive(out)) return true;
    pair.wait(std::chrono::milliseconds(1));
  }
  return false;
}

namespace {
hal::CanFrame frame(std::uint32_t id, std::uint8_t dlc, std::uint8_t seed, bool extended = false) {
  hal::CanFrame f;
  f.id = id;
  f.extended = extended;
  f.dlc = dlc;
  for (std::uint8_t i = 0; i < dlc; ++i)
    f.data[i] = static_cast<std::uint8_t>(seed * 31 + i);
  return f;
}
TimePoint soon(const CanBusPair& p) {
  return p.clock().now() + std::chrono::milliseconds(50);
}
}  // namespace

TEST_P(CanBusConformance, NothingQueuedMeansReceiveReturnsAtOnce) {
  hal::CanFrame out;
  EXPECT_FALSE(pair_->a().receive(out));
  EXPECT_FALSE(pair_->b().receive(out));
}

TEST_P(CanBusConformance, FramesArriveUnchangedAndInOrder) {
  for (std::uint8_t k = 0; k < 50; ++k) {
    const hal::CanFrame sent = frame(0x100 + k, static_cast<std::uint8_t>(k % 9), k);
    ASSERT_TRUE(pair_->a().send(sent, soon(*pair_)).is_ok());
    hal::CanFrame got;
    ASSERT_TRUE(receive_within(pair_->b(), got)) << "frame " << int{k};
    EXPECT_EQ(got.id, sent.id);
    EXPECT_EQ(got.extended, false);
    ASSERT_EQ(got.dlc, sent.dlc);
    for (int i = 0; i < sent.dlc; ++i)
      EXPECT_EQ(got.data[i], sent.data[i]);
  }
  EXPECT_EQ(pair_->a().stats().tx_frames, 50u);
  EXPECT_EQ(pair_->b().stats().rx_frames, 50u);
}

TEST_P(CanBusConformance, BothDirectionsAndExtendedIds) {
  ASSERT_TRUE(pair_->b().send(frame(0x1ABCDE01, 8, 3, true), soon(*pair_)).is_ok());
  hal::CanFrame got;
  ASSERT_TRUE(receive_within(pair_->a(), got));
  EXPECT_TRUE(got.extended);
  EXPECT_EQ(got.id, 0x1ABCDE01u);
  EXPECT_EQ(got.data[7], static_cast<std::uint8_t>(3 * 31 + 7));
}

TEST_P(CanBusConformance, BurstIsDeliveredCompletelyInOrder) {
  constexpr int kBurst = 40;  // below every implementation's queue depth
  for (int k = 0; k < kBurst; ++k)
    ASSERT_TRUE(
        pair_->a().send(frame(0x200, 8, static_cast<std::uint8_t>(k)), soon(*pair_)).is_ok());
  for (int k = 0; k < kBurst; ++k) {
    hal::CanFrame got;
    ASSERT_TRUE(receive_within(pair_->b(), got)) << "frame " << k;
    EXPECT_EQ(got.data[0], static_cast<std::uint8_t>(k * 31)) << "frame " << k;
  }
}

TEST_P(CanBusConformance, StampsAreMonotonicAndNotInTheFuture) {
  TimePoint previous{};
  for (std::uint8_t k = 0; k < 5; ++k) {
    ASSERT_TRUE(pair_->a().send(frame(0x300, 2, k), soon(*pair_)).is_ok());
    pair_->wait(std::chrono::milliseconds(2));
    hal::CanFrame got;
    ASSERT_TRUE(receive_within(pair_->b(), got));
    EXPECT_GE(got.stamp, previous);
    EXPECT_LE(got.stamp, pair_->clock().now());
    previous = got.stamp;
  }
}

TEST_P(CanBusConformance, InvalidFramesAreRefusedAndCounted) {
  hal::CanFrame too_long = frame(0x123, 8, 1);
  too_long.dlc = 9;
  EXPECT_EQ(pair_->a().send(too_long, soon(*pair_)).code(), Errc::kInvalidArgument);
  EXPECT_EQ(pair_->a().send(frame(0x800, 1, 1), soon(*pair_)).code(),
            Errc::kInvalidArgument);  // not an 11-bit id
  EXPECT_EQ(pair_->a().stats().tx_failures, 2u);
  hal::CanFrame got;
  pair_->wait(std::chrono::milliseconds(5));
  EXPECT_FALSE(pair_->b().receive(got));
}

}  // namespace colag::test
