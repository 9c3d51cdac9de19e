#pragma once
// Shared by the DDS tests and their peer process.
#include <cstdint>

namespace colag::test {

// Confines Cyclone DDS to the loopback interface (no multicast on the machine's network).
// Must be called before the first participant is created.
void confine_dds_to_loopback();

// A DDS domain id private to this test run (derived from the process id), so that parallel
// test processes do not hear each other.
std::uint32_t private_domain_id();

}  // namespace colag::test
