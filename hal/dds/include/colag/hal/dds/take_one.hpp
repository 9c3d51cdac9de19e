#pragma once
// Taking DDS samples one at a time, on loan from Cyclone (no copy of ours): the sim link, the
// PX4 and ROS 2 drivers.
#include <dds/dds.h>

namespace colag::hal::dds {

// Takes the oldest sample of `reader` and hands it to `use` if it carries data (not a
// dispose). Returns false when nothing was queued.
template <class Sample, class Use>
bool take_one(dds_entity_t reader, Use&& use) {
  if (reader <= 0) return false;
  void* samples[1] = {nullptr};
  dds_sample_info_t info[1];
  const dds_return_t n = dds_take(reader, samples, info, 1, 1);
  if (n <= 0) return false;
  if (info[0].valid_data) use(*static_cast<const Sample*>(samples[0]));
  dds_return_loan(reader, samples, n);
  return true;
}

}  // namespace colag::hal::dds
