#pragma once
// Placeholder UAV task for the foundation's smoke run: publishes odometry and counts the UGV
// statuses it hears. The UAV supervisor task (its own issue) replaces it.
#include "colag/platform/readers.hpp"

namespace colag::uav {

class UavStubTask final : public platform::Task {
 public:
  explicit UavStubTask(platform::Transport& transport) : transport_(transport) {}
  const char* name() const override { return "uav_stub"; }
  Status init(TimePoint now) override;
  void step(TimePoint now) override;

  std::uint64_t statuses_received() const { return statuses_received_; }

 private:
  platform::Transport& transport_;
  platform::QueueReader<msg::UgvStatus, 16> statuses_;
  std::uint64_t statuses_received_ = 0;
};

}  // namespace colag::uav
