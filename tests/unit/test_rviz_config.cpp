// config/colag.rviz (README "Watching a mission"): every topic it shows is one the fleet's
// ROS 2 telemetry publishes, asked for with a QoS that matches what the robots offer (a reliable
// reader never matches a best-effort writer, a transient-local one never a volatile writer: RViz2
// would show nothing), and its "2D Goal Pose" tools publish where the UGVs listen.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <regex>
#include <string>

namespace {

TEST(RvizConfig, ShowsTheTelemetrysTopicsWithMatchingQosAndSendsGoalsWhereUgvsListen) {
  const YAML::Node doc = YAML::LoadFile(std::string(COLAG_CONFIG_DIR) + "/colag.rviz");
  const YAML::Node vm = doc["Visualization Manager"];
  ASSERT_TRUE(vm);
  EXPECT_EQ(vm["Global Options"]["Fixed Frame"].as<std::string>(), "map");
  const std::regex telemetry(
      "/ugv[0-9]+/(odom|plan|prediction|map)|/uav/"
      "(odom|map|support_plan|support_plan/markers)");
  int shown = 0;
  for (const YAML::Node& d : vm["Displays"]) {
    if (!d["Topic"]) continue;
    const std::string topic = d["Topic"]["Value"].as<std::string>();
    EXPECT_TRUE(std::regex_match(topic, telemetry)) << topic << ": not published by the fleet";
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
    EXPECT_TRUE(std::regex_match(topic, std::regex("/ugv[0-9]+/goal_pose"))) << topic;
    EXPECT_EQ(t["Topic"]["Reliability Policy"].as<std::string>(), "Reliable") << topic;
    ++goal_tools;
  }
  EXPECT_GE(goal_tools, 1);
}

}  // namespace
