// Two processes, one robot each, talking only through Cyclone DDS on the loopback interface.
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>

#include "colag/platform/dds/dds_transport.hpp"
#include "colag/platform/readers.hpp"
#include "dds_test_env.hpp"

using namespace colag;
using namespace std::chrono_literals;

TEST(DdsMultiProcess, StatusFromAnotherProcessArrivesAndTheAnswerGoesBack) {
  test::confine_dds_to_loopback();
  const std::uint32_t domain = test::private_domain_id();
  platform::dds::DdsTransport dds;
  platform::dds::DdsConfig cfg;
  cfg.domain_id = domain;
  ASSERT_TRUE(dds.init(cfg));
  platform::QueueReader<msg::UgvStatus, 64> statuses;
  ASSERT_TRUE(statuses.attach(dds, 5));

#ifdef COLAG_DDS_PEER_IS_HOST
  // The cross build's run: this arm64 process (under qemu) and the host's amd64 peer.
  if (::access(COLAG_DDS_PEER_PATH, X_OK) != 0)
    GTEST_SKIP() << COLAG_DDS_PEER_PATH << " is missing: build the host preset first";
#endif
  const std::string domain_arg = std::to_string(domain);
  char* argv[] = {const_cast<char*>(COLAG_DDS_PEER_PATH), const_cast<char*>(domain_arg.c_str()),
                  nullptr};
  pid_t child = 0;
  ASSERT_EQ(posix_spawn(&child, COLAG_DDS_PEER_PATH, nullptr, nullptr, argv, environ), 0);

  // Wait for the peer's status (discovery + first samples).
  msg::UgvStatus got;
  bool received = false;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (!received && std::chrono::steady_clock::now() < deadline) {
    dds.poll(TimePoint{});
    received = statuses.pop(got);
    if (!received) std::this_thread::sleep_for(5ms);
  }
  ASSERT_TRUE(received) << "no UgvStatus from the peer process within 20 s";
  EXPECT_EQ(got.ugv_id, 5);
  EXPECT_EQ(got.mode, msg::UgvMode::kDriving);
  EXPECT_EQ(got.position_m[0], 1.25);
  EXPECT_EQ(got.position_m[1], -3.5);

  // Answer; the peer exits 0 once it hears it.
  msg::CollisionInfo ack;
  ack.ugv_id = 5;
  ack.cancel = true;
  int status = 0;
  pid_t done = 0;
  while (done == 0 && std::chrono::steady_clock::now() < deadline + 10s) {
    ASSERT_TRUE(dds.publish(ack));
    std::this_thread::sleep_for(20ms);
    done = waitpid(child, &status, WNOHANG);
  }
  if (done == 0) {
    kill(child, SIGKILL);
    waitpid(child, &status, 0);
    FAIL() << "peer did not receive the acknowledgement";
  }
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(dds.dds_stats().malformed, 0u);
}
