#pragma once
// Records a simulated mission as MCAP (ROS 2 profile) while it flies: every robot's ROS 2
// telemetry, as the boards publish it, plus the world's ground truth. Topics (frame `map`,
// the fleet's world frame; stamps: each robot's own, log times: simulated time):
//   /ugv<i>/odom (10 Hz), /ugv<i>/status, /ugv<i>/plan, /ugv<i>/prediction (2 Hz), /ugv<i>/map (1
//   Hz) /uav/odom (10 Hz), /uav/status (2 Hz), /uav/map (1 Hz), /uav/support_plan and
//   /uav/support_plan/markers (on every new plan), /tf (10 Hz)
//   /truth/ugv<i>/pose, /truth/uav/pose (10 Hz), /truth/obstacles (1 Hz), /truth/collisions
#include <memory>
#include <string>

#include "colag/sim/mcap/mcap_writer.hpp"
#include "colag/sim/mission/mission.hpp"

namespace colag::mission {

class McapRecorder final : public MissionWatcher {
 public:
  McapRecorder();
  ~McapRecorder();
  McapRecorder(const McapRecorder&) = delete;
  McapRecorder& operator=(const McapRecorder&) = delete;

  // Creates `path`; false with `error` set when it cannot.
  bool open(const std::string& path, std::string& error);
  void watch(const Mission& mission) override;
  // Writes the summary; false with `error` set when the file could not be written in full.
  bool close(std::string& error);

  std::uint64_t messages() const { return writer_.messages(); }
  std::uint64_t bytes() const { return writer_.bytes(); }

 private:
  struct Robots;
  void start(const Mission& m);
  void record_ugv(const Mission& m, std::size_t i, int tick);
  void record_uav(const Mission& m, int tick);
  void record_truth(const Mission& m, int tick);

  mcap::McapWriter writer_;
  std::unique_ptr<Robots> robots_;
  int tick_ = 0;
};

}  // namespace colag::mission
