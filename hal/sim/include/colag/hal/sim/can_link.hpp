#pragma once
// A CAN bus in memory between the UGV board (the real CanWheelOdometry / CanDrive drivers) and
// the simulated motor controller: two CanBus endpoints; a frame sent on one is received on the
// other, stamped with the simulated time of sending.
#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/hal/can_bus.hpp"
#include "colag/hal/clock.hpp"

namespace colag::hal::sim {

class SimCanLink {
 public:
  explicit SimCanLink(const hal::Clock& clock)
      : board_(*this, 0), motor_(*this, 1), clock_(clock) {}
  hal::CanBus& board() { return board_; }
  hal::CanBus& motor() { return motor_; }
  // Fault injection: frames sent while the link is down are lost (counted as tx failures).
  void set_down(bool down) { down_ = down; }

 private:
  class End final : public hal::CanBus {
   public:
    End(SimCanLink& link, int side) : link_(link), side_(side) {}
    Status send(const hal::CanFrame& frame, TimePoint deadline) override;
    bool receive(hal::CanFrame& out) override;
    hal::CanBusStats stats() const override { return stats_; }

   private:
    friend class SimCanLink;
    SimCanLink& link_;
    int side_;
    RingBuffer<hal::CanFrame, limits::kCanRxQueue> inbox_;
    hal::CanBusStats stats_;
  };
  End board_, motor_;
  const hal::Clock& clock_;
  bool down_ = false;
};

}  // namespace colag::hal::sim
