#pragma once
// Loads a PCD v0.7 point cloud (DATA ascii or binary; x, y, z fields of type F, size 4 or 8,
// among any others) and turns it into a box world: points above the ground are binned into
// 0.1 m columns, connected columns form one obstacle, and each obstacle becomes the bounding
// box of its columns up to its highest point (exact for the paper's box maps). Malformed
// files give an error that names the problem, never a crash.
#include <string>
#include <vector>

#include "colag/common/geometry.hpp"
#include "colag/common/status.hpp"
#include "colag/sim/world/box_world.hpp"

namespace colag::sim {

bool load_pcd(const std::string& path, std::vector<Vec3>& points, std::string& error);
bool parse_pcd(const std::string& bytes, std::vector<Vec3>& points, std::string& error);
BoxWorld box_world_from_points(const std::vector<Vec3>& points, double ground_z_m = 0.05,
                               double resolution_m = 0.1);

}  // namespace colag::sim
