#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "colag/common/map_patch_codec.hpp"
#include "colag/uav/map_sharer.hpp"
#include "colag/uav/mapper.hpp"
#include "dense_scans.hpp"

using namespace colag;
using namespace colag::uav;

namespace {

// A map of the dense box world seen along x = 0.3 and from near the grid's east edge (x = 18,
// so that the map reaches the edge at x = 20).
std::unique_ptr<Mapper> mapped_world() {
  std::vector<Pose3> poses;
  poses.reserve(40);
  for (int k = 0; k < 30; ++k)
    poses.push_back({Vec3(0.3, 8.0 - 0.5 * k, 1.0), Quat::Identity()});
  for (int k = 0; k < 10; ++k)
    poses.push_back({Vec3(18.0, 2.0 - 0.5 * k, 1.0), Quat::Identity()});
  auto map = std::make_unique<Mapper>();
  test::scan_dense_map(poses, {map.get()});
  return map;
}

}  // namespace

// make_patch reads the band with vectorised loops over whole rows (or, at the grid's east edge,
// over the patch's width only); every cell of the patch must still be what classify() makes of
// its column voxel by voxel. Patches inside the map, at its east and west edges, moving and not.
TEST(MapSharer, EveryPatchCellIsTheBandClassificationOfItsColumn) {
  const auto map = mapped_world();
  MapSharer sharer;
  const GridGeometry2d g = map->geometry().layer();
  std::size_t counts[3] = {0, 0, 0};
  for (const auto& [position, speed] :
       std::vector<std::pair<Vec2, double>>{{Vec2(0.0, 4.0), 0.0},
                                            {Vec2(1.3, -3.7), 0.5},
                                            {Vec2(19.0, 0.0), 0.0},
                                            {Vec2(19.9, -1.5), 0.0},
                                            {Vec2(-19.5, 0.0), 0.0}}) {
    msg::MapPatch patch;
    ASSERT_TRUE(sharer.make_patch(*map, position, -M_PI / 2, speed, patch));
    PatchCells cells;
    ASSERT_TRUE(decode_patch(patch, cells));
    const CellIndex lo = g.cell_of(
        Vec2(patch.origin_x_m + 0.5 * g.resolution(), patch.origin_y_m + 0.5 * g.resolution()));
    std::size_t wrong = 0;
    for (int y = 0; y < cells.height; ++y) {
      for (int x = 0; x < cells.width; ++x) {
        const CellState want = sharer.classify(*map, lo.x + x, lo.y + y);
        wrong += cells.at(x, y) != want ? 1U : 0U;
        ++counts[static_cast<int>(want)];
      }
    }
    EXPECT_EQ(wrong, 0u) << "patch at " << position.transpose();
  }
  // The patches saw every kind of cell.
  EXPECT_GT(counts[static_cast<int>(CellState::kFree)], 1000u);
  EXPECT_GT(counts[static_cast<int>(CellState::kOccupied)], 50u);
  EXPECT_GT(counts[static_cast<int>(CellState::kUnknown)], 1000u);
}
