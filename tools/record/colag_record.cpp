// colag_record: records a live fleet (SITL or robots with `ros2.enabled`) as MCAP, as
// `ros2 bag record` would: every ROS 2 topic of the telemetry's types that appears on the DDS
// domain (found through DDS discovery, so any fleet size and namespace), each sample stored as
// the CDR bytes it travelled as, with the type's ros2msg schema; log time = when it was received
// (this host's wall clock), publish time = the writer's source timestamp.
//
//   colag_record --domain D --out FILE [--duration S] [--security pki/operator/security.yaml]
//
// --security: join a fleet that runs DDS Security with an identity make-pki made (the operator's
// may read every ROS 2 topic).
//
// Stops on SIGINT/SIGTERM or after --duration, then writes the file's summary. Prints progress
// every 5 s. Exit codes: 0 recorded (the file is complete); 1 DDS or the file failed; 2 usage.
#include <dds/dds.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "colag/board/config.hpp"
#include "colag/hal/ros2/cdr.hpp"
#include "colag/hal/ros2/ros2_schemas.hpp"
#include "colag/hal/ros2/ros2_types.hpp"
#include "colag/platform/dds/dds_security.hpp"
#include "colag/sim/host_program.hpp"
#include "colag/sim/mcap/mcap_writer.hpp"

namespace {

using namespace colag;  // NOLINT(google-build-using-namespace): a program's main file

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) {
  g_stop.store(true);
}

std::uint64_t wall_ns() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::system_clock::now().time_since_epoch())
                                        .count());
}

struct Recorded {
  dds_entity_t reader = 0;
  const hal::ros2::Ros2Type* type = nullptr;
  std::uint16_t channel = 0;
  std::uint64_t messages = 0;
};

int run(int argc, char** argv) {
  CLI::App app{"colag_record: a live fleet's ROS 2 telemetry into an MCAP file"};
  unsigned domain = 0;
  std::string out;
  double duration = -1.0;
  app.add_option("--domain", domain, "the fleet's DDS domain (the robots' dds.domain)")
      ->required()
      ->check(CLI::Range(0U, 232U));
  app.add_option("--out", out, "the MCAP file to write")->required();
  app.add_option("--duration", duration, "stop after this many seconds (default: at Ctrl-C)")
      ->check(CLI::PositiveNumber);
  std::string security_file;
  app.add_option("--security", security_file,
                 "a secured fleet: the security.yaml of an identity from make-pki "
                 "(pki/operator/security.yaml)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  platform::DdsSecurityConfig security;
  std::string error;
  if (!security_file.empty() && !board::read_security_file(security_file, security, error)) {
    std::fprintf(stderr, "colag_record: --security %s\n", error.c_str());
    return 2;
  }
  platform::dds::ParticipantQos participant_qos;
  if (Status s = participant_qos.init(security); !s) {
    std::fprintf(stderr, "colag_record: --security: %s\n", s.message());
    return 2;
  }

  mcap::McapWriter writer;
  if (!writer.open(out)) {
    std::fprintf(stderr, "colag_record: --out: %s\n", writer.error().c_str());
    return 2;
  }
  const dds_entity_t participant = dds_create_participant(domain, participant_qos.get(), nullptr);
  if (participant < 0) {
    std::fprintf(
        stderr, "colag_record: DDS domain %u: %s%s\n", domain, dds_strretcode(participant),
        security.enabled() ? " (security: identity, permissions or governance rejected?)" : "");
    return 1;
  }
  // Every writer on the domain, as discovery announces it.
  const dds_entity_t publications =
      dds_create_reader(participant, DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
  if (publications < 0) {
    std::fprintf(stderr, "colag_record: discovery: %s\n", dds_strretcode(publications));
    dds_delete(participant);
    return 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::printf("colag_record: recording DDS domain %u into %s%s\n", domain, out.c_str(),
              duration > 0 ? "" : " (Ctrl-C to stop)");
  std::fflush(stdout);

  std::map<std::string, Recorded> topics;  // by DDS topic name
  std::map<std::string, std::uint16_t> schemas;
  std::vector<std::uint8_t> cdr;
  std::uint64_t refused = 0;
  const auto t0 = std::chrono::steady_clock::now();
  auto next_report = t0 + std::chrono::seconds(5);
  while (!g_stop.load()) {
    const auto now = std::chrono::steady_clock::now();
    if (duration > 0 && now - t0 >= std::chrono::duration<double>(duration)) break;
    // New ROS 2 topics of a known type: a best-effort reader (it matches every writer).
    void* samples[8] = {};
    dds_sample_info_t infos[8];
    const dds_return_t n = dds_take(publications, samples, infos, 8, 8);
    for (dds_return_t i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      const auto* ep = static_cast<const dds_builtintopic_endpoint_t*>(samples[i]);
      const std::string name = ep->topic_name;
      const hal::ros2::Ros2Type* type = hal::ros2::find_ros2_type(ep->type_name);
      if (type == nullptr || name.rfind("rt/", 0) != 0 || topics.count(name) != 0) continue;
      const dds_entity_t topic =
          dds_create_topic(participant, type->descriptor, name.c_str(), nullptr, nullptr);
      dds_qos_t* qos = dds_create_qos();
      dds_qset_reliability(qos, DDS_RELIABILITY_BEST_EFFORT, 0);
      dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 64);
      const dds_entity_t reader =
          topic < 0 ? topic : dds_create_reader(participant, topic, qos, nullptr);
      dds_delete_qos(qos);
      if (reader < 0) {
        std::fprintf(stderr, "colag_record: %s: %s (not recorded)\n", name.c_str(),
                     dds_strretcode(reader));
        topics[name] = {};
        continue;
      }
      const std::string ros_type(type->ros_name);
      auto s = schemas.find(ros_type);
      if (s == schemas.end())
        s = schemas
                .emplace(ros_type, writer.add_schema(ros_type, "ros2msg",
                                                     hal::ros2::ros2msg_schema(ros_type)))
                .first;
      topics[name] = {reader, type, writer.add_channel(s->second, name.substr(2), "cdr"), 0};
      std::printf("colag_record: + %s (%s)\n", name.substr(2).c_str(), ros_type.c_str());
      std::fflush(stdout);
    }
    if (n > 0) dds_return_loan(publications, samples, n);

    for (auto& [name, r] : topics) {
      if (r.reader <= 0) continue;
      for (;;) {
        void* sample[1] = {nullptr};
        dds_sample_info_t info[1];
        const dds_return_t got = dds_take(r.reader, sample, info, 1, 1);
        if (got <= 0) break;
        if (info[0].valid_data) {
          if (hal::ros2::to_cdr(sample[0], *r.type->descriptor, cdr)) {
            const auto published =
                static_cast<std::uint64_t>(std::max<dds_time_t>(0, info[0].source_timestamp));
            if (writer.write(r.channel, wall_ns(), published, cdr)) ++r.messages;
          } else {
            ++refused;
          }
        }
        dds_return_loan(r.reader, sample, got);
      }
    }
    if (now >= next_report) {
      next_report += std::chrono::seconds(5);
      std::printf("colag_record: %.0f s: %llu messages on %zu topics, %.1f MB\n",
                  std::chrono::duration<double>(now - t0).count(),
                  static_cast<unsigned long long>(writer.messages()), topics.size(),
                  static_cast<double>(writer.bytes()) / 1e6);
      std::fflush(stdout);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  dds_delete(participant);
  if (!writer.close()) {
    std::fprintf(stderr, "colag_record: %s\n", writer.error().c_str());
    return 1;
  }
  std::printf("colag_record: %s: %llu messages on %zu topics, %.1f MB%s\n", out.c_str(),
              static_cast<unsigned long long>(writer.messages()), topics.size(),
              static_cast<double>(writer.bytes()) / 1e6,
              refused > 0 ? " (some samples could not be serialised)" : "");
  return refused > 0 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  return colag::sim::guarded_main("colag_record", 1, [&] { return run(argc, argv); });
}
