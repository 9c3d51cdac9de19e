#pragma once
// The fleet's telemetry as ROS 2 messages (REP-103 units, REP-105 frames): each class is one
// generated DDS sample plus the storage its strings and sequences point into, sized at init;
// refilling within that capacity allocates nothing. Not copyable: the sample points into it.
// Used by the boards' ROS 2 telemetry and by MCAP recording (with to_cdr, cdr.hpp).
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "colag/common/ellipse.hpp"
#include "colag/common/grid2d.hpp"
#include "colag/common/map_patch_codec.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/support_plan.hpp"
#include "colag/msg/uav_odometry.hpp"
#include "colag/msg/ugv_status.hpp"
#include "ros2_msgs.h"

namespace colag::hal::ros2 {

inline constexpr const char* kMapFrame = "map";  // the fleet's world frame (the UAV odometry's)

// A short name kept in the message's own storage (frames, marker namespaces, texts).
using Name = std::array<char, 48>;
void set_name(Name& out, std::string_view text);  // cut to fit

void set_time(builtin_interfaces_msg_dds__Time_& out, TimePoint stamp);  // before 0: 0
void set_yaw(geometry_msgs_msg_dds__Quaternion_& out, double yaw_rad);
void set_pose(geometry_msgs_msg_dds__Pose_& out, double x, double y, double z, double yaw_rad);

class NoCopy {
 public:
  NoCopy() = default;
  NoCopy(const NoCopy&) = delete;
  NoCopy& operator=(const NoCopy&) = delete;
};

// nav_msgs/Odometry: pose in `map`, twist in the body frame.
class OdometryMessage : NoCopy {
 public:
  explicit OdometryMessage(std::string_view child_frame);
  // A UGV's estimate: (x, y, yaw) with its covariance, commanded speed and yaw rate.
  void set(const msg::UgvStatus& s);
  // The UAV's odometry (no covariance: -1 in its first element, "unknown" by ROS convention).
  void set(const msg::UavOdometry& o);
  const nav_msgs_msg_dds__Odometry_& sample() const { return msg_; }

 private:
  Name frame_{}, child_{};
  nav_msgs_msg_dds__Odometry_ msg_{};
};

// colag_msgs/UgvStatus and colag_msgs/UavStatus.
class UgvStatusMessage : NoCopy {
 public:
  UgvStatusMessage();
  void set(const msg::UgvStatus& s);
  // The goals received on <ns>/goal_pose and the answer to the last (`text`: a literal).
  void set_goals(std::uint32_t received, std::uint8_t last_result, const char* text);
  // The commands received on <ns>/command and the answer to the last: its id, its
  // value, the result and its text (a literal).
  void set_commands(std::uint32_t received, std::uint32_t last_id, std::uint8_t last,
                    std::uint8_t last_result, const char* text);
  const colag_msgs_msg_dds__UgvStatus_& sample() const { return msg_; }

 private:
  Name frame_{};
  colag_msgs_msg_dds__UgvStatus_ msg_{};
};

class UavStatusMessage : NoCopy {
 public:
  UavStatusMessage();
  void set(const msg::UavOdometry& o, const msg::SupportPlan& plan, std::uint32_t flight_lost);
  const colag_msgs_msg_dds__UavStatus_& sample() const { return msg_; }

 private:
  Name frame_{};
  colag_msgs_msg_dds__UavStatus_ msg_{};
};

// nav_msgs/Path in `map`.
class PathMessage : NoCopy {
 public:
  explicit PathMessage(std::size_t capacity);
  void clear(TimePoint stamp);
  bool push(double x, double y, double z, double yaw_rad);  // false when full
  const nav_msgs_msg_dds__Path_& sample() const { return msg_; }

 private:
  Name frame_{};
  std::vector<geometry_msgs_msg_dds__PoseStamped_> poses_;
  nav_msgs_msg_dds__Path_ msg_{};
};

// nav_msgs/OccupancyGrid in `map` over a grid geometry: -1 unknown, 0 free, 100 occupied.
class GridMessage : NoCopy {
 public:
  explicit GridMessage(const GridGeometry2d& geometry);
  // `value(CellIndex)` gives each cell's value, row by row from the origin.
  template <class Value>
  void fill(TimePoint stamp, Value&& value) {
    stamp_all(stamp);
    std::size_t i = 0;
    for (int y = 0; y < geometry_.cells_y(); ++y)
      for (int x = 0; x < geometry_.cells_x(); ++x)
        cells_[i++] = value(CellIndex{x, y});
  }
  // The grid's corner (cell (0, 0)) now: the robots' maps are windows that move over the site.
  void set_origin(const Vec2& origin);
  static constexpr std::int8_t kUnknown = -1, kFree = 0, kOccupied = 100;
  const nav_msgs_msg_dds__OccupancyGrid_& sample() const { return msg_; }

 private:
  void stamp_all(TimePoint stamp);
  GridGeometry2d geometry_;
  Name frame_{};
  std::vector<std::int8_t> cells_;
  nav_msgs_msg_dds__OccupancyGrid_ msg_{};
};

struct Rgba {
  float r, g, b, a;
};

// visualization_msgs/MarkerArray in `map`. Points go to the marker added last.
class MarkerArrayMessage : NoCopy {
 public:
  MarkerArrayMessage(std::size_t markers, std::size_t points);
  void clear(TimePoint stamp);
  // A marker that deletes every earlier one of this array's topic (first, to replace a set).
  bool delete_all();
  // A marker at (x, y, z, yaw) with scale (sx, sy, sz); null when full.
  visualization_msgs_msg_dds__Marker_* add(std::string_view ns, std::int32_t id, std::int32_t type,
                                           Rgba color, const double (&at)[4],
                                           const double (&scale)[3]);
  bool add_point(double x, double y, double z);
  void set_text(std::string_view text);  // of the marker added last
  // The k-sigma ellipses as flat cylinders (RViz2's and Foxglove's ellipse).
  void add_ellipses(std::string_view ns, std::span<const Ellipse> ellipses, double z, Rgba color);
  const visualization_msgs_msg_dds__MarkerArray_& sample() const { return msg_; }

  static constexpr std::int32_t kCube = 1, kSphere = 2, kCylinder = 3, kLineStrip = 4,
                                kCubeList = 6, kText = 9;

 private:
  TimePoint stamp_{};
  Name frame_{};
  std::vector<visualization_msgs_msg_dds__Marker_> markers_;
  std::vector<Name> names_;  // ns and text of each marker
  std::vector<Name> texts_;
  std::vector<geometry_msgs_msg_dds__Point_> points_;
  std::size_t used_points_ = 0;
  visualization_msgs_msg_dds__MarkerArray_ msg_{};
};

// tf2_msgs/TFMessage: `map` -> each robot's body.
class TfMessage : NoCopy {
 public:
  explicit TfMessage(std::size_t capacity);
  void clear();
  bool add(TimePoint stamp, std::string_view child_frame, double x, double y, double z,
           const double (&q_wxyz)[4]);
  const tf2_msgs_msg_dds__TFMessage_& sample() const { return msg_; }

 private:
  Name frame_{};
  std::vector<Name> children_;
  std::vector<geometry_msgs_msg_dds__TransformStamped_> transforms_;
  tf2_msgs_msg_dds__TFMessage_ msg_{};
};

// The namespaced frame of a robot's body: "ugv3/base_link".
std::string base_link(std::string_view ns);

// A map cell as an OccupancyGrid value: -1 unknown, 0 free, 100 occupied.
std::int8_t occupancy_value(CellState s);

// A UGV's collision prediction: its 3-sigma ellipses and, when a collision is predicted, the
// point (replacing the array's earlier markers).
void set_prediction(MarkerArrayMessage& out, TimePoint stamp, std::span<const Ellipse> ellipses,
                    const Vec2* collision_point);
// The UAV's support plan: the stops in visit order, and a marker per stop with its UGV, ETA
// and deadline (replacing the earlier ones).
void set_support_plan(const msg::SupportPlan& plan, PathMessage& path, MarkerArrayMessage& markers);

}  // namespace colag::hal::ros2
