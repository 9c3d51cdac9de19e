#include "colag/hal/sim/sim_link.hpp"

#include "sim.h"

namespace colag::hal::sim {

namespace {

struct TopicInfo {
  const char* name;
  const dds_topic_descriptor_t* descriptor;
  bool reliable;
  std::int32_t depth;
};
// CAN frames: reliable and deep (a bus loses nothing); the UAV's state and setpoints: the newest
// few; a LiDAR scan (~0.2 MB): only the newest.
const TopicInfo kTopics[kSimTopicCount] = {
    {"colag_sim_can_to_robot", &colag_sim_CanFrame_desc, true, 64},
    {"colag_sim_can_from_robot", &colag_sim_CanFrame_desc, true, 64},
    {"colag_sim_uav_state", &colag_sim_UavState_desc, true, 8},
    {"colag_sim_setpoint", &colag_sim_FlightSetpoint_desc, true, 8},
    {"colag_sim_lidar", &colag_sim_LidarScan_desc, true, 1},
    {"colag_sim_rpe", &colag_sim_RpeFrame_desc, true, 4},
};

}  // namespace

SimLink::~SimLink() {
  if (participant_ > 0) dds_delete(participant_);
}

Status SimLink::fail(dds_return_t rc, const char* what) {
  last_error_ = rc;
  return {Errc::kUnavailable, what};
}

Status SimLink::endpoints(SimTopic t, bool write, bool read) {
  const std::size_t i = static_cast<std::size_t>(t);
  const TopicInfo& info = kTopics[i];
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, info.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_MSECS(100));
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, info.depth);
  topics_[i] = dds_create_topic(participant_, info.descriptor, info.name, qos, nullptr);
  Status s = Status::ok();
  if (topics_[i] < 0) {
    s = fail(topics_[i], "sim link: dds_create_topic failed");
  } else {
    if (write) writers_[i] = dds_create_writer(participant_, topics_[i], qos, nullptr);
    if (read) readers_[i] = dds_create_reader(participant_, topics_[i], qos, nullptr);
    if (writers_[i] < 0) s = fail(writers_[i], "sim link: dds_create_writer failed");
    if (readers_[i] < 0) s = fail(readers_[i], "sim link: dds_create_reader failed");
  }
  dds_delete_qos(qos);
  return s;
}

Status SimLink::init(std::uint32_t sim_domain, Side side, RobotId robot) {
  if (participant_ > 0) return {Errc::kInvalidArgument, "sim link initialised twice"};
  participant_ = dds_create_participant(sim_domain, nullptr, nullptr);
  if (participant_ < 0) return fail(participant_, "sim link: dds_create_participant failed");
  const bool world = side == Side::kWorld, uav = side == Side::kUav, ugv = side == Side::kUgv;
  Status s = Status::ok();
  if (world || ugv) {
    s = endpoints(SimTopic::kCanToRobot, world, ugv);
    if (s) s = endpoints(SimTopic::kCanFromRobot, ugv, world);
    robot_ = robot;
    if (s && ugv) {
      // Only this UGV's frames reach its reader's history: the others would crowd them out.
      dds_set_topic_filter_and_arg(
          topics_[static_cast<std::size_t>(SimTopic::kCanToRobot)],
          [](const void* sample, void* arg) {
            return static_cast<const colag_sim_CanFrame*>(sample)->robot_id ==
                   *static_cast<const RobotId*>(arg);
          },
          &robot_);
    }
  }
  if (s && (world || uav)) {
    // The world writes what the UAV reads, and reads its setpoints.
    s = endpoints(SimTopic::kUavState, world, uav);
    if (s) s = endpoints(SimTopic::kSetpoint, uav, world);
    if (s) s = endpoints(SimTopic::kLidar, world, uav);
    if (s) s = endpoints(SimTopic::kRpe, world, uav);
  }
  return s;
}

}  // namespace colag::hal::sim
