// A map that does not fit the mission is refused or warned about before anything flies
// (issue 19, item 10): it used to fly as an empty arena and report success.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "colag/sim/mission/mission_config.hpp"

using namespace colag;
using namespace colag::mission;

namespace {

// The points as an ASCII PCD file; removed when the test ends.
struct CloudFile {
  explicit CloudFile(const std::vector<Vec3>& pts, const std::string& name)
      : path((std::filesystem::temp_directory_path() /
              ("colag_" + name + "_" + std::to_string(::getpid()) + ".pcd"))
                 .string()) {
    std::ofstream out(path);
    out << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " << pts.size()
        << "\nHEIGHT 1\nPOINTS " << pts.size() << "\nDATA ascii\n";
    for (const Vec3& p : pts)
      out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  ~CloudFile() { std::filesystem::remove(path); }
  std::string path;
};

// A 36 x 36 m site (0.2 m ground grid) with a 0.8 m box at `box` unless none, all scaled
// by `scale` and shifted by `shift`.
std::vector<Vec3> site(bool with_box, Vec2 box = Vec2(1.0, 3.0), double scale = 1.0,
                       Vec2 shift = Vec2::Zero()) {
  std::vector<Vec3> pts;
  const auto add = [&](double x, double y, double z) {
    pts.emplace_back(scale * x + shift.x(), scale * y + shift.y(), scale * z);
  };
  for (int j = -90; j <= 90; ++j) {
    for (int i = -90; i <= 90; ++i)
      add(0.2 * i, 0.2 * j, 0.0);
  }
  if (with_box) {
    for (double y = box.y() - 0.35; y < box.y() + 0.4; y += 0.1) {
      for (double x = box.x() - 0.35; x < box.x() + 0.4; x += 0.1) {
        for (double z = 0.1; z < 0.65; z += 0.1)
          add(x, y, z);
      }
    }
  }
  return pts;
}

bool build(const CloudFile& f, std::vector<std::string>& warnings, std::string& error) {
  MissionConfig cfg;
  cfg.scenario = "file";
  cfg.map_file = f.path;
  cfg.ugvs = 3;
  sim::BoxWorld world;
  return build_world(cfg, world, error, &warnings);
}

}  // namespace

TEST(MapChecks, AGoodMapLoadsWithoutWarnings) {
  const CloudFile f(site(true), "good");
  std::vector<std::string> warnings;
  std::string error;
  ASSERT_TRUE(build(f, warnings, error)) << error;
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}

TEST(MapChecks, AMapInMillimetresIsRefused) {
  const CloudFile f(site(true, Vec2(1.0, 3.0), 1000.0), "millimetres");
  std::vector<std::string> warnings;
  std::string error;
  EXPECT_FALSE(build(f, warnings, error));
  EXPECT_NE(error.find("millimetres"), std::string::npos) << error;
}

TEST(MapChecks, AMapShiftedTo0To36IsRefused) {
  const CloudFile f(site(true, Vec2(1.0, 3.0), 1.0, Vec2(18.0, 18.0)), "shifted");
  std::vector<std::string> warnings;
  std::string error;
  EXPECT_FALSE(build(f, warnings, error));
  EXPECT_NE(error.find("outside the map"), std::string::npos) << error;
}

TEST(MapChecks, AnEmptyArenaIsWarnedAbout) {
  const CloudFile f(site(false), "empty");
  std::vector<std::string> warnings;
  std::string error;
  ASSERT_TRUE(build(f, warnings, error)) << error;
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("no obstacle"), std::string::npos) << warnings[0];
}

TEST(MapChecks, AStartInsideAnObstacleIsWarnedAbout) {
  const CloudFile f(site(true, Vec2(-2.0, 16.0)), "start_in_box");  // on UGV 1's start
  std::vector<std::string> warnings;
  std::string error;
  ASSERT_TRUE(build(f, warnings, error)) << error;
  bool found = false;
  for (const std::string& w : warnings)
    found = found || w.find("UGV 1's start (-2.00, 16.00) is inside") != std::string::npos;
  EXPECT_TRUE(found);
}
