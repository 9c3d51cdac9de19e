#pragma once
// Placeholder UGV task for the foundation's smoke run: listens to the UAV's odometry and
// publishes its status. The UGV navigation task (its own issue) replaces it.
#include "colag/platform/readers.hpp"

namespace colag::ugv {

class UgvStubTask final : public platform::Task {
 public:
  UgvStubTask(platform::Transport& transport, RobotId id) : transport_(transport), id_(id) {}
  const char* name() const override { return "ugv_stub"; }
  Status init(TimePoint now) override;
  void step(TimePoint now) override;

  std::uint64_t odometry_received() const { return odometry_.updates(); }
  std::uint64_t status_sent() const { return sent_; }

 private:
  platform::Transport& transport_;
  RobotId id_;
  platform::LatestReader<msg::UavOdometry> odometry_;
  std::uint64_t sent_ = 0;
};

}  // namespace colag::ugv
