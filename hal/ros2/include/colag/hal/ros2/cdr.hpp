#pragma once
// A DDS sample as the CDR bytes a ROS 2 peer receives (and `ros2 bag` / MCAP's `cdr` encoding
// stores): the 4-byte encapsulation header (XCDR1, little endian), then the data, serialised
// by Cyclone's own serializer from the type's generated descriptor (one encoder: the same one
// that puts the sample on the wire). Host tools only: it allocates.
#include <dds/dds.h>

#include <cstdint>
#include <vector>

namespace colag::hal::ros2 {

// Replaces `out` with the bytes of `sample` (a struct of `type`). False if Cyclone refuses it.
bool to_cdr(const void* sample, const dds_topic_descriptor_t& type, std::vector<std::uint8_t>& out);

}  // namespace colag::hal::ros2
