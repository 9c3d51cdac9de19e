#include "colag/uav/uav_stub_task.hpp"

namespace colag::uav {

Status UavStubTask::init(TimePoint) {
  return statuses_.attach(transport_);
}

void UavStubTask::step(TimePoint now) {
  msg::UgvStatus status;
  while (statuses_.pop(status))
    ++statuses_received_;
  msg::UavOdometry odom;
  odom.stamp = now;
  odom.position_m[2] = 1.0;
  (void)transport_.publish(odom);
}

}  // namespace colag::uav
