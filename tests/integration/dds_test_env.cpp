#include "dds_test_env.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace colag::test {

void confine_dds_to_loopback() {
  setenv("CYCLONEDDS_URI",
         "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces></General>", 1);
}

std::uint32_t private_domain_id() {
  // Taken as scripts/lib/claim-domain.sh takes a SITL run's (even domains 10..208, the odd one
  // above each being a SITL run's sim link): held by an flock on the same per-domain file for the
  // life of this process, so that neither another test process nor a SITL run shares it. Drawn
  // from the process id alone, a test once met a SITL run's sim link on its domain and Cyclone ran
  // out of participant indices for the two.
  static const std::uint32_t domain = [] {
    const char* env = std::getenv("COLAG_DOMAIN_LOCKS");
    const std::string dir = env != nullptr ? env : "/tmp/colag-sitl-domains";
    (void)mkdir(dir.c_str(), 0777);  // it may exist
    const int first = static_cast<int>(getpid() % 100);
    for (int k = 0; k < 100; ++k) {
      const int d = 10 + ((first + k) % 100) * 2;
      const std::string path = dir + "/domain-" + std::to_string(d) + ".lock";
      const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
      if (fd < 0) continue;
      if (flock(fd, LOCK_EX | LOCK_NB) == 0) return static_cast<std::uint32_t>(d);  // kept open
      close(fd);
    }
    return 20 + static_cast<std::uint32_t>(getpid() % 200);  // every lock taken: as before
  }();
  return domain;
}

}  // namespace colag::test
