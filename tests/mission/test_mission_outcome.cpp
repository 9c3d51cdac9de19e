// What a mission reports about a collision: when, where and with what, in words and in the JSON.
#include <gtest/gtest.h>

#include <memory>

#include <nlohmann/json.hpp>

#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/sim/mission/mission_outcome.hpp"
#include "colag/sim/world/sim_world.hpp"

using namespace colag;
using namespace std::chrono_literals;

TEST(MissionOutcome, ACollisionIsReportedWithWhenWhereAndWhat) {
  sim::BoxWorld world;
  world.boxes.push_back({Vec2(3.0, 0.0), Vec2(0.5, 0.5), 0.6});
  hal::scripted::ManualClock clock;
  auto sim = std::make_unique<sim::SimWorld>(sim::SimWorldConfig{}, world, clock);
  const int u = sim->add_ugv({Vec2(0, 0), 0.0});
  const int still = sim->add_ugv({Vec2(0, 3), 0.0});
  hal::can::CanDrive drive(sim->ugv_can(u), {}, {});
  for (int i = 0; i < 400; ++i) {  // 8 s at 0.5 m/s: straight into the box's face at x = 2.5
    clock.advance(20ms);
    (void)drive.command({clock.now(), 0.5, 0.0});
    sim->step(clock.now(), 0.02);
  }
  ASSERT_EQ(sim->collisions().size(), 1u);

  mission::MissionOutcome out;
  out.ugvs.resize(2);
  out.ugvs[0].id = u;
  out.ugvs[1].id = still;
  mission::summarise(*sim, out);
  const mission::UgvOutcome& hit = out.ugvs[0];
  EXPECT_TRUE(hit.collided);
  EXPECT_EQ(hit.collided_with, -1);
  EXPECT_NEAR(hit.collided_where.x(), 2.25, 0.05);  // its centre, a radius from the face
  EXPECT_NEAR(hit.collided_where.y(), 0.0, 1e-6);
  EXPECT_NEAR(hit.collided_at_s, to_seconds(sim->collisions()[0].at), 1e-9);
  EXPECT_GT(hit.collided_at_s, 4.0);
  EXPECT_LT(hit.collided_at_s, 6.0);
  EXPECT_NE(hit.end.find("collided with an obstacle at"), std::string::npos) << hit.end;
  EXPECT_FALSE(out.ugvs[1].collided);

  const auto j = nlohmann::json::parse(mission::to_json(out, false));
  const auto& c = j["ugvs"][0]["collision"];
  EXPECT_EQ(c["with"], "obstacle");
  EXPECT_NEAR(c["x_m"].get<double>(), hit.collided_where.x(), 1e-9);
  EXPECT_NEAR(c["t_s"].get<double>(), hit.collided_at_s, 1e-9);
  EXPECT_FALSE(j["ugvs"][1].contains("collision"));
  EXPECT_EQ(j["summary"]["collisions"], 1);
}
