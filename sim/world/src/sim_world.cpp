#include "colag/sim/world/sim_world.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "colag/common/ring_buffer.hpp"

namespace colag::sim {

// A LiDAR device: the latest scan of a LidarSimulator, handed out once.
class SimWorld::ScanDevice final : public hal::Lidar {
 public:
  ScanDevice(const LidarPattern& pattern, ForkJoin* fork_join, const LidarErrors& errors,
             std::uint64_t seed)
      : sim_(pattern, fork_join), fork_join_(fork_join), errors_(errors), seed_(seed) {
    if (errors_.any()) noisy_.resize(limits::kMaxLidarPoints);
  }
  void scan(const BoxWorld& world, const Pose3& pose, TimePoint now) {
    sim_.scan(world, pose, points_, misses_);
    if (errors_.any()) add_errors();
    stamp_ = now;
    fresh_ = true;
  }
  bool poll(hal::LidarScanView& out) override {
    if (!fresh_) return false;
    fresh_ = false;
    out = {stamp_, static_cast<float>(sim_.pattern().max_range_m), points_, misses_};
    return true;
  }

 private:
  // Each return off along its ray; some lost (lidar_errors.hpp).
  void add_errors() {
    const std::size_t n = add_lidar_errors(errors_, seed_, ++scans_, points_, noisy_, fork_join_);
    points_ = std::span<const hal::LidarPoint>(noisy_.data(), n);
    if (errors_.returns_only) misses_ = {};
  }

  LidarSimulator sim_;
  ForkJoin* fork_join_;
  LidarErrors errors_;
  std::uint64_t seed_, scans_ = 0;
  std::vector<hal::LidarPoint> noisy_;
  std::span<const hal::LidarPoint> points_, misses_;
  TimePoint stamp_{};
  bool fresh_ = false;
};

// The UAV's relative-pose camera: the newest frame of detections, handed out once.
// Frames wait `latency` (+ jitter) between capture and delivery; a newer frame delivered
// replaces one not yet taken.
class SimWorld::Camera final : public hal::RelativePoseSensor {
 public:
  using Frame = StaticVector<hal::RelativePoseDetection, limits::kMaxRpeDetectionsPerFrame>;
  std::size_t poll(std::span<hal::RelativePoseDetection> out) override {
    if (!fresh_) return 0;
    fresh_ = false;
    const std::size_t n = std::min(out.size(), delivered_.size());
    std::copy_n(delivered_.begin(), n, out.begin());
    return n;
  }
  // The frame just captured (in `frame`) leaves the camera at `release` (world time).
  void capture(TimePoint release) {
    Pending p{release, frame};
    if (pending_.full()) pending_.pop_front();  // a camera that far behind drops frames
    (void)pending_.try_push(p);
  }
  void deliver(TimePoint now) {
    while (!pending_.empty() && pending_.front().release <= now) {
      delivered_ = pending_.front().frame;
      pending_.pop_front();
      fresh_ = true;
    }
  }
  Frame frame;

 private:
  struct Pending {
    TimePoint release;
    Frame frame;
  };
  RingBuffer<Pending, 16> pending_;
  Frame delivered_;
  bool fresh_ = false;
};

struct SimWorld::Ugv {
  Ugv(const UgvBodyConfig& c, const Pose2& start, std::uint64_t seed, const hal::Clock& world,
      const ClockModel& model)
      : body(c, start, seed), clock(world, model), link(clock) {}
  UgvBody body;
  RobotClock clock;  // the UGV's: its CAN bus, motor controller and firmware run on it
  hal::sim::SimCanLink link;
  std::unique_ptr<ScanDevice> lidar;
  double min_clearance = std::numeric_limits<double>::infinity();
  bool collided = false;
};

struct SimWorld::Uav {
  Uav(const UavBodyConfig& c, const Vec3& start, const ClockModel& model)
      : body(c, start), clock(model) {}
  UavBody body;
  ClockModel clock;  // what its devices stamp with
  std::unique_ptr<ScanDevice> lidar;
  Camera camera;
  bool silent = false;
};

SimWorld::SimWorld(const SimWorldConfig& config, BoxWorld world, const hal::Clock& clock,
                   ForkJoin* fork_join)
    : config_(config),
      world_(std::move(world)),
      scene_(world_),
      clock_(clock),
      fork_join_(fork_join),
      rng_(config.seed) {
  collisions_.reserve(64);
}

SimWorld::~SimWorld() = default;

int SimWorld::add_ugv(const Pose2& start, const ClockModel& clock, const WheelErrors* wheels) {
  const auto seed = config_.seed * 1000003ULL + ugvs_.size() + 1;
  UgvBodyConfig body = config_.ugv;
  if (wheels != nullptr) body.wheel_errors = *wheels;
  ugvs_.push_back(std::make_unique<Ugv>(body, start, seed, clock_, clock));
  scene_.boxes.emplace_back();  // its body, placed by update_scene
  update_scene();
  return static_cast<int>(ugvs_.size()) - 1;
}

int SimWorld::add_uav(const Vec3& start, const ClockModel& clock) {
  const std::uint64_t k = uavs_.size();
  uavs_.push_back(std::make_unique<Uav>(config_.uav, start, clock));
  uavs_.back()->lidar = std::make_unique<ScanDevice>(
      config_.lidar, fork_join_, config_.lidar_errors, config_.seed * 7919ULL + 17 + 1000 * k);
  return static_cast<int>(k);
}

void SimWorld::silence_uav(int i) {
  Uav& u = *uavs_.at(static_cast<std::size_t>(i));
  u.silent = true;
  hal::FlightSetpoint hold;  // where it is, still
  hold.position_m = u.body.state().pose.p;
  hold.velocity_mps = Vec3::Zero();
  (void)u.body.send_setpoint(hold);
}

void SimWorld::enable_ugv_lidars() {
  std::uint64_t k = 0;
  for (auto& u : ugvs_)
    u->lidar = std::make_unique<ScanDevice>(config_.lidar, fork_join_, config_.lidar_errors,
                                            config_.seed * 7919ULL + 18 + k++);
}

hal::CanBus& SimWorld::ugv_can(int i) {
  return ugvs_.at(static_cast<std::size_t>(i))->link.board();
}
hal::Lidar& SimWorld::ugv_lidar(int i) {
  return *ugvs_.at(static_cast<std::size_t>(i))->lidar;
}
UavBody& SimWorld::uav(int i) {
  return uavs_.at(static_cast<std::size_t>(i))->body;
}
const UavBody* SimWorld::uav_body(int i) const {
  return i >= 0 && i < uav_count() ? &uavs_[static_cast<std::size_t>(i)]->body : nullptr;
}
hal::Lidar& SimWorld::uav_lidar(int i) {
  return *uavs_.at(static_cast<std::size_t>(i))->lidar;
}
hal::RelativePoseSensor& SimWorld::uav_camera(int i) {
  return uavs_.at(static_cast<std::size_t>(i))->camera;
}
void SimWorld::set_base_fault(int i, bool on) {
  ugvs_[static_cast<std::size_t>(i)]->body.controller().set_fault(on);
}

const UgvBody& SimWorld::ugv(int i) const {
  return ugvs_.at(static_cast<std::size_t>(i))->body;
}
const OdometryFrame& SimWorld::odometry_frame() const {
  static const OdometryFrame kWorld;
  return uavs_.empty() ? kWorld : uavs_.front()->body.odometry_frame();
}
double SimWorld::min_clearance_m(int i) const {
  return ugvs_.at(static_cast<std::size_t>(i))->min_clearance;
}

bool SimWorld::line_of_sight(const Vec3& a, const Vec3& b, int except_ugv) const {
  const Vec3 d = b - a;
  const double len = d.norm();
  if (len < 1e-9) return true;
  const std::size_t skip = except_ugv < 0
                               ? scene_.boxes.size()
                               : world_.boxes.size() + static_cast<std::size_t>(except_ugv);
  for (std::size_t i = 0; i < scene_.boxes.size(); ++i) {
    if (i == skip) continue;
    const double t = ray_box(a, d / len, scene_.boxes[i]);
    if (t >= 0.0 && t < len) return false;
  }
  return true;
}

// A UGV's chassis as the sensors see it: the square inscribed in its footprint disc (the disc is
// the collision model: it circumscribes the chassis at any heading), axis-aligned (the LiDAR casts
// axis-aligned boxes), up to its top.
void SimWorld::update_scene() {
  const double r = config_.ugv.radius_m / std::sqrt(2.0);
  for (std::size_t i = 0; i < ugvs_.size(); ++i) {
    scene_.boxes[world_.boxes.size() + i] = {ugvs_[i]->body.pose().p, Vec2(r, r),
                                             config_.ugv.height_m};
  }
}

void SimWorld::detect(Uav& uav, TimePoint now) {
  uav.camera.frame.clear();
  const Pose3& cam = uav.body.state().pose;
  const CameraConfig& c = config_.camera;
  for (std::size_t i = 0; i < ugvs_.size(); ++i) {
    const Pose2& g = ugvs_[i]->body.pose();
    const Vec3 tag(g.p.x(), g.p.y(), c.tag_height_m);
    const Vec3 to_tag = tag - cam.p;
    if (to_tag.norm() > c.range_m) continue;
    if (std::acos(std::clamp(-to_tag.normalized().z(), -1.0, 1.0)) > c.fov_half_angle_rad) continue;
    if (!line_of_sight(cam.p, tag, static_cast<int>(i))) continue;  // its own body carries it
    const Pose3 truth =
        cam.inverse().compose({Vec3(g.p.x(), g.p.y(), 0.0), quat_from_yaw(g.yaw_rad)});
    hal::RelativePoseDetection d;
    d.stamp = now;
    d.ugv_id = static_cast<RobotId>(i);
    // One draw per statement: the order of a constructor's arguments is unspecified (GCC takes
    // them last to first on x86-64, first to last on aarch64). z, y, x: as the seeds have flown.
    if (c.miss_probability > 0.0 && rng_.bernoulli(c.miss_probability)) continue;
    const double sp_true = c.sigma_position_m * c.true_sigma_scale;
    const double nz = rng_.gaussian(0, sp_true);
    const double ny = rng_.gaussian(0, sp_true);
    const double nx = rng_.gaussian(0, sp_true);
    double yaw_error = rng_.gaussian(0, c.sigma_yaw_rad * c.true_sigma_scale);
    Vec3 error(nx, ny, nz);
    if (c.outlier_probability > 0.0 && rng_.bernoulli(c.outlier_probability)) {
      // Far off, in the camera's frame; mostly sideways, as a mismatched tag is.
      const double r = rng_.uniform(0.3, 1.0) * c.outlier_max_m;
      const double a = rng_.uniform(-M_PI, M_PI);
      error += Vec3(r * std::cos(a), r * std::sin(a), 0.0);
      yaw_error += rng_.uniform(-c.outlier_max_rad, c.outlier_max_rad);
    }
    d.ugv_in_uav.p = truth.p + error;
    d.ugv_in_uav.q = (truth.q * quat_from_yaw(yaw_error)).normalized();
    const double sp = c.sigma_position_m * c.sigma_position_m;
    d.covariance = Eigen::Vector4d(sp, sp, sp, c.sigma_yaw_rad * c.sigma_yaw_rad).asDiagonal();
    (void)uav.camera.frame.push_back(d);
  }
}

void SimWorld::watch_collisions(TimePoint now) {
  const double r = config_.ugv.radius_m;
  for (std::size_t i = 0; i < ugvs_.size(); ++i) {
    Ugv& u = *ugvs_[i];
    const Vec2 p = u.body.pose().p;
    const double clear = world_.clearance(p, config_.ugv.band_low_m, config_.ugv.band_high_m) - r;
    u.min_clearance = std::min(u.min_clearance, clear);
    if (clear < 0.0 && !u.collided) {
      u.collided = true;
      u.body.freeze();
      collisions_.push_back({now, static_cast<int>(i), -1, p});
    }
    for (std::size_t j = i + 1; j < ugvs_.size(); ++j) {
      Ugv& o = *ugvs_[j];
      const double gap = (o.body.pose().p - p).norm() - 2.0 * r;
      u.min_clearance = std::min(u.min_clearance, gap);
      o.min_clearance = std::min(o.min_clearance, gap);
      if (gap < 0.0 && !(u.collided && o.collided)) {
        if (!u.collided) u.body.freeze();
        if (!o.collided) o.body.freeze();
        u.collided = o.collided = true;
        collisions_.push_back({now, static_cast<int>(i), static_cast<int>(j), p});
      }
    }
  }
}

void SimWorld::step(TimePoint now, double dt) {
  for (auto& u : ugvs_)
    u->body.step(u->clock.now(), dt, u->link.motor());
  for (std::size_t k = 0; k < uavs_.size(); ++k) {
    Uav& u = *uavs_[k];
    if (k > 0) u.body.use_frame(uavs_.front()->body.odometry_frame());  // one map frame
    // A silent UAV's body holds still; its odometry is not read any more.
    u.body.step(u.clock.local(now), dt);
  }
  watch_collisions(now);
  if (now >= next_scan_) {
    next_scan_ = now + config_.lidar_period;
    update_scene();
    for (auto& u : uavs_) {
      if (!u->silent) u->lidar->scan(scene_, u->body.state().pose, u->clock.local(now));
    }
    for (auto& u : ugvs_) {
      if (!u->lidar) continue;
      const Pose2& g = u->body.pose();
      u->lidar->scan(scene_,
                     {Vec3(g.p.x(), g.p.y(), config_.ugv_lidar_height_m), quat_from_yaw(g.yaw_rad)},
                     now);
    }
  }
  if (!uavs_.empty() && now >= next_frame_) {
    next_frame_ = now + config_.camera.period;
    update_scene();
    for (auto& u : uavs_) {
      if (u->silent) continue;
      detect(*u, u->clock.local(now));
      const CameraConfig& c = config_.camera;
      Duration late = c.latency;
      if (c.jitter.count() > 0) late += seconds(rng_.uniform(0.0, to_seconds(c.jitter)));
      u->camera.capture(now + late);
    }
  }
  for (auto& u : uavs_) {
    if (!u->silent) u->camera.deliver(now);
  }
}

}  // namespace colag::sim
