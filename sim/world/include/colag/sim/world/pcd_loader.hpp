#pragma once
// Loads a PCD v0.7 point cloud (DATA ascii or binary; x, y, z fields of type F, size 4 or 8,
// among any others); cloud_world.hpp turns it into boxes. Malformed files give an error that
// names the problem, never a crash.
#include <string>
#include <vector>

#include "colag/common/geometry.hpp"
#include "colag/common/status.hpp"

namespace colag::sim {

bool load_pcd(const std::string& path, std::vector<Vec3>& points, std::string& error);
bool parse_pcd(const std::string& bytes, std::vector<Vec3>& points, std::string& error);

}  // namespace colag::sim
