// colag_dds_secure_peer: the other processes of the DDS Security test.
// Usage: colag_dds_secure_peer ROLE DOMAIN_ID PKI_DIR SECONDS
//   uav       fleet identity of the UAV: publishes map patches and relative poses for UGV 1
//             (uav_id 100) every 50 ms; exits 0 if it heard UGV 1's status, 1 if not
//   rogue     an identity from another CA claiming to be the UAV: publishes the same with uav_id 66
//   plain     no security at all: publishes the same with uav_id 77
//   forger    the intruder's valid identity with self-signed UAV permissions: publishes the same
//             with uav_id 88
//   intruder  a valid fleet identity allowed to publish UGV status only: tries to create map
//             patch and relative pose writers; exits 3 when access control refuses them, 0 if it
//             could publish (a failure of the test)
//   spoofer   UGV 2's identity writing statuses in UGV 1's partition (as UGV 1); exits 3 when
//             access control refuses the writer
//   eavesdropper  UGV 2's identity reading UGV 1's map patches; exits 3 when the reader is
//             refused
// ROS 2 commands to UGV 1 (rt/ugv1/command, colag_msgs/UgvCommand, every 100 ms):
//   operator             the fleet's operator identity: PAUSE (the only one allowed)
//   ROLE-commands        ROLE = rogue, plain, forger, intruder as above: ABORT; exits 3 when its
//                        own access control refuses the writer (the intruder's case)
// Exit 2: usage or set-up error.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "colag/hal/dds/device_participant.hpp"
#include "colag/hal/ros2/ros2_names.hpp"
#include "colag/platform/dds/dds_security.hpp"
#include "colag/platform/dds/dds_transport.hpp"
#include "colag/platform/readers.hpp"
#include "dds_test_env.hpp"
#include "ros2_msgs.h"

using namespace colag;
using namespace std::chrono_literals;

namespace {

platform::DdsSecurityConfig identity(const std::string& pki, const std::string& who,
                                     const std::string& ca) {
  platform::DdsSecurityConfig s;
  s.identity_ca = ca;
  s.certificate = pki + "/" + who + "/identity.pem";
  s.private_key = pki + "/" + who + "/key.pem";
  s.permissions_ca = pki + "/ca.pem";
  s.governance = pki + "/governance.p7s";
  s.permissions = pki + "/" + who + "/permissions.p7s";
  return s;
}

// Sends `command` to UGV 1 over ROS 2 for `run_for` as `role`, secured by `security`.
int send_commands(const std::string& role, std::uint32_t domain,
                  const platform::DdsSecurityConfig& security, std::uint8_t command,
                  std::chrono::seconds run_for) {
  platform::dds::ParticipantQos qos;
  if (Status s = qos.init(security); !s) {
    std::printf("colag_dds_secure_peer %s: %s\n", role.c_str(), s.message());
    return 2;
  }
  hal::dds::DeviceParticipant dds;
  if (!dds.init(domain, qos.get())) {
    std::printf("colag_dds_secure_peer %s: %s\n", role.c_str(), dds.last_error().c_str());
    return 2;
  }
  const dds_entity_t w =
      dds.writer(hal::ros2::ros2_dds_topic("ugv1", "command"), colag_msgs_msg_dds__UgvCommand__desc,
                 {.reliable = true, .depth = 10});
  if (w <= 0) {
    std::printf("colag_dds_secure_peer %s: no command writer: %s\n", role.c_str(),
                dds.last_error().c_str());
    return dds.last_error().find("Security") != std::string::npos ? 3 : 2;
  }
  colag_msgs_msg_dds__UgvCommand_ c{};
  c.header.frame_id = const_cast<char*>("");  // NOLINT(cppcoreguidelines-pro-type-const-cast)
  c.command = command;
  const auto end = std::chrono::steady_clock::now() + run_for;
  while (std::chrono::steady_clock::now() < end) {
    ++c.id;
    (void)dds_write(w, &c);
    std::this_thread::sleep_for(100ms);
  }
  std::printf("colag_dds_secure_peer %s: sent %u commands %u\n", role.c_str(), c.id,
              static_cast<unsigned>(command));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(
        stderr,
        "usage: colag_dds_secure_peer uav|rogue|plain|forger|intruder|spoofer|eavesdropper DOMAIN "
        "PKI SECONDS\n");
    return 2;
  }
  const std::string pki = argv[3];
  std::string role = argv[1];
  const bool commands = role == "operator" || role.ends_with("-commands");
  if (role.ends_with("-commands")) role.resize(role.size() - 9);
  const auto run_for = std::chrono::seconds(std::atoi(argv[4]));
  test::confine_dds_to_loopback();
  platform::dds::DdsConfig cfg;
  cfg.domain_id = static_cast<std::uint32_t>(std::atoi(argv[2]));
  RobotId uav_id = 100;
  // The UAV's writers only (its permissions allow nothing else); the intruder tries all.
  if (role != "intruder")
    cfg.publish_only<msg::UavOdometry, msg::RelativePose, msg::MapPatch, msg::SupportPlan>();
  cfg.ugvs = {0, 3};  // the test fleet's UGVs (make-pki --ugvs 3)
  if (role == "uav") {
    cfg.security = identity(pki, "uav", pki + "/ca.pem");
  } else if (role == "rogue") {
    cfg.security = identity(pki, "rogue", pki + "/rogue/ca/ca.pem");
    uav_id = 66;
  } else if (role == "plain") {
    uav_id = 77;
  } else if (role == "forger") {
    cfg.security = identity(pki, "forger", pki + "/ca.pem");
    cfg.security.permissions_ca = pki + "/rogue/ca/ca.pem";  // trusts its own signature
    cfg.security.governance = pki + "/forger/governance.p7s";
    uav_id = 88;
  } else if (role == "intruder") {
    cfg.security = identity(pki, "intruder", pki + "/ca.pem");
  } else if (role == "spoofer" || role == "eavesdropper") {
    // UGV 2's identity, in UGV 1's partition: to publish statuses as UGV 1, or read its patches.
    cfg.security = identity(pki, "ugv2", pki + "/ca.pem");
    cfg.ugvs = {1, 1};
    if (role == "spoofer")
      cfg.publish_only<msg::UgvStatus>();
    else
      cfg.publish_only<>();
  } else if (role == "operator") {
    cfg.security = identity(pki, "operator", pki + "/ca.pem");
  } else {
    std::fprintf(stderr, "colag_dds_secure_peer: unknown role %s\n", role.c_str());
    return 2;
  }

  if (commands) {
    return send_commands(role, cfg.domain_id, cfg.security, role == "operator" ? 1 : 3, run_for);
  }
  platform::dds::DdsTransport dds;
  const bool refused_role = role == "intruder" || role == "spoofer" || role == "eavesdropper";
  Status started = dds.init(cfg);
  if (started && role == "eavesdropper") {
    static platform::LatestReader<msg::MapPatch> patches;
    started = patches.attach(dds, 1);
  }
  if (!started) {
    std::printf("colag_dds_secure_peer %s: %s (%s)\n", role.c_str(), started.message(),
                dds_strretcode(dds.last_error()));
    // Access control must refuse the intruder's writers for the UAV's topics, the spoofer's
    // writer in another UGV's partition and the eavesdropper's reader there.
    return refused_role && dds.last_error() == DDS_RETCODE_NOT_ALLOWED_BY_SECURITY ? 3 : 2;
  }
  if (refused_role) {
    std::printf("colag_dds_secure_peer %s: access control let it in\n", role.c_str());
    return 0;
  }
  platform::LatestReader<msg::UgvStatus> status;
  if (!status.attach(dds, 1)) return 2;

  const auto end = std::chrono::steady_clock::now() + run_for;
  std::uint32_t seq = 0;
  while (std::chrono::steady_clock::now() < end) {
    msg::MapPatch patch;
    patch.uav_id = uav_id;
    patch.ugv_id = 1;
    patch.seq = ++seq;
    patch.resolution_m = 0.1;
    (void)dds.publish(patch);
    msg::RelativePose rpe;
    rpe.uav_id = uav_id;
    rpe.ugv_id = 1;
    (void)dds.publish(rpe);
    dds.poll(TimePoint{});
    std::this_thread::sleep_for(50ms);
  }
  const bool heard = status.has_value();
  std::printf("colag_dds_secure_peer %s: sent %u patches; UGV 1's status %s\n", role.c_str(), seq,
              heard ? "received" : "never received");
  return role == "uav" && !heard ? 1 : 0;
}
