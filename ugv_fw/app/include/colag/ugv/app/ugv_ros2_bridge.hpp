#pragma once
// A UGV's ROS 2 telemetry and goals (`ros2` in ugv.yaml; README "Watching a mission"): on the
// fleet's DDS domain, under ROS 2 names and types, namespace <ns> (default ugv<id>):
//   <ns>/odom (nav_msgs/Odometry, best effort) and /tf (map -> <ns>/base_link) every step;
//   <ns>/status (colag_msgs/UgvStatus), <ns>/plan (nav_msgs/Path), <ns>/prediction
//   (visualization_msgs/MarkerArray) every status period; <ns>/map (nav_msgs/OccupancyGrid,
//   transient local) every map period. In: <ns>/goal_pose (geometry_msgs/PoseStamped, frame
//   `map`, as RViz2's "2D Goal Pose" sends it), validated by the task; <ns>/command
//   (colag_msgs/UgvCommand: pause, resume, abort, return to start), in the order sent. The
//   answers (and the last command's id) are in the status.
//
// Two halves: step() runs in the UGV's executor table on the task's thread (it copies the task's
// state into a mailbox and hands it the goals waiting; no allocation, never blocks: a busy
// mailbox skips the period); a thread of its own turns the copy into ROS 2 messages and writes
// them (Cyclone allocates there, not on the task's thread), and takes the goals and commands.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "colag/board/config.hpp"
#include "colag/board/snapshot_mailbox.hpp"
#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/hal/dds/device_participant.hpp"
#include "colag/hal/ros2/ros2_messages.hpp"
#include "colag/platform/task.hpp"
#include "colag/ugv/ugv_nav_task.hpp"

namespace colag::ugv {

struct UgvRos2Counters {
  std::uint64_t published = 0;
  std::uint64_t write_errors = 0;
  std::uint64_t skipped = 0;  // periods the mailbox was busy
  std::uint64_t goals = 0;    // goals received
  std::uint64_t goals_refused = 0;
  std::uint64_t commands = 0;  // commands received
  std::uint64_t commands_refused = 0;
};

class UgvRos2Bridge final : public platform::Task {
 public:
  explicit UgvRos2Bridge(UgvNavTask& task);
  ~UgvRos2Bridge() override;
  UgvRos2Bridge(const UgvRos2Bridge&) = delete;
  UgvRos2Bridge& operator=(const UgvRos2Bridge&) = delete;

  // The writers and the readers on `domain` (secured as the robot's own participant when
  // `security` is on), and the thread. False with `error` set.
  bool start(std::uint32_t domain, const board::Ros2Config& config,
             const platform::DdsSecurityConfig& security, std::string& error);
  const char* name() const override { return "ugv_ros2"; }
  void step(TimePoint now) override;
  UgvRos2Counters counters() const;

 private:
  struct Snapshot {
    msg::UgvStatus status;
    bool detail = false;  // status, plan and prediction due
    bool map = false;     // the grid due
    Trajectory trajectory;
    Prediction prediction;
    std::vector<CellState> cells;  // the map store's cells (MapStore::cells)
    Vec2 origin = Vec2::Zero();    // of its window
    std::uint32_t goals = 0;       // goals taken so far, and the answer to the last
    GoalResult last_goal = GoalResult::kAccepted;
    std::uint32_t commands = 0;  // commands taken so far, and the last one with its answer
    std::uint32_t last_id = 0;
    std::uint8_t last_command = 0;
    CommandResult last_command_result = CommandResult::kAccepted;
  };
  struct Command {
    std::uint32_t id = 0;
    std::uint8_t command = 0;
  };
  void publish(const Snapshot& s);
  void take_inputs();
  void answer(const Command& c, CommandResult r);  // under input_mutex_

  UgvNavTask& task_;
  std::string ns_;
  Duration status_period_{}, map_period_{};
  TimePoint next_status_{}, next_map_{};

  // Goals and commands: the thread puts, step() takes (validated by the task).
  std::mutex input_mutex_;
  std::optional<Vec2> goal_;
  GoalResult last_goal_ = GoalResult::kAccepted;
  RingBuffer<Command, limits::kRos2CommandQueue> commands_;
  Command last_command_;
  CommandResult last_command_result_ = CommandResult::kAccepted;

  // The thread's own: the DDS entities and the messages (filled from a copy of the mailbox).
  hal::dds::DeviceParticipant dds_;
  dds_entity_t odom_w_ = 0, tf_w_ = 0, status_w_ = 0, plan_w_ = 0, prediction_w_ = 0, map_w_ = 0,
               goal_r_ = 0, command_r_ = 0;
  std::unique_ptr<hal::ros2::OdometryMessage> odom_;
  hal::ros2::TfMessage tf_{1};
  hal::ros2::UgvStatusMessage status_;
  hal::ros2::PathMessage plan_{limits::kMaxTrajectorySamples};
  hal::ros2::MarkerArrayMessage prediction_{limits::kMaxPredictionSteps + 2, 0};
  hal::ros2::GridMessage map_{kWorldGrid2d};
  board::SnapshotMailbox<Snapshot> mailbox_;  // last: its thread stops before the rest goes
  std::atomic<std::uint64_t> published_{0}, write_errors_{0}, skipped_{0}, goals_{0},
      goals_refused_{0}, commands_received_{0}, commands_refused_{0};
};

}  // namespace colag::ugv
