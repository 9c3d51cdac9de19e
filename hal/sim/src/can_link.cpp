#include "colag/hal/sim/can_link.hpp"

namespace colag::hal::sim {

Status SimCanLink::End::send(const hal::CanFrame& frame, TimePoint) {
  // The same refusals as SocketCAN (the shared conformance suite checks both).
  if (!hal::is_valid(frame)) {
    ++stats_.tx_failures;
    return {Errc::kInvalidArgument, "CAN frame: dlc > 8 or id too large"};
  }
  if (link_.down_) {
    ++stats_.tx_failures;
    return {Errc::kUnavailable, "CAN link down"};
  }
  End& peer = side_ == 0 ? link_.motor_ : link_.board_;
  hal::CanFrame f = frame;
  f.stamp = link_.clock_.now();
  if (peer.inbox_.push_overwrite(f)) ++peer.stats_.rx_overruns;
  ++stats_.tx_frames;
  return Status::ok();
}

bool SimCanLink::End::receive(hal::CanFrame& out) {
  if (!inbox_.pop_front(out)) return false;
  ++stats_.rx_frames;
  return true;
}

}  // namespace colag::hal::sim
