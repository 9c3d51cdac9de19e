#include "colag/sim/recording/mcap_recorder.hpp"

#include <cstdio>
#include <map>
#include <vector>

#include "colag/hal/ros2/cdr.hpp"
#include "colag/hal/ros2/ros2_messages.hpp"
#include "colag/hal/ros2/ros2_schemas.hpp"

namespace colag::mission {

namespace {

using namespace colag::hal::ros2;  // NOLINT(google-build-using-namespace): the message builders

constexpr int kTicksPerStatus = 5;  // 2 Hz at the mission's 100 ms watch
constexpr int kTicksPerMap = 10;    // 1 Hz

struct Channel {
  std::uint16_t id = 0;
  const dds_topic_descriptor_t* type = nullptr;
};

void yaw_quaternion(double yaw, double (&q)[4]) {
  q[0] = std::cos(yaw / 2.0);
  q[1] = q[2] = 0.0;
  q[3] = std::sin(yaw / 2.0);
}

}  // namespace

struct McapRecorder::Robots {
  struct Ugv {
    explicit Ugv(std::string name)
        : ns(std::move(name)),
          odom_msg(base_link(ns)),
          plan_msg(limits::kMaxTrajectorySamples),
          prediction_msg(limits::kMaxPredictionSteps + 2, 0),
          map_msg(kWorldGrid2d) {}
    std::string ns;
    Channel odom, status, plan, prediction, map, truth;
    OdometryMessage odom_msg;
    UgvStatusMessage status_msg;
    PathMessage plan_msg;
    MarkerArrayMessage prediction_msg;
    GridMessage map_msg;
  };
  struct Uav {
    Uav() : odom_msg(base_link("uav")), map_msg(kWorldGrid3d.layer()) {}
    Channel odom, status, map, plan, markers, truth;
    OdometryMessage odom_msg;
    UavStatusMessage status_msg;
    GridMessage map_msg;
    PathMessage plan_msg{limits::kMaxSupportRequests};
    MarkerArrayMessage plan_markers{2 * limits::kMaxSupportRequests + 1, 0};
    std::uint32_t plan_seq = 0;
    bool plan_seen = false;
  };

  explicit Robots(mcap::McapWriter& w) : writer(w) {}

  Channel channel(const std::string& topic, const char* type, const dds_topic_descriptor_t& d) {
    auto s = schemas.find(type);
    if (s == schemas.end())
      s = schemas.emplace(type, writer.add_schema(type, "ros2msg", ros2msg_schema(type))).first;
    return {writer.add_channel(s->second, topic, "cdr"), &d};
  }
  void put(const Channel& c, const void* sample, TimePoint stamp) {
    if (!to_cdr(sample, *c.type, cdr)) {
      ++refused;
      return;
    }
    const auto ns = [](TimePoint t) {
      return static_cast<std::uint64_t>(std::max<std::int64_t>(0, t.time_since_epoch().count()));
    };
    (void)writer.write(c.id, ns(now), ns(stamp), cdr);
  }

  mcap::McapWriter& writer;
  std::map<std::string, std::uint16_t> schemas;
  std::vector<std::uint8_t> cdr;
  std::uint64_t refused = 0;  // samples Cyclone's serializer refused (a bug if ever > 0)
  TimePoint now{};
  std::vector<std::unique_ptr<Ugv>> ugvs;
  std::unique_ptr<Uav> uav;
  Channel tf, obstacles, collisions;
  TfMessage tf_msg{limits::kMaxUgvs + 1};
  std::unique_ptr<MarkerArrayMessage> obstacle_msg;  // one marker per box
  MarkerArrayMessage collision_msg{64, 0};
  std::size_t collisions_seen = 0;
  std::vector<std::unique_ptr<geometry_msgs_msg_dds__PoseStamped_>> truth_poses;
  Name map_frame{};
};

McapRecorder::McapRecorder() = default;
McapRecorder::~McapRecorder() = default;

bool McapRecorder::open(const std::string& path, std::string& error) {
  if (!writer_.open(path)) {
    error = writer_.error();
    return false;
  }
  robots_ = std::make_unique<Robots>(writer_);
  return true;
}

bool McapRecorder::close(std::string& error) {
  if (!writer_.close()) {
    error = writer_.error();
    return false;
  }
  if (robots_ && robots_->refused > 0) {
    error = std::to_string(robots_->refused) + " samples could not be serialised";
    return false;
  }
  return true;
}

void McapRecorder::start(const Mission& m) {
  Robots& r = *robots_;
  set_name(r.map_frame, kMapFrame);
  for (std::size_t i = 0; i < m.ugv_count(); ++i) {
    auto u = std::make_unique<Robots::Ugv>("ugv" + std::to_string(m.ugv(i).config().id));
    const std::string t = "/" + u->ns;
    u->odom = r.channel(t + "/odom", "nav_msgs/msg/Odometry", nav_msgs_msg_dds__Odometry__desc);
    u->status =
        r.channel(t + "/status", "colag_msgs/msg/UgvStatus", colag_msgs_msg_dds__UgvStatus__desc);
    u->plan = r.channel(t + "/plan", "nav_msgs/msg/Path", nav_msgs_msg_dds__Path__desc);
    u->prediction = r.channel(t + "/prediction", "visualization_msgs/msg/MarkerArray",
                              visualization_msgs_msg_dds__MarkerArray__desc);
    u->map =
        r.channel(t + "/map", "nav_msgs/msg/OccupancyGrid", nav_msgs_msg_dds__OccupancyGrid__desc);
    u->truth = r.channel("/truth" + t + "/pose", "geometry_msgs/msg/PoseStamped",
                         geometry_msgs_msg_dds__PoseStamped__desc);
    r.ugvs.push_back(std::move(u));
  }
  if (m.uav() != nullptr) {
    r.uav = std::make_unique<Robots::Uav>();
    Robots::Uav& a = *r.uav;
    a.odom = r.channel("/uav/odom", "nav_msgs/msg/Odometry", nav_msgs_msg_dds__Odometry__desc);
    a.status =
        r.channel("/uav/status", "colag_msgs/msg/UavStatus", colag_msgs_msg_dds__UavStatus__desc);
    a.map =
        r.channel("/uav/map", "nav_msgs/msg/OccupancyGrid", nav_msgs_msg_dds__OccupancyGrid__desc);
    a.plan = r.channel("/uav/support_plan", "nav_msgs/msg/Path", nav_msgs_msg_dds__Path__desc);
    a.markers = r.channel("/uav/support_plan/markers", "visualization_msgs/msg/MarkerArray",
                          visualization_msgs_msg_dds__MarkerArray__desc);
    a.truth = r.channel("/truth/uav/pose", "geometry_msgs/msg/PoseStamped",
                        geometry_msgs_msg_dds__PoseStamped__desc);
  }
  r.tf = r.channel("/tf", "tf2_msgs/msg/TFMessage", tf2_msgs_msg_dds__TFMessage__desc);
  r.obstacles = r.channel("/truth/obstacles", "visualization_msgs/msg/MarkerArray",
                          visualization_msgs_msg_dds__MarkerArray__desc);
  r.collisions = r.channel("/truth/collisions", "visualization_msgs/msg/MarkerArray",
                           visualization_msgs_msg_dds__MarkerArray__desc);
  r.obstacle_msg = std::make_unique<MarkerArrayMessage>(m.world().world().boxes.size(), 0);
}

void McapRecorder::watch(const Mission& m) {
  if (!robots_ || !writer_.is_open()) return;
  if (tick_ == 0) start(m);
  robots_->now = m.now();
  robots_->tf_msg.clear();
  for (std::size_t i = 0; i < m.ugv_count(); ++i)
    record_ugv(m, i, tick_);
  record_uav(m, tick_);
  if (robots_->tf_msg.sample().transforms._length > 0)
    robots_->put(robots_->tf, &robots_->tf_msg.sample(), m.now());
  record_truth(m, tick_);
  ++tick_;
}

void McapRecorder::record_ugv(const Mission& m, std::size_t i, int tick) {
  Robots& r = *robots_;
  Robots::Ugv& u = *r.ugvs[i];
  const ugv::UgvNavTask& task = m.ugv(i);
  const msg::UgvStatus& s = task.last_status();
  if (s.stamp == TimePoint{} && s.mode == msg::UgvMode::kWaitingForInit) return;  // not yet
  u.odom_msg.set(s);
  r.put(u.odom, &u.odom_msg.sample(), s.stamp);
  double q[4];
  yaw_quaternion(s.yaw_rad, q);
  (void)r.tf_msg.add(s.stamp, base_link(u.ns), s.position_m[0], s.position_m[1], 0.0, q);
  if (tick % kTicksPerStatus == 0) {
    u.status_msg.set(s);
    r.put(u.status, &u.status_msg.sample(), s.stamp);
    u.plan_msg.clear(s.stamp);
    for (const ugv::TrajectorySample& p : task.trajectory().samples())
      if (!u.plan_msg.push(p.p.x(), p.p.y(), 0.0, p.yaw_rad)) break;
    r.put(u.plan, &u.plan_msg.sample(), s.stamp);
    const ugv::Prediction& pr = task.prediction();
    set_prediction(u.prediction_msg, s.stamp, {pr.ellipses.data(), pr.ellipses.size()},
                   pr.kind != ugv::CollisionKind::kNone ? &pr.point : nullptr);
    r.put(u.prediction, &u.prediction_msg.sample(), s.stamp);
  }
  if (tick % kTicksPerMap == 0) {
    const MapStore& map = task.map();
    u.map_msg.set_origin(Vec2(map.geometry().origin_x(), map.geometry().origin_y()));
    u.map_msg.fill(m.now(), [&](CellIndex c) { return occupancy_value(map.state(c)); });
    r.put(u.map, &u.map_msg.sample(), m.now());
  }
}

void McapRecorder::record_uav(const Mission& m, int tick) {
  Robots& r = *robots_;
  if (!r.uav || m.uav() == nullptr) return;
  Robots::Uav& a = *r.uav;
  const uav::UavSupervisorTask& task = *m.uav();
  const msg::UavOdometry& o = task.last_odometry();
  if (o.stamp != TimePoint{}) {
    a.odom_msg.set(o);
    r.put(a.odom, &a.odom_msg.sample(), o.stamp);
    (void)r.tf_msg.add(o.stamp, base_link("uav"), o.position_m[0], o.position_m[1], o.position_m[2],
                       o.orientation_wxyz);
  }
  const msg::SupportPlan& plan = task.plan();
  if (tick % kTicksPerStatus == 0) {
    a.status_msg.set(o, plan, static_cast<std::uint32_t>(task.health().flight_lost));
    r.put(a.status, &a.status_msg.sample(), m.now());
  }
  if (tick % kTicksPerMap == 0) {
    const GridGeometry3d& g = task.mapper().geometry();
    a.map_msg.set_origin(Vec2(g.origin_x(), g.origin_y()));
    a.map_msg.fill(m.now(), [&](CellIndex c) {
      return occupancy_value(task.sharer().classify(task.mapper(), c.x, c.y));
    });
    r.put(a.map, &a.map_msg.sample(), m.now());
  }
  if (!a.plan_seen || plan.seq != a.plan_seq) {
    a.plan_seen = true;
    a.plan_seq = plan.seq;
    set_support_plan(plan, a.plan_msg, a.plan_markers);
    r.put(a.plan, &a.plan_msg.sample(), plan.stamp);
    r.put(a.markers, &a.plan_markers.sample(), plan.stamp);
  }
}

void McapRecorder::record_truth(const Mission& m, int tick) {
  Robots& r = *robots_;
  const sim::SimWorld& w = m.world();
  const sim::OdometryFrame& frame = w.odometry_frame();
  geometry_msgs_msg_dds__PoseStamped_ p{};
  p.header.frame_id = r.map_frame.data();
  set_time(p.header.stamp, m.now());
  for (std::size_t i = 0; i < r.ugvs.size(); ++i) {
    const Pose2 t = frame.to_odometry(w.ugv(static_cast<int>(i)).pose());
    set_pose(p.pose, t.p.x(), t.p.y(), 0.0, t.yaw_rad);
    r.put(r.ugvs[i]->truth, &p, m.now());
  }
  if (r.uav && w.uav_body() != nullptr) {
    const hal::UavState& s = w.uav_body()->state();
    const Vec3 at = frame.to_odometry(s.pose.p);
    set_pose(p.pose, at.x(), at.y(), at.z(), 0.0);
    r.put(r.uav->truth, &p, m.now());
  }
  if (tick % kTicksPerMap == 0) {
    r.obstacle_msg->clear(m.now());
    std::int32_t id = 0;
    for (const sim::Box& b : w.world().boxes) {
      const Vec2 c = frame.to_odometry(b.center);
      const double at[4] = {c.x(), c.y(), (b.base_m + b.height_m) / 2.0, 0.0};
      const double scale[3] = {2.0 * b.half_size.x(), 2.0 * b.half_size.y(), b.height_m - b.base_m};
      (void)r.obstacle_msg->add("boxes", id++, MarkerArrayMessage::kCube, {0.5F, 0.5F, 0.5F, 1.0F},
                                at, scale);
    }
    r.put(r.obstacles, &r.obstacle_msg->sample(), m.now());
  }
  const auto& hits = w.collisions();
  if (hits.size() != r.collisions_seen) {
    r.collisions_seen = hits.size();
    r.collision_msg.clear(m.now());
    std::int32_t id = 0;
    for (const sim::CollisionEvent& e : hits) {
      const Vec2 c = frame.to_odometry(e.where);
      const double at[4] = {c.x(), c.y(), 0.3, 0.0}, scale[3] = {0.6, 0.6, 0.6};
      if (r.collision_msg.add("collisions", id++, MarkerArrayMessage::kSphere,
                              {1.0F, 0.0F, 0.0F, 0.8F}, at, scale) == nullptr)
        break;
    }
    r.put(r.collisions, &r.collision_msg.sample(), m.now());
  }
}

}  // namespace colag::mission
