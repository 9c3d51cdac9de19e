#include "colag/platform/lane_outbox.hpp"

#include <cstring>

namespace colag::platform {

Status LaneOutbox::publish(msg::Topic topic, const void* sample) {
  if (static_cast<std::size_t>(topic) >= msg::kTopicCount || sample == nullptr) {
    ++stats_.rejected;
    return {Errc::kInvalidArgument, "lane outbox: bad topic or null sample"};
  }
  if (!kept_.resize(kept_.size() + 1)) {
    ++stats_.overflowed;
    return {Errc::kCapacityExceeded, "lane outbox: full"};
  }
  Kept& k = kept_.back();
  std::memcpy(k.bytes.data(), sample, msg::topic_info(topic).size_bytes);
  k.topic = topic;
  ++stats_.published;
  return Status::ok();
}

void LaneOutbox::flush() {
  for (const Kept& k : kept_) {
    if (!shared_.publish(k.topic, k.bytes.data())) ++stats_.rejected;
  }
  kept_.clear();
}

}  // namespace colag::platform
