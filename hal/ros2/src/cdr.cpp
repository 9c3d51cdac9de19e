#include "colag/hal/ros2/cdr.hpp"

#include <dds/ddsi/ddsi_cdrstream.h>
#include <dds/ddsi/q_protocol.h>

namespace colag::hal::ros2 {

bool to_cdr(const void* sample, const dds_topic_descriptor_t& type,
            std::vector<std::uint8_t>& out) {
  dds_ostreamLE_t os;
  dds_ostreamLE_init(&os, 256, CDR_ENC_VERSION_1);
  const bool ok = dds_stream_writeLE(&os, static_cast<const char*>(sample), type.m_ops) != nullptr;
  out.assign({0x00, 0x01, 0x00, 0x00});  // CDR_LE: plain CDR, little endian, no options
  if (ok) out.insert(out.end(), os.x.m_buffer, os.x.m_buffer + os.x.m_index);
  dds_ostreamLE_fini(&os);
  return ok;
}

}  // namespace colag::hal::ros2
