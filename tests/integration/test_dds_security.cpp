// DDS Security end to end (scripts/security/make-pki material, Cyclone's plugins): UGV 1 runs
// here with its fleet identity while other processes publish map patches and relative poses for
// it: the UAV (fleet identity), a rogue (identity from another CA, claiming to be the UAV), a
// participant without security, an intruder (valid identity, no permission for those topics) and a
// forger (the intruder's identity with UAV permissions it signed itself).
// Only the UAV's samples may arrive, and the UAV must hear the UGV. Then the same over ROS 2:
// only the operator identity's commands reach UGV 1's ROS 2 bridge.
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>  // environ

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/platform/dds/dds_transport.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/ugv/app/ugv_ros2_bridge.hpp"
#include "dds_test_env.hpp"

namespace {

using namespace colag;
using namespace std::chrono_literals;

// Counts samples per sending UAV id.
template <class Msg>
class CountBySender final : public platform::SampleSink {
 public:
  void on_sample(msg::Topic, const void* sample, TimePoint) override {
    const auto& m = *static_cast<const Msg*>(sample);
    if (m.uav_id == 100)
      ++fleet;
    else
      ++other;
  }
  int fleet = 0, other = 0;
};

pid_t spawn(const char* role, std::uint32_t domain, const std::string& pki, const char* seconds) {
  const std::string d = std::to_string(domain);
  char* argv[] = {const_cast<char*>(COLAG_DDS_SECURE_PEER_PATH),
                  const_cast<char*>(role),
                  const_cast<char*>(d.c_str()),
                  const_cast<char*>(pki.c_str()),
                  const_cast<char*>(seconds),
                  nullptr};
  pid_t pid = -1;
  if (posix_spawn(&pid, COLAG_DDS_SECURE_PEER_PATH, nullptr, nullptr, argv, environ) != 0)
    return -1;
  return pid;
}
int exit_code(pid_t pid) {
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

platform::DdsSecurityConfig fleet_identity(const std::string& pki, const std::string& who) {
  platform::DdsSecurityConfig s;
  s.identity_ca = s.permissions_ca = pki + "/ca.pem";
  s.certificate = pki + "/" + who + "/identity.pem";
  s.private_key = pki + "/" + who + "/key.pem";
  s.governance = pki + "/governance.p7s";
  s.permissions = pki + "/" + who + "/permissions.p7s";
  return s;
}

TEST(DdsSecurity, OnlyTheFleetUavReachesTheUgvAndTheMissionTrafficFlows) {
  const std::string pki = COLAG_TEST_PKI_DIR;
  if (!std::filesystem::exists(pki + "/ugv1/identity.pem"))
    GTEST_SKIP() << "no test PKI in " << pki << " (the dds.security.pki fixture creates it)";
  test::confine_dds_to_loopback();
  const std::uint32_t domain = test::private_domain_id();

  // The intruder's writers are refused when it starts; so are UGV 2's writer and reader in
  // UGV 1's partition (it cannot speak for UGV 1, nor read what is meant for it).
  EXPECT_EQ(exit_code(spawn("intruder", domain, pki, "1")), 3);
  EXPECT_EQ(exit_code(spawn("spoofer", domain, pki, "1")), 3);
  EXPECT_EQ(exit_code(spawn("eavesdropper", domain, pki, "1")), 3);

  platform::dds::DdsConfig cfg;
  cfg.domain_id = domain;
  cfg.security = fleet_identity(pki, "ugv1");
  cfg.ugvs = {1, 1};
  cfg.publish_only<msg::CollisionInfo, msg::UgvStatus>();
  platform::dds::DdsTransport dds;
  ASSERT_TRUE(dds.init(cfg)) << dds_strretcode(dds.last_error());
  CountBySender<msg::MapPatch> patches;
  CountBySender<msg::RelativePose> poses;
  ASSERT_TRUE(dds.subscribe(msg::topic_of<msg::MapPatch>, 1, patches));
  ASSERT_TRUE(dds.subscribe(msg::topic_of<msg::RelativePose>, 1, poses));

  const pid_t uav = spawn("uav", domain, pki, "8");
  const pid_t rogue = spawn("rogue", domain, pki, "8");
  const pid_t plain = spawn("plain", domain, pki, "8");
  const pid_t forger = spawn("forger", domain, pki, "8");
  ASSERT_GT(uav, 0);
  ASSERT_GT(rogue, 0);
  ASSERT_GT(plain, 0);
  ASSERT_GT(forger, 0);
  const auto end = std::chrono::steady_clock::now() + 9s;
  while (std::chrono::steady_clock::now() < end) {
    msg::UgvStatus st;
    st.ugv_id = 1;
    st.mode = msg::UgvMode::kDriving;
    (void)dds.publish(st);
    dds.poll(TimePoint{});
    std::this_thread::sleep_for(50ms);
  }
  EXPECT_EQ(exit_code(uav), 0) << "the UAV never heard UGV 1";
  EXPECT_EQ(exit_code(rogue), 0);
  EXPECT_EQ(exit_code(plain), 0);
  EXPECT_EQ(exit_code(forger), 0);
  // Authentication takes a few hundred ms; then the UAV's ~20 samples/s arrive.
  EXPECT_GE(patches.fleet, 40);
  EXPECT_GE(poses.fleet, 40);
  EXPECT_EQ(patches.other, 0);
  EXPECT_EQ(poses.other, 0);
  std::printf(
      "UGV 1 accepted %d patches and %d relative poses from the fleet UAV, %d / %d from "
      "others\n",
      patches.fleet, poses.fleet, patches.other, poses.other);
}

// UGV 1's ROS 2 bridge, secured with its identity, takes commands from the operator (PAUSE)
// while a rogue, an unsecured participant and a forger send ABORT and the intruder (a fleet
// identity without the permission) cannot even create its writer: it must end paused, never
// aborted, every command it took the operator's.
TEST(DdsSecurity, OnlyTheOperatorCommandsAUgvOverRos2) {
  const std::string pki = COLAG_TEST_PKI_DIR;
  if (!std::filesystem::exists(pki + "/operator/identity.pem"))
    GTEST_SKIP() << "no test PKI in " << pki << " (the dds.security.pki fixture creates it)";
  test::confine_dds_to_loopback();
  const std::uint32_t domain = test::private_domain_id();
  EXPECT_EQ(exit_code(spawn("intruder-commands", domain, pki, "1")), 3);

  ugv::UgvNavConfig config;
  config.id = 1;
  // On the heap: a UGV task and a simulated network together outgrow a thread's stack.
  const auto bus = std::make_unique<platform::LoopbackTransport>(1);
  hal::scripted::ScriptedWheelOdometry odo;
  hal::scripted::RecordingDrive drive;
  const auto owned = std::make_unique<ugv::UgvNavTask>(config, *bus, odo, drive);
  ugv::UgvNavTask& task = *owned;
  ugv::UgvRos2Bridge bridge(task);
  board::Ros2Config ros2;
  ros2.enabled = true;
  std::string error;
  ASSERT_TRUE(bridge.start(domain, ros2, fleet_identity(pki, "ugv1"), error)) << error;

  const pid_t op = spawn("operator", domain, pki, "6");
  const pid_t rogue = spawn("rogue-commands", domain, pki, "6");
  const pid_t plain = spawn("plain-commands", domain, pki, "6");
  const pid_t forger = spawn("forger-commands", domain, pki, "6");
  for (pid_t p : {op, rogue, plain, forger})
    ASSERT_GT(p, 0);
  TimePoint now{};
  const auto end = std::chrono::steady_clock::now() + 7s;
  while (std::chrono::steady_clock::now() < end) {
    bridge.step(now += 50ms);
    std::this_thread::sleep_for(50ms);
  }
  EXPECT_EQ(exit_code(op), 0);
  EXPECT_EQ(exit_code(plain), 0);
  EXPECT_EQ(exit_code(forger), 0);  // its forged permissions let it write: UGV 1 must not take
  // The rogue holds the UAV's permissions (no commands): its own access control refuses it.
  EXPECT_EQ(exit_code(rogue), 3);
  const ugv::UgvRos2Counters c = bridge.counters();
  EXPECT_TRUE(task.paused());
  EXPECT_FALSE(task.aborted());
  EXPECT_GE(c.commands, 20U);  // the operator's ~10/s, after authentication
  EXPECT_EQ(c.commands_refused, 0U);
  std::printf("UGV 1 took %llu commands over ROS 2, all the operator's\n",
              static_cast<unsigned long long>(c.commands));
}

TEST(DdsSecurity, AMissingFileIsNamedBeforeDdsStarts) {
  platform::dds::DdsConfig cfg;
  cfg.security.identity_ca = "/nonexistent/ca.pem";
  platform::dds::DdsTransport dds;
  const Status s = dds.init(cfg);
  EXPECT_FALSE(s);
  EXPECT_NE(std::string(s.message()).find("identity_ca"), std::string::npos) << s.message();
}

}  // namespace
