// colag_dds_peer: the other process of the multi-process DDS test. Publishes UgvStatus samples
// of UGV 5 (sequence in rejected_inputs) every 20 ms until it receives a CollisionInfo cancel
// from UGV 5's supervisor, then exits 0; exits 1 after 20 s without one.
// Usage: colag_dds_peer DOMAIN_ID
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "colag/platform/dds/dds_transport.hpp"
#include "colag/platform/readers.hpp"
#include "dds_test_env.hpp"

using namespace colag;
using namespace std::chrono_literals;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: colag_dds_peer DOMAIN_ID\n");
    return 2;
  }
  test::confine_dds_to_loopback();
  platform::dds::DdsTransport dds;
  platform::dds::DdsConfig cfg;
  cfg.domain_id = static_cast<std::uint32_t>(std::atoi(argv[1]));
  if (Status s = dds.init(cfg); !s) {
    std::fprintf(stderr, "colag_dds_peer: %s (%s)\n", s.message(),
                 dds_strretcode(dds.last_error()));
    return 2;
  }
  platform::LatestReader<msg::CollisionInfo> acks;
  if (!acks.attach(dds, 5)) return 2;

  const auto deadline = std::chrono::steady_clock::now() + 20s;
  std::uint32_t seq = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    msg::UgvStatus st;
    st.ugv_id = 5;
    st.mode = msg::UgvMode::kDriving;
    st.position_m[0] = 1.25;
    st.position_m[1] = -3.5;
    st.rejected_inputs = seq++;
    (void)dds.publish(st);
    dds.poll(TimePoint{});
    if (acks.has_value() && acks.value().cancel) {
      std::printf("colag_dds_peer: acknowledged after %u samples\n", seq);
      return 0;
    }
    std::this_thread::sleep_for(20ms);
  }
  std::fprintf(stderr, "colag_dds_peer: no acknowledgement within 20 s\n");
  return 1;
}
