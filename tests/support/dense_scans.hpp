#pragma once
// Test helper: the UAV's map of the dense box world (80 boxes, the default seed) built by the
// real LiDAR simulator and the real mapper.
#include <initializer_list>
#include <memory>
#include <vector>

#include "colag/sim/world/lidar_simulator.hpp"
#include "colag/uav/mapper.hpp"

namespace colag::test {

// Scans of the dense map from each pose, each inserted into every map given.
inline void scan_dense_map(const std::vector<Pose3>& poses,
                           std::initializer_list<uav::Mapper*> maps) {
  sim::MapGenConfig gen;
  gen.boxes = 80;
  const sim::BoxWorld world = sim::generate_box_world(gen).value();
  auto lidar = std::make_unique<sim::LidarSimulator>();
  for (const Pose3& pose : poses) {
    std::span<const hal::LidarPoint> points, misses;
    lidar->scan(world, pose, points, misses);
    for (uav::Mapper* map : maps)
      map->insert_scan(pose, {TimePoint{}, 8.0F, points, misses});
  }
}

}  // namespace colag::test
