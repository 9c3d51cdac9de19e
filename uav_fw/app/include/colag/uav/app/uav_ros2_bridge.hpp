#pragma once
// The UAV's ROS 2 telemetry (`ros2` in uav.yaml; README "Watching a mission"), namespace <ns>
// (default uav): <ns>/odom and /tf (map -> <ns>/base_link) every step; <ns>/status
// (colag_msgs/UavStatus) every status period; <ns>/support_plan (nav_msgs/Path of the support
// points in visit order) and <ns>/support_plan/markers (each stop's UGV, ETA and deadline) on
// every new plan; <ns>/map (nav_msgs/OccupancyGrid, the 2-D view it shares with the UGVs,
// transient local) every map period. The same two halves as the UGV's bridge: step() on the
// task's thread copies (the map view a slice of rows per step), a thread of its own writes.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "colag/board/config.hpp"
#include "colag/board/snapshot_mailbox.hpp"
#include "colag/hal/dds/device_participant.hpp"
#include "colag/hal/ros2/ros2_messages.hpp"
#include "colag/platform/task.hpp"
#include "colag/uav/uav_supervisor_task.hpp"

namespace colag::uav {

struct UavRos2Counters {
  std::uint64_t published = 0;
  std::uint64_t write_errors = 0;
  std::uint64_t skipped = 0;  // periods the mailbox was busy
};

class UavRos2Bridge final : public platform::Task {
 public:
  explicit UavRos2Bridge(const UavSupervisorTask& task);
  ~UavRos2Bridge() override;
  UavRos2Bridge(const UavRos2Bridge&) = delete;
  UavRos2Bridge& operator=(const UavRos2Bridge&) = delete;

  // The writers on `domain` (secured as the robot's own participant when `security` is on), and
  // the thread. False with `error` set.
  bool start(std::uint32_t domain, const board::Ros2Config& config, Duration step_period,
             const platform::DdsSecurityConfig& security, std::string& error);
  const char* name() const override { return "uav_ros2"; }
  void step(TimePoint now) override;
  UavRos2Counters counters() const;

 private:
  struct Snapshot {
    msg::UavOdometry odometry;
    msg::SupportPlan plan;
    std::uint64_t flight_lost = 0;
    bool status = false, new_plan = false, map = false;
    std::vector<CellState> cells;  // the 2-D view, a full sweep
    Vec2 origin = Vec2::Zero();    // of the map's window during the sweep
  };
  void publish(const Snapshot& s);

  const UavSupervisorTask& task_;
  std::string ns_;
  Duration status_period_{};
  TimePoint next_status_{};
  // The map view, swept a slice of rows per step on the task's thread.
  std::vector<CellState> sweep_;
  int sweep_row_ = 0, rows_per_step_ = 1;
  Vec2 sweep_origin_ = Vec2::Zero();  // the map's window the sweep reads (it restarts if it moves)
  std::uint32_t plan_seq_ = 0;
  bool plan_sent_ = false;

  hal::dds::DeviceParticipant dds_;
  dds_entity_t odom_w_ = 0, tf_w_ = 0, status_w_ = 0, plan_w_ = 0, markers_w_ = 0, map_w_ = 0;
  std::unique_ptr<hal::ros2::OdometryMessage> odom_;
  hal::ros2::TfMessage tf_{1};
  hal::ros2::UavStatusMessage status_;
  hal::ros2::PathMessage plan_{limits::kMaxSupportRequests};
  hal::ros2::MarkerArrayMessage markers_{2 * limits::kMaxSupportRequests + 1, 0};
  hal::ros2::GridMessage map_{kWorldGrid3d.layer()};
  board::SnapshotMailbox<Snapshot> mailbox_;  // last: its thread stops before the rest goes
  std::atomic<std::uint64_t> published_{0}, write_errors_{0}, skipped_{0};
};

}  // namespace colag::uav
