#pragma once
// The simulated UAV: a point mass that follows the flight controller's velocity setpoints within
// its speed and acceleration limits, and the HAL devices on top of it: OdometrySource and
// FlightController. The setpoint's position is not fed back here: the flight planner closes the
// position loop itself (a position term on a setpoint that is one step old pushes the vehicle
// forward and fights the planner's braking).
//
// Its odometry is exact in the ideal world (as in the paper). In the field world it is in the
// frame a LiDAR-inertial odometry builds (OdometryFrame), delivered late and stamped when
// measured. The flight controller works in that frame (PX4 flies on the estimate it is given).
#include "colag/common/ring_buffer.hpp"
#include "colag/hal/flight_controller.hpp"
#include "colag/hal/odometry_source.hpp"
#include "colag/sim/world/odometry_frame.hpp"

namespace colag::sim {

struct UavBodyConfig {
  double v_max_mps = 3.0;
  double a_max_mps2 = 1.0;
  UavOdometryErrors odometry;
  std::uint64_t seed = 1;
};

class UavBody final : public hal::FlightController, public hal::OdometrySource {
 public:
  UavBody(const UavBodyConfig& config, const Vec3& start);

  void step(TimePoint now, double dt);  // moves, then publishes the new state as odometry

  // hal::FlightController
  Status send_setpoint(const hal::FlightSetpoint& sp) override;
  // hal::OdometrySource
  bool poll(hal::UavState& out) override { return pending_.pop_front(out); }

  const hal::UavState& state() const { return state_; }  // the truth
  // Its odometry's frame: where the firmware's map, goals and estimates are.
  const OdometryFrame& odometry_frame() const { return frame_; }
  // Its odometry in another's frame from now on (a fleet's co-registered map); call each step
  // before step().
  void use_frame(const OdometryFrame& frame) {
    frame_ = frame;
    borrowed_frame_ = true;
  }
  double travelled_m() const { return travelled_; }

 private:
  UavBodyConfig config_;
  hal::UavState state_;  // the truth
  OdometryFrame frame_;
  bool borrowed_frame_ = false;
  hal::FlightSetpoint setpoint_;
  bool have_setpoint_ = false;
  double travelled_ = 0.0;
  RingBuffer<hal::UavState, 64> in_flight_;  // measured, not yet delivered (the latency)
  RingBuffer<hal::UavState, 8> pending_;
};

}  // namespace colag::sim
