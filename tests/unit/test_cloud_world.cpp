// Point clouds as the simulated world (issue 19, item 10): the ground is fitted, obstacles keep
// their real vertical extent and shape, and only what reaches the UGV's body band can be hit.
#include <gtest/gtest.h>

#include <random>

#include "colag/sim/world/cloud_world.hpp"
#include "colag/sim/world/lidar_simulator.hpp"

using namespace colag;
using namespace colag::sim;

namespace {

constexpr double kBandLow = 0.1, kBandHigh = 0.7;

// A 20 x 20 m ground on a 0.1 m grid at height `z` (+ Gaussian noise of `sigma`).
void add_ground(std::vector<Vec3>& pts, double z, double sigma = 0.0, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma > 0.0 ? sigma : 1.0);
  for (int j = -100; j <= 100; ++j) {
    for (int i = -100; i <= 100; ++i)
      pts.emplace_back(0.1 * i, 0.1 * j, z + (sigma > 0.0 ? noise(rng) : 0.0));
  }
}

// A solid box sampled as the paper's maps are: a point at each 0.1 m cell centre of its
// footprint, every 0.1 m from `base` (exclusive of the ground) up to `top`, over `z0`.
void add_box(std::vector<Vec3>& pts, Vec2 lo, Vec2 hi, double base, double top, double z0) {
  for (double y = lo.y() + 0.05; y < hi.y(); y += 0.1) {
    for (double x = lo.x() + 0.05; x < hi.x(); x += 0.1) {
      for (double z = std::max(base, 0.1); z <= top + 1e-9; z += 0.1)
        pts.emplace_back(x, y, z0 + z);
    }
  }
}

double band_clearance(const BoxWorld& w, const Vec2& p) {
  return w.clearance(p, kBandLow, kBandHigh);
}

}  // namespace

// The case: a ground plane at z = 0.1 m made the whole map one obstacle.
TEST(CloudWorld, AGroundAbove0IsFittedNotTakenForAnObstacle) {
  std::vector<Vec3> pts;
  add_ground(pts, 0.1);
  add_box(pts, Vec2(1.0, 1.0), Vec2(1.7, 1.7), 0.0, 0.6, 0.1);
  CloudWorldReport report;
  const BoxWorld w = box_world_from_points(pts, {}, &report);
  EXPECT_NEAR(report.ground.z_m, 0.1, 1e-6);
  ASSERT_EQ(w.boxes.size(), 1u);
  EXPECT_NEAR(w.boxes[0].height_m, 0.6, 1e-6);  // from the ground, not from z = 0
  EXPECT_NEAR(w.boxes[0].half_size.x(), 0.35, 1e-6);
  EXPECT_GT(band_clearance(w, Vec2(-5, -5)), 5.0);
}

// 2 cm of ground noise made ~700 obstacles lower than 0.1 m: none now, the boxes exactly.
TEST(CloudWorld, GroundNoiseMakesNoObstacles) {
  std::vector<Vec3> pts;
  add_ground(pts, 0.0, 0.02);
  add_box(pts, Vec2(1.0, 1.0), Vec2(1.7, 1.7), 0.0, 0.6, 0.0);
  add_box(pts, Vec2(-4.0, 2.0), Vec2(-3.1, 2.9), 0.0, 1.2, 0.0);
  CloudWorldReport report;
  const BoxWorld w = box_world_from_points(pts, {}, &report);
  EXPECT_NEAR(report.ground.sigma_m, 0.02, 0.004);
  ASSERT_EQ(w.boxes.size(), 2u);
  double tops = 0.0;
  for (const Box& b : w.boxes)
    tops += b.height_m;
  EXPECT_NEAR(tops, 1.8, 0.05);
}

// A slab at 1.5 m on two pillars (a bridge) was a wall: now the UGVs pass under the deck,
// the pillars stay obstacles, and the LiDAR still sees the deck.
TEST(CloudWorld, ABridgeDeckIsOverheadItsPillarsAreObstacles) {
  std::vector<Vec3> pts;
  add_ground(pts, 0.0);
  add_box(pts, Vec2(-3.0, -0.5), Vec2(-2.5, 0.5), 0.0, 1.5, 0.0);  // pillars
  add_box(pts, Vec2(2.5, -0.5), Vec2(3.0, 0.5), 0.0, 1.5, 0.0);
  add_box(pts, Vec2(-2.5, -0.5), Vec2(2.5, 0.5), 1.5, 1.6, 0.0);  // the deck between them
  CloudWorldReport report;
  const BoxWorld w = box_world_from_points(pts, {}, &report);
  EXPECT_GE(report.overhead_boxes, 1u);
  EXPECT_GT(band_clearance(w, Vec2(0.0, 0.0)), 2.0);     // under the middle of the deck: free
  EXPECT_LT(band_clearance(w, Vec2(-2.75, 0.0)), 1e-9);  // in a pillar
  EXPECT_LT(w.clearance(Vec2(0.0, 0.0)), 1e-9);          // every box: the deck is above
  // A ray from a UAV above the deck stops on it; one under it goes through.
  const Box* deck = nullptr;
  for (const Box& b : w.boxes) {
    if (b.base_m > kBandHigh) deck = &b;
  }
  ASSERT_NE(deck, nullptr);
  EXPECT_NEAR(ray_box(Vec3(0, 0, 5), Vec3(0, 0, -1), *deck), 5.0 - 1.6, 1e-6);
  EXPECT_LT(ray_box(Vec3(0, -3, 0.3), Vec3(0, 1, 0), *deck), 0.0);
}

// Walls keep their shape: a pen is a ring with free ground inside, not one filled box.
TEST(CloudWorld, APenStaysARing) {
  std::vector<Vec3> pts;
  add_ground(pts, 0.0);
  add_box(pts, Vec2(-1.1, -1.1), Vec2(1.1, -0.9), 0.0, 0.6, 0.0);
  add_box(pts, Vec2(-1.1, 0.9), Vec2(1.1, 1.1), 0.0, 0.6, 0.0);
  add_box(pts, Vec2(-1.1, -0.9), Vec2(-0.9, 0.9), 0.0, 0.6, 0.0);
  add_box(pts, Vec2(0.9, -0.9), Vec2(1.1, 0.9), 0.0, 0.6, 0.0);
  const BoxWorld w = box_world_from_points(pts);
  EXPECT_NEAR(band_clearance(w, Vec2(0, 0)), 0.9, 1e-6);
  EXPECT_LT(band_clearance(w, Vec2(1.0, 0.0)), 1e-9);
}

// Clutter lower than the band (kerbs, cables) is driven over; it is not an obstacle.
TEST(CloudWorld, ClutterBelowTheBandIsDroppedAndCounted) {
  std::vector<Vec3> pts;
  add_ground(pts, 0.0);
  for (int i = 0; i < 20; ++i)
    pts.emplace_back(-2.0 + 0.1 * i + 0.05, 3.05, 0.06);  // a 6 cm cable across the way
  CloudWorldReport report;
  const BoxWorld w = box_world_from_points(pts, {}, &report);
  EXPECT_TRUE(w.boxes.empty());
  EXPECT_EQ(report.clutter_columns, 20u);
}
