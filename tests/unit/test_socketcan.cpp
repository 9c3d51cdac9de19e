// SocketCAN: the CanBus conformance suite on a real kernel CAN interface, plus what only a
// kernel does (receive filters, error frames, the interface going down and up). Needs AF_CAN and
// a vcan0 (or $COLAG_CAN_INTERFACE): these run inside the HIL VM (scripts/hil); elsewhere they
// skip and say why.
#include <linux/can.h>
#include <linux/can/error.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <thread>

#include "can_bus_conformance.hpp"
#include "colag/hal/linux/socketcan_bus.hpp"
#include "colag/platform/monotonic_clock.hpp"

namespace colag::test {
namespace {

std::string interface_name() {
  const char* env = std::getenv("COLAG_CAN_INTERFACE");
  return env != nullptr ? env : "vcan0";
}

linux_hal::SocketCanConfig config(std::initializer_list<linux_hal::CanFilter> filters = {}) {
  linux_hal::SocketCanConfig c;
  c.interface = interface_name();
  c.reconnect_period = std::chrono::milliseconds(50);
  for (const auto& f : filters)
    (void)c.filters.push_back(f);
  return c;
}

struct SocketPair final : CanBusPair {
  platform::MonotonicClock clock_;
  linux_hal::SocketCanBus bus_a{config(), clock_}, bus_b{config(), clock_};
  hal::CanBus& a() override { return bus_a; }
  hal::CanBus& b() override { return bus_b; }
  const hal::Clock& clock() const override { return clock_; }
  void wait(Duration d) override { std::this_thread::sleep_for(d); }
};

std::unique_ptr<SocketPair> open_pair(std::string& why) {
  auto pair = std::make_unique<SocketPair>();
  const Status s = pair->bus_a.open();
  if (!s.is_ok()) {
    why = std::string(s.message()) + " (" + interface_name() + ": " +
          std::strerror(pair->bus_a.driver_stats().last_errno) + ")";
    return nullptr;
  }
  if (!pair->bus_b.open().is_ok()) {
    why = "second socket failed";
    return nullptr;
  }
  return pair;
}

INSTANTIATE_TEST_SUITE_P(SocketCan, CanBusConformance,
                         ::testing::Values(CanBusImplementation{
                             "SocketCan",
                             [](std::string& why) -> std::unique_ptr<CanBusPair> {
                               return open_pair(why);
                             }}),
                         [](const auto& p) { return p.param.name; });

class SocketCan : public ::testing::Test {
 protected:
  void SetUp() override {
    pair_ = open_pair(why_);
    if (!pair_) GTEST_SKIP() << "SocketCAN not available here: " << why_;
  }
  bool receive_within(hal::CanBus& bus, hal::CanFrame& out, int ms = 200) {
    return test::receive_within(*pair_, bus, out, ms);
  }
  TimePoint soon() const { return pair_->clock_.now() + std::chrono::milliseconds(50); }
  std::string why_;
  std::unique_ptr<SocketPair> pair_;
};

hal::CanFrame frame(std::uint32_t id) {
  hal::CanFrame f;
  f.id = id;
  f.dlc = 8;
  return f;
}

TEST_F(SocketCan, KernelFiltersPassOnlyOurIds) {
  linux_hal::SocketCanBus filtered(config({{0x101, 0x7FF}, {0x102, 0x7FF}}), pair_->clock_);
  ASSERT_TRUE(filtered.open().is_ok());
  for (std::uint32_t id : {0x101u, 0x555u, 0x102u, 0x100u})
    ASSERT_TRUE(pair_->bus_a.send(frame(id), soon()).is_ok());
  hal::CanFrame got;
  ASSERT_TRUE(receive_within(filtered, got));
  EXPECT_EQ(got.id, 0x101u);
  ASSERT_TRUE(receive_within(filtered, got));
  EXPECT_EQ(got.id, 0x102u);
  EXPECT_FALSE(receive_within(filtered, got, 20));
  EXPECT_EQ(filtered.stats().rx_frames, 2u);
}

TEST_F(SocketCan, ErrorFramesAreSurfacedNotReturnedAsData) {
  // A controller reports bus-off and error-passive as error frames; on vcan we write them from
  // a raw socket, which the kernel passes to sockets that enabled error frames.
  const int raw = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  ASSERT_GE(raw, 0);
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(if_nametoindex(interface_name().c_str()));
  ASSERT_EQ(::bind(raw, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  can_frame err{};
  err.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF | CAN_ERR_CRTL;
  err.len = CAN_ERR_DLC;
  err.data[1] = CAN_ERR_CRTL_TX_PASSIVE;
  ASSERT_EQ(::write(raw, &err, sizeof err), static_cast<ssize_t>(sizeof err))
      << std::strerror(errno);
  ::close(raw);
  hal::CanFrame got;
  EXPECT_FALSE(receive_within(pair_->bus_b, got, 50));  // not data
  EXPECT_EQ(pair_->bus_b.stats().error_frames, 1u);
  EXPECT_TRUE(pair_->bus_b.stats().bus_off);
  EXPECT_TRUE(pair_->bus_b.stats().error_passive);
  EXPECT_EQ(pair_->bus_b.stats().rx_frames, 0u);
}

TEST_F(SocketCan, ReconnectsAfterTheInterfaceGoesDownAndUp) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to take " << interface_name() << " down";
  const std::string down = "ip link set " + interface_name() + " down";
  const std::string up = "ip link set " + interface_name() + " up";
  ASSERT_EQ(std::system(down.c_str()), 0);
  EXPECT_EQ(pair_->bus_a.send(frame(0x101), soon()).code(), Errc::kUnavailable);
  EXPECT_FALSE(pair_->bus_a.is_open());
  ASSERT_EQ(std::system(up.c_str()), 0);
  // Both ends notice the outage on their next call and reopen after reconnect_period; frames
  // sent while the receiving end is still closed are gone (as on a real bus that was down).
  bool received = false;
  for (int i = 0; i < 40 && !received; ++i) {
    hal::CanFrame got;
    (void)pair_->bus_a.send(frame(0x123), soon());
    received = receive_within(pair_->bus_b, got, 30) && got.id == 0x123u;
  }
  EXPECT_TRUE(received);
  EXPECT_GE(pair_->bus_a.driver_stats().reconnects, 1u);
  EXPECT_GE(pair_->bus_b.driver_stats().reconnects, 1u);
}

}  // namespace
}  // namespace colag::test
