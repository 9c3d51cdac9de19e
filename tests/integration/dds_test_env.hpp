#pragma once
// Shared by the DDS tests and their peer process.
#include <cstdint>

namespace colag::test {

// Confines Cyclone DDS to the loopback interface (no multicast on the machine's network).
// Must be called before the first participant is created.
void confine_dds_to_loopback();

// A DDS domain id private to this test process (the same on every call), held against other
// test processes and SITL runs on this machine, so that none hears another.
std::uint32_t private_domain_id();

}  // namespace colag::test
