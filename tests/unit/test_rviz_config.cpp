// config/colag.rviz (README "Watching a mission"): every topic it shows is one the fleet's
// ROS 2 telemetry publishes, asked for with a QoS that matches what the robots offer (a reliable
// reader never matches a best-effort writer, a transient-local one never a volatile writer: RViz2
// would show nothing), and its "2D Goal Pose" tools publish where the UGVs listen.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cctype>
#include <initializer_list>
#include <string>
#include <string_view>

namespace {

// "/ugv<digits>/" followed by `rest`, for one of `rests` (no std::regex: GCC 12 under ASan warns
// inside it).
bool ugv_topic(std::string_view topic, std::initializer_list<std::string_view> rests) {
  if (!topic.starts_with("/ugv")) return false;
  topic.remove_prefix(4);
  std::size_t digits = 0;
  while (digits < topic.size() && std::isdigit(static_cast<unsigned char>(topic[digits])) != 0)
    ++digits;
  if (digits == 0 || digits == topic.size() || topic[digits] != '/') return false;
  topic.remove_prefix(digits + 1);
  for (std::string_view r : rests)
    if (topic == r) return true;
  return false;
}

bool uav_topic(std::string_view topic) {
  for (std::string_view t :
       {"/uav/odom", "/uav/map", "/uav/support_plan", "/uav/support_plan/markers"})
    if (topic == t) return true;
  return false;
}

TEST(RvizConfig, ShowsTheTelemetrysTopicsWithMatchingQosAndSendsGoalsWhereUgvsListen) {
  const YAML::Node doc = YAML::LoadFile(std::string(COLAG_CONFIG_DIR) + "/colag.rviz");
  const YAML::Node vm = doc["Visualization Manager"];
  ASSERT_TRUE(vm);
  EXPECT_EQ(vm["Global Options"]["Fixed Frame"].as<std::string>(), "map");
  int shown = 0;
  for (const YAML::Node& d : vm["Displays"]) {
    if (!d["Topic"]) continue;
    const std::string topic = d["Topic"]["Value"].as<std::string>();
    EXPECT_TRUE(ugv_topic(topic, {"odom", "plan", "prediction", "map"}) || uav_topic(topic))
        << topic << ": not published by the fleet";
    const bool latched = topic.ends_with("/map") || topic.find("support_plan") != std::string::npos;
    const bool sensor = topic.ends_with("/odom");
    EXPECT_EQ(d["Topic"]["Durability Policy"].as<std::string>(),
              latched ? "Transient Local" : "Volatile")
        << topic;
    if (sensor) {
      EXPECT_EQ(d["Topic"]["Reliability Policy"].as<std::string>(), "Best Effort") << topic;
    }
    ++shown;
  }
  EXPECT_GE(shown, 10);
  int goal_tools = 0;
  for (const YAML::Node& t : vm["Tools"]) {
    if (t["Class"].as<std::string>() != "rviz_default_plugins/SetGoal") continue;
    const std::string topic = t["Topic"]["Value"].as<std::string>();
    EXPECT_TRUE(ugv_topic(topic, {"goal_pose"})) << topic;
    EXPECT_EQ(t["Topic"]["Reliability Policy"].as<std::string>(), "Reliable") << topic;
    ++goal_tools;
  }
  EXPECT_GE(goal_tools, 1);
}

}  // namespace
