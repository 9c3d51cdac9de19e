#include "dds_test_env.hpp"

#include <unistd.h>

#include <cstdlib>

namespace colag::test {

void confine_dds_to_loopback() {
  setenv("CYCLONEDDS_URI",
         "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces></General>", 1);
}

std::uint32_t private_domain_id() {
  // Domain ids 0..232 are valid; keep clear of 0 (the default that robots use).
  return 20 + static_cast<std::uint32_t>(getpid()) % 200;
}

}  // namespace colag::test
