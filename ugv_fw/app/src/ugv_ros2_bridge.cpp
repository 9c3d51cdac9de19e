#include "colag/ugv/app/ugv_ros2_bridge.hpp"

#include <algorithm>
#include <cmath>

#include "colag/hal/dds/take_one.hpp"
#include "colag/hal/ros2/pose_writers.hpp"
#include "colag/hal/ros2/ros2_names.hpp"
#include "colag/platform/dds/dds_security.hpp"
#include "ros2_msgs.h"

namespace colag::ugv {

namespace {

using hal::ros2::GridMessage;
using hal::ros2::MarkerArrayMessage;

Duration seconds(double s) {
  return Duration(static_cast<Duration::rep>(std::llround(s * 1e9)));
}

}  // namespace

UgvRos2Bridge::UgvRos2Bridge(UgvNavTask& task) : task_(task) {
  mailbox_.init([](Snapshot& s) { s.cells.assign(kWorldGrid2d.size(), CellState::kUnknown); });
}

UgvRos2Bridge::~UgvRos2Bridge() {
  mailbox_.stop();
}

bool UgvRos2Bridge::start(std::uint32_t domain, const board::Ros2Config& config,
                          const platform::DdsSecurityConfig& security, std::string& error) {
  ns_ = config.ns.empty() ? "ugv" + std::to_string(task_.config().id) : config.ns;
  status_period_ = seconds(config.status_period_s);
  map_period_ = seconds(config.map_period_s);
  odom_ = std::make_unique<hal::ros2::OdometryMessage>(hal::ros2::base_link(ns_));
  platform::dds::ParticipantQos qos;
  if (Status s = qos.init(security); !s) {
    error = std::string("ROS 2 telemetry: ") + s.message();
    return false;
  }
  hal::ros2::PoseWriters pose;
  if (!pose.open(dds_, domain, qos.get(), ns_, error)) return false;
  odom_w_ = pose.odom;
  tf_w_ = pose.tf;
  using hal::ros2::ros2_dds_topic;
  status_w_ = dds_.writer(ros2_dds_topic(ns_, "status"), colag_msgs_msg_dds__UgvStatus__desc,
                          hal::dds::kDefaultQos);
  plan_w_ =
      dds_.writer(ros2_dds_topic(ns_, "plan"), nav_msgs_msg_dds__Path__desc, hal::dds::kDefaultQos);
  prediction_w_ = dds_.writer(ros2_dds_topic(ns_, "prediction"),
                              visualization_msgs_msg_dds__MarkerArray__desc, hal::dds::kDefaultQos);
  map_w_ = dds_.writer(ros2_dds_topic(ns_, "map"), nav_msgs_msg_dds__OccupancyGrid__desc,
                       hal::dds::kLatchedQos);
  if (config.commands) {
    goal_r_ = dds_.reader(ros2_dds_topic(ns_, "goal_pose"),
                          geometry_msgs_msg_dds__PoseStamped__desc, hal::dds::kDefaultQos);
    command_r_ = dds_.reader(ros2_dds_topic(ns_, "command"), colag_msgs_msg_dds__UgvCommand__desc,
                             hal::dds::kDefaultQos);
  }
  if (status_w_ <= 0 || plan_w_ <= 0 || prediction_w_ <= 0 || map_w_ <= 0 ||
      (config.commands && (goal_r_ <= 0 || command_r_ <= 0))) {
    error = "ROS 2 telemetry: " + dds_.last_error();
    return false;
  }
  mailbox_.start([this](const Snapshot& s) { publish(s); }, [this] { take_inputs(); });
  return true;
}

// The task's thread: goals and commands in, a copy of the state out. Nothing here allocates or
// waits.
void UgvRos2Bridge::step(TimePoint now) {
  if (std::unique_lock<std::mutex> lock(input_mutex_, std::try_to_lock); lock.owns_lock()) {
    if (goal_) {
      last_goal_ = task_.request_goal(*goal_);
      if (last_goal_ != GoalResult::kAccepted) goals_refused_.fetch_add(1);
      goal_.reset();
    }
    Command c;
    while (commands_.pop_front(c))
      answer(c, task_.request_command(c.command));
  }
  const bool offered = mailbox_.offer([&](Snapshot& s) {
    s.status = task_.last_status();
    s.detail = now >= next_status_;
    s.map = now >= next_map_;
    if (s.detail) {
      next_status_ = now + status_period_;
      s.trajectory = task_.trajectory();
      s.prediction = task_.prediction();
    }
    if (s.map) {
      next_map_ = now + map_period_;
      const std::span<const CellState> cells = task_.map().cells();
      s.origin = Vec2(task_.map().geometry().origin_x(), task_.map().geometry().origin_y());
      std::copy(cells.begin(), cells.end(), s.cells.begin());
    }
    if (std::unique_lock<std::mutex> g(input_mutex_, std::try_to_lock); g.owns_lock()) {
      s.goals = static_cast<std::uint32_t>(goals_.load());
      s.last_goal = last_goal_;
      s.commands = static_cast<std::uint32_t>(commands_received_.load());
      s.last_id = last_command_.id;
      s.last_command = last_command_.command;
      s.last_command_result = last_command_result_;
    }
  });
  if (!offered) skipped_.fetch_add(1);
}

void UgvRos2Bridge::answer(const Command& c, CommandResult r) {
  last_command_ = c;
  last_command_result_ = r;
  if (r != CommandResult::kAccepted) commands_refused_.fetch_add(1);
}

void UgvRos2Bridge::take_inputs() {
  if (goal_r_ <= 0) return;
  while (hal::dds::take_one<colag_msgs_msg_dds__UgvCommand_>(
      command_r_, [&](const colag_msgs_msg_dds__UgvCommand_& m) {
        const std::lock_guard<std::mutex> lock(input_mutex_);
        commands_received_.fetch_add(1);
        const Command c{m.id, m.command};
        if (!commands_.try_push(c)) answer(c, CommandResult::kBusy);
      })) {
  }
  while (hal::dds::take_one<geometry_msgs_msg_dds__PoseStamped_>(
      goal_r_, [&](const geometry_msgs_msg_dds__PoseStamped_& p) {
        const std::lock_guard<std::mutex> lock(input_mutex_);
        goals_.fetch_add(1);
        const bool in_map = p.header.frame_id != nullptr &&
                            std::string_view(p.header.frame_id) == hal::ros2::kMapFrame;
        if (!in_map) {
          last_goal_ = GoalResult::kWrongFrame;
          goals_refused_.fetch_add(1);
          goal_.reset();
          return;
        }
        goal_ = Vec2(p.pose.position.x, p.pose.position.y);  // the task validates the rest
      })) {
  }
}

void UgvRos2Bridge::publish(const Snapshot& s) {
  if (s.status.stamp == TimePoint{} && s.status.mode == msg::UgvMode::kWaitingForInit)
    return;  // nothing published by the task yet
  std::uint64_t ok = 0, failed = 0;
  auto write = [&](dds_entity_t w, const void* sample) {
    ++(dds_write(w, sample) == DDS_RETCODE_OK ? ok : failed);
  };
  odom_->set(s.status);
  write(odom_w_, &odom_->sample());
  tf_.clear();
  const double yaw = s.status.yaw_rad;
  const double q[4] = {std::cos(yaw / 2), 0.0, 0.0, std::sin(yaw / 2)};
  (void)tf_.add(s.status.stamp, hal::ros2::base_link(ns_), s.status.position_m[0],
                s.status.position_m[1], 0.0, q);
  write(tf_w_, &tf_.sample());
  if (s.detail) {
    status_.set(s.status);
    status_.set_goals(s.goals, static_cast<std::uint8_t>(s.last_goal), to_string(s.last_goal));
    status_.set_commands(s.commands, s.last_id, s.last_command,
                         static_cast<std::uint8_t>(s.last_command_result),
                         to_string(s.last_command_result));
    write(status_w_, &status_.sample());
    plan_.clear(s.status.stamp);
    for (const TrajectorySample& p : s.trajectory.samples())
      if (!plan_.push(p.p.x(), p.p.y(), 0.0, p.yaw_rad)) break;
    write(plan_w_, &plan_.sample());
    hal::ros2::set_prediction(
        prediction_, s.status.stamp, {s.prediction.ellipses.data(), s.prediction.ellipses.size()},
        s.prediction.kind != CollisionKind::kNone ? &s.prediction.point : nullptr);
    write(prediction_w_, &prediction_.sample());
  }
  if (s.map) {
    std::size_t i = 0;
    map_.set_origin(s.origin);
    map_.fill(s.status.stamp, [&](CellIndex) { return hal::ros2::occupancy_value(s.cells[i++]); });
    write(map_w_, &map_.sample());
  }
  published_.fetch_add(ok);
  write_errors_.fetch_add(failed);
}

UgvRos2Counters UgvRos2Bridge::counters() const {
  return {published_.load(),     write_errors_.load(),      skipped_.load(),         goals_.load(),
          goals_refused_.load(), commands_received_.load(), commands_refused_.load()};
}

}  // namespace colag::ugv
