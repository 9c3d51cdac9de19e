#include "colag/uav/app/uav_ros2_bridge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "colag/hal/ros2/pose_writers.hpp"
#include "colag/hal/ros2/ros2_names.hpp"
#include "colag/platform/dds/dds_security.hpp"
#include "ros2_msgs.h"

namespace colag::uav {

namespace {

using hal::ros2::GridMessage;
using hal::ros2::MarkerArrayMessage;

}  // namespace

UavRos2Bridge::UavRos2Bridge(const UavSupervisorTask& task)
    : task_(task), sweep_(kWorldGrid3d.layer().size(), CellState::kUnknown) {
  mailbox_.init(
      [](Snapshot& s) { s.cells.assign(kWorldGrid3d.layer().size(), CellState::kUnknown); });
}

UavRos2Bridge::~UavRos2Bridge() {
  mailbox_.stop();
}

bool UavRos2Bridge::start(std::uint32_t domain, const board::Ros2Config& config,
                          Duration step_period, const platform::DdsSecurityConfig& security,
                          std::string& error) {
  ns_ = config.ns.empty() ? "uav" : config.ns;
  status_period_ = Duration(static_cast<Duration::rep>(std::llround(config.status_period_s * 1e9)));
  // A full sweep of the map view every map period, but never more than kMaxRowsPerStep rows a
  // step (each cell reads its column of the 3-D map: 40 rows took 7 ms on the host, too long on
  // the task's thread); a sweep then takes longer than the period.
  constexpr int kMaxRowsPerStep = 12;
  const double steps = std::max(1.0, config.map_period_s / to_seconds(step_period));
  rows_per_step_ = std::clamp(static_cast<int>(std::ceil(kWorldGrid3d.layer().cells_y() / steps)),
                              1, kMaxRowsPerStep);
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
  status_w_ = dds_.writer(ros2_dds_topic(ns_, "status"), colag_msgs_msg_dds__UavStatus__desc,
                          hal::dds::kDefaultQos);
  plan_w_ = dds_.writer(ros2_dds_topic(ns_, "support_plan"), nav_msgs_msg_dds__Path__desc,
                        hal::dds::kLatchedQos);
  markers_w_ = dds_.writer(ros2_dds_topic(ns_, "support_plan/markers"),
                           visualization_msgs_msg_dds__MarkerArray__desc, hal::dds::kLatchedQos);
  map_w_ = dds_.writer(ros2_dds_topic(ns_, "map"), nav_msgs_msg_dds__OccupancyGrid__desc,
                       hal::dds::kLatchedQos);
  if (status_w_ <= 0 || plan_w_ <= 0 || markers_w_ <= 0 || map_w_ <= 0) {
    error = "ROS 2 telemetry: " + dds_.last_error();
    return false;
  }
  mailbox_.start([this](const Snapshot& s) { publish(s); }, nullptr);
  return true;
}

void UavRos2Bridge::step(TimePoint now) {
  // A slice of the map view's rows (the classification reads the 3-D map: too long for one step).
  const GridGeometry2d g = task_.mapper().geometry().layer();
  if (const Vec2 o(g.origin_x(), g.origin_y()); o != sweep_origin_) {
    sweep_origin_ = o;  // the window moved: rows swept so far show another place
    sweep_row_ = 0;
  }
  for (int k = 0; k < rows_per_step_ && sweep_row_ < g.cells_y(); ++k, ++sweep_row_)
    for (int x = 0; x < g.cells_x(); ++x)
      sweep_[g.index({x, sweep_row_})] = task_.sharer().classify(task_.mapper(), x, sweep_row_);
  const bool sweep_done = sweep_row_ == g.cells_y();
  const msg::SupportPlan& plan = task_.plan();
  const bool offered = mailbox_.offer([&](Snapshot& s) {
    s.odometry = task_.last_odometry();
    s.status = now >= next_status_;
    if (s.status) {
      next_status_ = now + status_period_;
      s.flight_lost = task_.health().flight_lost;
    }
    s.new_plan = !plan_sent_ || plan.seq != plan_seq_;
    if (s.new_plan) s.plan = plan;
    s.map = sweep_done;
    if (s.map) {
      std::copy(sweep_.begin(), sweep_.end(), s.cells.begin());
      s.origin = sweep_origin_;
    }
  });
  if (!offered) {
    skipped_.fetch_add(1);
    return;
  }
  plan_sent_ = true;
  plan_seq_ = plan.seq;
  if (sweep_done) sweep_row_ = 0;
}

void UavRos2Bridge::publish(const Snapshot& s) {
  std::uint64_t ok = 0, failed = 0;
  auto write = [&](dds_entity_t w, const void* sample) {
    ++(dds_write(w, sample) == DDS_RETCODE_OK ? ok : failed);
  };
  const msg::UavOdometry& o = s.odometry;
  if (o.stamp != TimePoint{}) {
    odom_->set(o);
    write(odom_w_, &odom_->sample());
    tf_.clear();
    (void)tf_.add(o.stamp, hal::ros2::base_link(ns_), o.position_m[0], o.position_m[1],
                  o.position_m[2], o.orientation_wxyz);
    write(tf_w_, &tf_.sample());
  }
  if (s.status) {
    status_.set(o, s.plan, static_cast<std::uint32_t>(s.flight_lost));
    write(status_w_, &status_.sample());
  }
  if (s.new_plan) {
    hal::ros2::set_support_plan(s.plan, plan_, markers_);
    write(plan_w_, &plan_.sample());
    write(markers_w_, &markers_.sample());
  }
  if (s.map) {
    std::size_t i = 0;
    map_.set_origin(s.origin);
    map_.fill(o.stamp, [&](CellIndex) { return hal::ros2::occupancy_value(s.cells[i++]); });
    write(map_w_, &map_.sample());
  }
  published_.fetch_add(ok);
  write_errors_.fetch_add(failed);
}

UavRos2Counters UavRos2Bridge::counters() const {
  return {published_.load(), write_errors_.load(), skipped_.load()};
}

}  // namespace colag::uav
