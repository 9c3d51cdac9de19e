#pragma once
// The UAV's side of fleet time (see msg/clock_sync.hpp): every clock request, a UGV's or another
// UAV's, is answered at once with this UAV's receive and send times. Runs in the control loop
// (50 Hz), so a request waits at most one control period; the askers' filters use the exchanges
// with the shortest round trips. The time server answers on its own clock; another UAV stands in
// only while it knows fleet time and does not hear the server, answering in the fleet time it
// learnt (see platform/fleet_clock.hpp: who takes a stand-in's answer). Allocation-free.
#include <optional>

#include <cstdint>

#include "colag/msg/clock_sync.hpp"
#include "colag/platform/readers.hpp"

namespace colag::uav {

class ClockServer {
 public:
  Status attach(platform::Transport& transport, RobotId uav_id);
  // `fleet_minus_local`: what to add to this UAV's clock for fleet time (zero on the time
  // server); none: no answers now (the requests are dropped).
  void step(TimePoint now, std::optional<Duration> fleet_minus_local = Duration::zero());
  std::uint64_t answered() const { return answered_; }

 private:
  platform::Transport* transport_ = nullptr;
  RobotId uav_id_ = 0;
  platform::QueueReader<msg::ClockRequest, limits::kMaxUgvs> requests_;
  platform::QueueReader<msg::UavClockRequest, limits::kMaxUavs> uav_requests_;
  std::uint64_t answered_ = 0;
};

}  // namespace colag::uav
