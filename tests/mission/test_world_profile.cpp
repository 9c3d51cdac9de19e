// The world profiles: the shipped field.yaml is the field world's defaults, and a scenario file
// with a mistake is refused with the key and the problem.
#include <gtest/gtest.h>

#include <string>

#include "colag/sim/mission/world_file.hpp"
#include "temp_file.hpp"

using namespace colag;

TEST(WorldProfile, TheShippedFieldFileIsTheFieldWorld) {
  sim::WorldProfile file, code = sim::field_world();
  std::string error;
  ASSERT_TRUE(mission::load_world_file(COLAG_CONFIG_DIR "/worlds/field.yaml", file, error))
      << error;
  EXPECT_EQ(file.wheels.scale_spread, code.wheels.scale_spread);
  EXPECT_EQ(file.wheels.slip_per_radps, code.wheels.slip_per_radps);
  EXPECT_EQ(file.wheels.slip_per_mps2, code.wheels.slip_per_mps2);
  EXPECT_EQ(file.wheels.yaw_rate_bias_radps, code.wheels.yaw_rate_bias_radps);
  EXPECT_EQ(file.lidar.range_sigma_m, code.lidar.range_sigma_m);
  EXPECT_EQ(file.lidar.dropout, code.lidar.dropout);
  EXPECT_EQ(file.camera.fov_half_angle_deg, code.camera.fov_half_angle_deg);
  EXPECT_EQ(file.camera.miss, code.camera.miss);
  EXPECT_EQ(file.camera.outlier, code.camera.outlier);
  EXPECT_EQ(file.camera.true_sigma_scale, code.camera.true_sigma_scale);
  EXPECT_EQ(file.camera.latency_ms, code.camera.latency_ms);
  EXPECT_EQ(file.camera.jitter_ms, code.camera.jitter_ms);
  EXPECT_NEAR(file.camera.sigma_yaw_rad, code.camera.sigma_yaw_rad, 1e-3);
  EXPECT_EQ(file.clocks.offset_s, code.clocks.offset_s);
  EXPECT_EQ(file.clocks.drift_ppm, code.clocks.drift_ppm);
}

TEST(WorldProfile, AFileStartsFromItsBaseAndSetsOnlyWhatItSays) {
  sim::WorldProfile w;
  std::string error;
  ASSERT_TRUE(mission::load_world_file(
      test::write_temp_file("ideal_plus.yaml", "base: ideal\ncamera: {miss: 0.3}\n"), w, error))
      << error;
  EXPECT_EQ(w.camera.miss, 0.3);
  EXPECT_EQ(w.wheels.scale_spread, 0.0);  // ideal
  EXPECT_EQ(w.camera.fov_half_angle_deg, 180.0);
  ASSERT_TRUE(mission::world_from_name("field", w, error));
  EXPECT_GT(w.wheels.scale_spread, 0.0);
}

TEST(WorldProfile, MistakesAreRefusedWithTheKeyAndTheProblem) {
  const struct {
    const char* text;
    const char* expect;
  } cases[] = {
      {"wheels: {scale: 0.05}\n", "wheels.scale: unknown key"},
      {"wheels: {scale_spread: 0.9}\n", "wheels.scale_spread: out of range"},
      {"camera: {miss: lots}\n", "camera.miss: expected"},
      {"base: moon\n", "base: expected ideal or field"},
      {"sensors: {}\n", "sensors: unknown key"},
      {"camera: [1, 2\n", ""},  // not YAML
  };
  for (const auto& c : cases) {
    sim::WorldProfile w;
    std::string error;
    EXPECT_FALSE(mission::load_world_file(test::write_temp_file("bad.yaml", c.text), w, error))
        << c.text;
    EXPECT_NE(error.find(c.expect), std::string::npos) << error;
    EXPECT_NE(error.find("bad.yaml"), std::string::npos) << error;
  }
  sim::WorldProfile w;
  std::string error;
  EXPECT_FALSE(mission::world_from_name("/nonexistent/world.yaml", w, error));
  EXPECT_NE(error.find("/nonexistent/world.yaml"), std::string::npos) << error;
}
