#pragma once
// The simulated world for host runs: the obstacles, the UGV bodies (each behind its own CAN
// link, speaking the real protocol), the UAV body, and the UAV's sensors as HAL devices — a
// VLP-32-like LiDAR and a camera that measures the relative pose of every UGV within range
// and line of sight. Optionally every UGV has its own LiDAR (the self-perception baseline).
// The UGVs' bodies are obstacles to those sensors like the boxes: they block LiDAR rays and the
// camera's view (a UGV frozen by a collision, or whose firmware died, is seen, not invisible).
// Ground truth is watched at every step: the UGV footprints against the obstacles and each
// other; a collision is recorded (never hidden) and the UGV stops where it hit.
// Host-side only. Built once before a run; step() allocates nothing.
#include <memory>
#include <vector>

#include "colag/common/limits.hpp"
#include "colag/common/random.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/hal/lidar.hpp"
#include "colag/hal/relative_pose_sensor.hpp"
#include "colag/hal/sim/can_link.hpp"
#include "colag/sim/world/box_world.hpp"
#include "colag/sim/world/lidar_errors.hpp"
#include "colag/sim/world/lidar_simulator.hpp"
#include "colag/sim/world/robot_clock.hpp"
#include "colag/sim/world/uav_body.hpp"
#include "colag/sim/world/ugv_body.hpp"

namespace colag::sim {

struct CameraConfig {
  double range_m = 5.0;
  double sigma_position_m = 0.2;
  double sigma_yaw_rad = 0.05;
  double fov_half_angle_rad = M_PI;  // from straight down; pi = unlimited (the paper's device)
  double tag_height_m = 0.3;         // what the camera looks at, above the UGV's origin
  Duration period = std::chrono::milliseconds(50);
  // The field world's camera (all off in the ideal one): tags missed, detections far off (a
  // flipped or mismatched tag), the true error larger than the covariance reported, and frames
  // arriving late.
  double miss_probability = 0.0;
  double outlier_probability = 0.0;
  double outlier_max_m = 1.0;     // an outlier's horizontal error: uniform up to this
  double outlier_max_rad = 0.52;  // and its yaw error
  double true_sigma_scale = 1.0;  // true error sigma = this x the reported sigma
  Duration latency{};             // capture to delivery
  Duration jitter{};              // + uniform 0..jitter
};

struct SimWorldConfig {
  UgvBodyConfig ugv;
  UavBodyConfig uav;
  LidarPattern lidar;
  Duration lidar_period = std::chrono::milliseconds(100);
  LidarErrors lidar_errors;
  CameraConfig camera;
  double ugv_lidar_height_m = 0.4;  // self-perception baseline
  std::uint64_t seed = 1;
};

struct CollisionEvent {
  TimePoint at;
  int ugv = -1;
  int other_ugv = -1;  // -1: an obstacle
  Vec2 where = Vec2::Zero();
};

class SimWorld {
 public:
  // `fork_join` (optional, not owned): the LiDAR simulation may use more cores.
  SimWorld(const SimWorldConfig& config, BoxWorld world, const hal::Clock& clock,
           ForkJoin* fork_join = nullptr);
  ~SimWorld();

  // Each robot runs on its own clock (its devices stamp with it); the default is the world's.
  // `wheels`: this UGV's own (the field world's), over config.ugv.wheel_errors.
  int add_ugv(const Pose2& start, const ClockModel& clock = {},
              const WheelErrors* wheels = nullptr);
  // Returns its index. Several UAVs (beyond the paper) share the first one's odometry frame (one
  // co-registered map, as a fleet's LiDAR-inertial odometries must be to share their maps).
  int add_uav(const Vec3& start, const ClockModel& clock = {});
  int uav_count() const { return static_cast<int>(uavs_.size()); }
  // Fault injection: UAV i's board dies: it stops where it is, its devices fall silent.
  void silence_uav(int i);
  void enable_ugv_lidars();  // self-perception baseline

  // Advances every body by dt and produces the sensor data due at `now`.
  void step(TimePoint now, double dt);

  // HAL devices for the firmware under test.
  hal::CanBus& ugv_can(int i);
  hal::Lidar& ugv_lidar(int i);
  UavBody& uav(int i = 0);
  const UavBody* uav_body(int i = 0) const;  // null without that UAV
  hal::Lidar& uav_lidar(int i = 0);
  hal::RelativePoseSensor& uav_camera(int i = 0);

  // Ground truth.
  const BoxWorld& world() const { return world_; }
  int ugv_count() const { return static_cast<int>(ugvs_.size()); }
  const UgvBody& ugv(int i) const;
  // Fault injection: UGV i's base reports its own fault (BaseEmulator::set_fault).
  void set_base_fault(int i, bool on);
  double min_clearance_m(int i) const;
  // The frame the UAV's odometry (so its map, and the UGVs' estimates) is in: the world's
  // without a UAV.
  const OdometryFrame& odometry_frame() const;
  const std::vector<CollisionEvent>& collisions() const { return collisions_; }
  // Nothing blocks the segment: no box, and no UGV body but `except_ugv`'s (-1: none).
  bool line_of_sight(const Vec3& a, const Vec3& b, int except_ugv = -1) const;

 private:
  struct Ugv;
  struct Uav;
  class ScanDevice;
  class Camera;
  void detect(Uav& uav, TimePoint now);
  void watch_collisions(TimePoint now);
  void update_scene();

  SimWorldConfig config_;
  BoxWorld world_;
  BoxWorld scene_;  // what the sensors see: world_'s boxes, then one box per UGV body
  const hal::Clock& clock_;
  ForkJoin* fork_join_;
  Rng rng_;
  std::vector<std::unique_ptr<Ugv>> ugvs_;
  std::vector<std::unique_ptr<Uav>> uavs_;
  TimePoint next_scan_{}, next_frame_{};
  std::vector<CollisionEvent> collisions_;
};

}  // namespace colag::sim
