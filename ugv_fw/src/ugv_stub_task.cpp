#include "colag/ugv/ugv_stub_task.hpp"

namespace colag::ugv {

Status UgvStubTask::init(TimePoint) {
  return odometry_.attach(transport_);
}

void UgvStubTask::step(TimePoint now) {
  msg::UgvStatus status;
  status.stamp = now;
  status.ugv_id = id_;
  status.mode = odometry_.has_value() ? msg::UgvMode::kDriving : msg::UgvMode::kWaitingForInit;
  if (transport_.publish(status)) ++sent_;
}

}  // namespace colag::ugv
