#pragma once
// Writes a box world as a point cloud in the format of the paper's maps (PCD v0.7, ASCII, x y z):
// the ground on a 0.1 m grid over the arena plus a 3.5 m margin, at z = 0, and each box as a
// column of points on the 0.1 m grid of its footprint, every 0.1 m up to its height. Reading it
// back (load_pcd, box_world_from_points) gives the same boxes.
#include <string>

#include "colag/sim/world/box_world.hpp"

namespace colag::sim {

std::string to_pcd(const BoxWorld& world);
// False with `error` set when the file cannot be written.
bool save_pcd(const std::string& path, const BoxWorld& world, std::string& error);

}  // namespace colag::sim
