#pragma once
// A building floor instead of a field of boxes: the arena cut into a grid of rooms by thin walls
// (as tall as the UGVs and more), each wall between two rooms with one doorway at a random
// place along it, and a few boxes of furniture in the rooms, kept clear of the walls so that
// every doorway stays passable. The outside of the grid is open (the UGVs start and end outside
// it, as in the paper's layout). Host-side only (sim/).
#include <cstddef>
#include <cstdint>

#include "colag/common/status.hpp"
#include "colag/sim/world/box_world.hpp"

namespace colag::sim {

struct RoomGenConfig {
  int rooms_x = 3;  // rooms along x and along y
  int rooms_y = 3;
  Vec2 arena_half = Vec2::Constant(13.5);  // the building: [-x, x] x [-y, y]
  double wall_thickness_m = 0.2;
  double wall_height_m = 1.2;
  double door_m = 1.6;         // doorway width
  double door_margin_m = 0.6;  // doorways keep this far from a wall's ends
  std::size_t furniture = 16;  // boxes (the paper's sizes) spread over the rooms
  // From any wall and from each other: 1.4 m lets a UGV (0.25 m body) with its planner's 0.4 m
  // margin through every gap, so furniture never closes off a doorway or a corner.
  double furniture_clear_m = 1.4;
  std::uint64_t seed = 1;
};

// Fails (kInvalidArgument) when the rooms are too small for their doorways, or
// (kCapacityExceeded) when the furniture does not fit at that clearance.
Result<BoxWorld> generate_room_world(const RoomGenConfig& config);

}  // namespace colag::sim
