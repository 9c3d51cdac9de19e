#include "colag/hal/ros2/ros2_schemas.hpp"

#include <array>
#include <vector>

namespace colag::hal::ros2 {

namespace {

struct Definition {
  std::string_view name;  // pkg/Type, as `MSG:` lines name it
  std::string_view text;
  std::array<std::string_view, 10> uses;  // the types its fields name, in field order
};

// One row per type; `uses` lists direct dependencies only.
constexpr std::array kDefinitions = {
    Definition{"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n", {}},
    Definition{"builtin_interfaces/Duration", "int32 sec\nuint32 nanosec\n", {}},
    Definition{"std_msgs/Header",
               "builtin_interfaces/Time stamp\nstring frame_id\n",
               {"builtin_interfaces/Time"}},
    Definition{"std_msgs/ColorRGBA", "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n", {}},
    Definition{"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n", {}},
    Definition{"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n", {}},
    Definition{"geometry_msgs/Quaternion", "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n", {}},
    Definition{"geometry_msgs/Pose",
               "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n",
               {"geometry_msgs/Point", "geometry_msgs/Quaternion"}},
    Definition{"geometry_msgs/PoseStamped",
               "std_msgs/Header header\ngeometry_msgs/Pose pose\n",
               {"std_msgs/Header", "geometry_msgs/Pose"}},
    Definition{"geometry_msgs/PoseWithCovariance",
               "geometry_msgs/Pose pose\nfloat64[36] covariance\n",
               {"geometry_msgs/Pose"}},
    Definition{"geometry_msgs/Twist",
               "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n",
               {"geometry_msgs/Vector3"}},
    Definition{"geometry_msgs/TwistWithCovariance",
               "geometry_msgs/Twist twist\nfloat64[36] covariance\n",
               {"geometry_msgs/Twist"}},
    Definition{"geometry_msgs/Transform",
               "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n",
               {"geometry_msgs/Vector3", "geometry_msgs/Quaternion"}},
    Definition{"geometry_msgs/TransformStamped",
               "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n",
               {"std_msgs/Header", "geometry_msgs/Transform"}},
    Definition{"tf2_msgs/TFMessage",
               "geometry_msgs/TransformStamped[] transforms\n",
               {"geometry_msgs/TransformStamped"}},
    Definition{"nav_msgs/Odometry",
               "std_msgs/Header header\nstring child_frame_id\n"
               "geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n",
               {"std_msgs/Header", "geometry_msgs/PoseWithCovariance",
                "geometry_msgs/TwistWithCovariance"}},
    Definition{"nav_msgs/Path",
               "std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses\n",
               {"std_msgs/Header", "geometry_msgs/PoseStamped"}},
    Definition{"nav_msgs/MapMetaData",
               "builtin_interfaces/Time map_load_time\nfloat32 resolution\nuint32 width\n"
               "uint32 height\ngeometry_msgs/Pose origin\n",
               {"builtin_interfaces/Time", "geometry_msgs/Pose"}},
    Definition{"nav_msgs/OccupancyGrid",
               "std_msgs/Header header\nnav_msgs/MapMetaData info\nint8[] data\n",
               {"std_msgs/Header", "nav_msgs/MapMetaData"}},
    Definition{"sensor_msgs/CompressedImage",
               "std_msgs/Header header\nstring format\nuint8[] data\n",
               {"std_msgs/Header"}},
    Definition{"visualization_msgs/UVCoordinate", "float32 u\nfloat32 v\n", {}},
    Definition{"visualization_msgs/MeshFile", "string filename\nuint8[] data\n", {}},
    Definition{
        "visualization_msgs/Marker",
        "int32 ARROW=0\nint32 CUBE=1\nint32 SPHERE=2\nint32 CYLINDER=3\n"
        "int32 LINE_STRIP=4\nint32 LINE_LIST=5\nint32 CUBE_LIST=6\nint32 SPHERE_LIST=7\n"
        "int32 POINTS=8\nint32 TEXT_VIEW_FACING=9\nint32 MESH_RESOURCE=10\n"
        "int32 TRIANGLE_LIST=11\nint32 ARROW_STRIP=12\n"
        "int32 ADD=0\nint32 MODIFY=0\nint32 DELETE=2\nint32 DELETEALL=3\n"
        "std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\n"
        "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\n"
        "builtin_interfaces/Duration lifetime\nbool frame_locked\n"
        "geometry_msgs/Point[] points\nstd_msgs/ColorRGBA[] colors\n"
        "string texture_resource\nsensor_msgs/CompressedImage texture\n"
        "visualization_msgs/UVCoordinate[] uv_coordinates\nstring text\nstring mesh_resource\n"
        "visualization_msgs/MeshFile mesh_file\nbool mesh_use_embedded_materials\n",
        {"std_msgs/Header", "geometry_msgs/Pose", "geometry_msgs/Vector3", "std_msgs/ColorRGBA",
         "builtin_interfaces/Duration", "geometry_msgs/Point", "sensor_msgs/CompressedImage",
         "visualization_msgs/UVCoordinate", "visualization_msgs/MeshFile"}},
    Definition{"visualization_msgs/MarkerArray",
               "visualization_msgs/Marker[] markers\n",
               {"visualization_msgs/Marker"}},
    Definition{"colag_msgs/UgvStatus",
               "uint8 WAITING_FOR_INIT=0\nuint8 DRIVING=1\nuint8 WAITING_FOR_SUPPORT=2\n"
               "uint8 ARRIVED=3\nuint8 NO_PATH=4\nuint8 FAULT=5\nuint8 BLOCKED=6\n"
               "uint8 WAITING_FOR_ROBOT=7\nuint8 UAV_UNAVAILABLE=8\nuint8 PAUSED=9\n"
               "uint8 ABORTED=10\n"
               "std_msgs/Header header\nuint16 ugv_id\nuint8 mode\nstring mode_name\n"
               "uint8 blocked_reason\nstring blocked_reason_text\nuint8 base_fault\n"
               "string base_fault_text\nuint32 base_error\ngeometry_msgs/Point goal\n"
               "float64 waiting_time_s\nfloat64 clock_error_s\nuint32 rejected_inputs\n"
               "uint32 overruns\nuint8 degradation\nuint32 goals_received\n"
               "uint8 last_goal_result\nstring last_goal_text\nuint32 commands_received\n"
               "uint32 last_command_id\nuint8 last_command\nuint8 last_command_result\n"
               "string last_command_text\n",
               {"std_msgs/Header", "geometry_msgs/Point"}},
    Definition{"colag_msgs/UgvCommand",
               "uint8 PAUSE=1\nuint8 RESUME=2\nuint8 ABORT=3\nuint8 RETURN_TO_START=4\n"
               "std_msgs/Header header\nuint32 id\nuint8 command\n",
               {"std_msgs/Header"}},
    Definition{"colag_msgs/UavStatus",
               "uint8 IN_CONTROL=0\nuint8 STARTING=1\nuint8 LOST=2\nuint8 LANDING=3\n"
               "std_msgs/Header header\nuint16 uav_id\nuint8 flight\nstring flight_name\n"
               "uint8 fault\nstring fault_text\nuint32 plan_seq\nuint32 plan_stops\n"
               "float64 total_lateness_s\nuint32 flight_lost\n",
               {"std_msgs/Header"}},
};

const Definition* find(std::string_view name) {
  for (const Definition& d : kDefinitions)
    if (d.name == name) return &d;
  return nullptr;
}

// Appends the dependencies of `d` not yet in `seen`, depth first in field order.
void collect(const Definition& d, std::vector<const Definition*>& seen) {
  for (std::string_view u : d.uses) {
    if (u.empty()) break;
    const Definition* dep = find(u);
    bool known = dep == nullptr;
    for (const Definition* s : seen)
      known = known || s == dep;
    if (known) continue;
    seen.push_back(dep);
    collect(*dep, seen);
  }
}

}  // namespace

std::string ros2msg_schema(std::string_view type) {
  // "pkg/msg/Type" -> "pkg/Type"
  const std::size_t slash = type.find("/msg/");
  if (slash == std::string_view::npos) return {};
  std::string name(type.substr(0, slash));
  name += '/';
  name += type.substr(slash + 5);
  const Definition* d = find(name);
  if (d == nullptr) return {};
  std::vector<const Definition*> deps;
  collect(*d, deps);
  std::string out(d->text);
  for (const Definition* dep : deps) {
    out += std::string(80, '=');
    out += "\nMSG: ";
    out += dep->name;
    out += '\n';
    out += dep->text;
  }
  return out;
}

}  // namespace colag::hal::ros2
