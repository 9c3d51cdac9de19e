#include <gtest/gtest.h>

#include <memory>

#include "colag/common/map_store.hpp"
#include "colag/common/random.hpp"
#include "map_fixtures.hpp"

using namespace colag;

namespace {

// Square-to-square distance between two cells, in metres.
double gap_m(CellIndex a, CellIndex b) {
  const double gx = std::max(0, std::abs(a.x - b.x) - 1), gy = std::max(0, std::abs(a.y - b.y) - 1);
  return 0.1 * std::sqrt(gx * gx + gy * gy);
}

class MapStoreTest : public ::testing::Test {
 protected:
  std::unique_ptr<MapStore> map = std::make_unique<MapStore>();  // ~1.5 MB: not on the stack
  const GridGeometry2d g = map->geometry();                      // a copy: tests replace the map
  // Random patches in the 4.4 m square from (x0, y0), then every cell's views against a
  // recomputation from the cell states.
  void check_against_recomputation(double x0, double y0);
};

}  // namespace

TEST_F(MapStoreTest, BeforeAnyDataEverythingIsUnknownBlockedForPredictionFreeForPlanning) {
  for (const Vec2& p : {Vec2(0, 0), Vec2(10.3, -7.9), Vec2(-19.95, 19.95)}) {
    EXPECT_EQ(map->state(g.cell_of(p)), CellState::kUnknown);
    EXPECT_TRUE(map->predict_blocked(p));
    EXPECT_FALSE(map->plan_blocked(p));
  }
  EXPECT_TRUE(map->plan_blocked(Vec2(25, 0)));  // outside the grid
  EXPECT_TRUE(map->predict_blocked(Vec2(0, -21)));
}

TEST_F(MapStoreTest, AWholeMapOfFreeCellsUnblocksEveryCellUpToTheEdges) {
  // The initial unknown counts (computed, not stamped) must fall to exactly zero everywhere,
  // along the grid's edges and in its corners too.
  const double lo = g.origin_x() + 0.05, hi = g.origin_x() + g.cells_x() * 0.1 - 0.05;
  ASSERT_TRUE(test::fill_map(*map, lo, lo, hi, hi, [](const Vec2&) { return CellState::kFree; }));
  for (int y = 0; y < g.cells_y(); ++y) {
    for (int x = 0; x < g.cells_x(); ++x)
      ASSERT_FALSE(map->predict_blocked(CellIndex{x, y})) << x << "," << y;
  }
}

TEST(MapStoreDiscs, EveryCountFitsInItsEightBits) {
  // A cell's count is how many occupied (or unknown) cells its disc holds: 8 bits each, so the
  // largest disc must hold fewer than 256 cells, and a larger radius is clamped to it.
  EXPECT_LT(MapStore::disc_cells(100.0), 256);
  EXPECT_EQ(MapStore::disc_cells(100.0),
            MapStore::disc_cells(MapStore::kMaxInflationCells * limits::kGridResolution_m));
  EXPECT_GT(MapStore::disc_cells(0.4), MapStore::disc_cells(0.25));
  EXPECT_EQ(MapStore::disc_cells(0.0), 9);  // the cell and its 8 neighbours (any overlap)
}

TEST_F(MapStoreTest, MergesAPatchAndInflatesBothViews) {
  const Vec2 obstacle(0.05, 0.05);  // the centre of cell (200, 200)
  ASSERT_TRUE(test::fill_map(*map, -3, -3, 3, 3, [&](const Vec2& p) {
    return (p - obstacle).norm() < 0.01 ? CellState::kOccupied : CellState::kFree;
  }));
  const CellIndex o = g.cell_of(obstacle);
  EXPECT_EQ(map->state(o), CellState::kOccupied);
  EXPECT_EQ(map->state(g.cell_of(Vec2(1, 1))), CellState::kFree);
  // Every cell around: blocked exactly when its square is within the radius of the obstacle's.
  for (int dy = -8; dy <= 8; ++dy) {
    for (int dx = -8; dx <= 8; ++dx) {
      const CellIndex c{o.x + dx, o.y + dy};
      EXPECT_EQ(map->plan_blocked(c), gap_m(c, o) <= 0.4 + 1e-9) << dx << "," << dy;
      EXPECT_EQ(map->predict_blocked(c), gap_m(c, o) <= 0.25 + 1e-9) << dx << "," << dy;
    }
  }
  // Unknown beyond the patch still blocks prediction near the patch border, not planning.
  EXPECT_TRUE(map->predict_blocked(Vec2(2.95, 0)));
  EXPECT_FALSE(map->predict_blocked(Vec2(2.5, 0)));
  EXPECT_FALSE(map->plan_blocked(Vec2(2.95, 0)));
}

// Two UAVs' patches: what one knows, the other's unknown does not erase; a UAV may take back its
// own word, and either may change a known cell to another known state.
TEST_F(MapStoreTest, AUavsUnknownCellsDoNotEraseWhatAnotherUavMadeKnown) {
  const auto all = [](CellState s) { return [s](const Vec2&) { return s; }; };
  ASSERT_TRUE(test::fill_map(*map, 0, 0, 2, 2, all(CellState::kFree), 0));
  ASSERT_TRUE(test::fill_map(*map, 1, 0, 3, 2, all(CellState::kUnknown), 1));  // UAV 1: no idea
  EXPECT_EQ(map->state(g.cell_of(Vec2(1.5, 1))), CellState::kFree);            // UAV 0's stands
  EXPECT_EQ(map->state(g.cell_of(Vec2(2.5, 1))), CellState::kUnknown);
  EXPECT_FALSE(map->predict_blocked(Vec2(1.0, 1.0)));
  ASSERT_TRUE(test::fill_map(*map, 1, 0, 2, 2, all(CellState::kOccupied), 1));  // UAV 1 sees it
  EXPECT_EQ(map->state(g.cell_of(Vec2(1.5, 1))), CellState::kOccupied);
  ASSERT_TRUE(test::fill_map(*map, 1, 0, 2, 2, all(CellState::kUnknown), 1));  // and takes it back
  EXPECT_EQ(map->state(g.cell_of(Vec2(1.5, 1))), CellState::kUnknown);
  ASSERT_TRUE(test::fill_map(*map, 0, 0, 1, 2, all(CellState::kUnknown), 0));  // UAV 0 too
  EXPECT_EQ(map->state(g.cell_of(Vec2(0.5, 1))), CellState::kUnknown);
}

// Inside the grid and at its corner, where the inflation discs are cut by the edges.
TEST_F(MapStoreTest, IncrementalViewsEqualARecomputationAfterRandomPatches) {
  for (const double corner : {-2.0, -20.0}) {
    SCOPED_TRACE(corner);
    map = std::make_unique<MapStore>(MapStoreConfig{.clearance_m = 0.7});
    check_against_recomputation(corner, corner);
  }
}

void MapStoreTest::check_against_recomputation(double x0, double y0) {
  Rng rng(3);
  for (int round = 0; round < 30; ++round) {
    const double px = x0 + 0.1 * static_cast<double>(rng.below(20)),
                 py = y0 + 0.1 * static_cast<double>(rng.below(20));
    const double size = 0.1 * static_cast<double>(5 + rng.below(20));
    ASSERT_TRUE(test::fill_map(*map, px, py, px + size, py + size, [&](const Vec2&) {
      const double u = rng.uniform();
      return u < 0.6 ? CellState::kFree : (u < 0.85 ? CellState::kOccupied : CellState::kUnknown);
    }));
  }
  const CellIndex c0 = g.cell_of(Vec2(x0 - 1, y0 - 1)), c1 = g.cell_of(Vec2(x0 + 5, y0 + 5));
  for (int y = c0.y; y <= c1.y; ++y) {
    for (int x = c0.x; x <= c1.x; ++x) {
      if (!g.contains(CellIndex{x, y})) continue;
      bool plan = false, predict = false, band = false;
      for (int yy = y - 8; yy <= y + 8; ++yy) {
        for (int xx = x - 8; xx <= x + 8; ++xx) {
          if (!g.contains(CellIndex{xx, yy})) continue;  // no cell there: neither view counts it
          const CellState s = map->state({xx, yy});
          const double d = gap_m({x, y}, {xx, yy});
          plan |= s == CellState::kOccupied && d <= 0.4 + 1e-9;
          predict |= s != CellState::kFree && d <= 0.25 + 1e-9;
          band |= s == CellState::kOccupied && d <= 0.7 + 1e-9;
        }
      }
      ASSERT_EQ(map->in_clearance_band_at(g.index({x, y})), band) << x << "," << y;
      ASSERT_EQ(map->plan_blocked(CellIndex{x, y}), plan) << x << "," << y;
      ASSERT_EQ(map->predict_blocked(CellIndex{x, y}), predict) << x << "," << y;
    }
  }
}

TEST_F(MapStoreTest, RejectsEveryMalformedPatchWithoutTouchingTheMap) {
  PatchCells cells;
  cells.width = cells.height = 10;  // all free
  msg::MapPatch good;
  ASSERT_TRUE(encode_patch(cells, good));
  good.resolution_m = 0.1;
  good.origin_x_m = 1.0;
  good.origin_y_m = 1.0;

  const auto rejected = [&](msg::MapPatch p, const char* why) {
    const auto before = map->counters().patches_rejected;
    EXPECT_FALSE(map->apply(p)) << why;
    EXPECT_EQ(map->counters().patches_rejected, before + 1) << why;
    EXPECT_EQ(map->state(g.cell_of(Vec2(1.05, 1.05))), CellState::kUnknown) << why;
  };
  msg::MapPatch p = good;
  p.resolution_m = 0.2;
  rejected(p, "resolution");
  p = good;
  p.resolution_m = std::numeric_limits<double>::quiet_NaN();
  rejected(p, "NaN resolution");
  p = good;
  p.origin_x_m = std::numeric_limits<double>::infinity();
  rejected(p, "infinite origin");
  p = good;
  p.origin_y_m = 1.03;
  rejected(p, "origin off the grid");
  p = good;
  p.origin_x_m = 20.0;  // starts at the edge: wholly outside
  rejected(p, "outside");
  p = good;
  p.origin_x_m = -1e300;
  rejected(p, "far outside");
  p = good;
  p.width_cells = 11;  // payload no longer matches the size
  rejected(p, "size/payload mismatch");
  p = good;
  p.width_cells = 0;
  rejected(p, "zero width");
  p = good;
  p.data.count = 0;
  rejected(p, "empty payload");
  EXPECT_EQ(map->counters().patches_applied, 0u);
  EXPECT_TRUE(map->apply(good));
  EXPECT_EQ(map->state(g.cell_of(Vec2(1.05, 1.05))), CellState::kFree);
  // Past the edge: the 5 columns inside are applied, nothing else happens.
  p = good;
  p.origin_x_m = 19.5;
  p.origin_y_m = -20.5;  // and 5 rows below the bottom edge
  EXPECT_TRUE(map->apply(p));
  EXPECT_EQ(map->state(g.cell_of(Vec2(19.95, -19.95))), CellState::kFree);
  EXPECT_EQ(map->state(g.cell_of(Vec2(19.55, -19.55))), CellState::kFree);
  EXPECT_EQ(map->state(g.cell_of(Vec2(19.45, -19.55))), CellState::kUnknown);
  EXPECT_EQ(map->state(g.cell_of(Vec2(19.55, -19.45))), CellState::kUnknown);
  EXPECT_EQ(map->counters().cells_changed, 100u + 25u);
}

TEST(MapStoreOptions, WhenUnknownDoesNotBlockOnlyOccupiedCellsBlockPrediction) {
  MapStoreConfig cfg;
  cfg.unknown_blocks_prediction = false;  // a robot that sees for itself
  auto map = std::make_unique<MapStore>(cfg);
  EXPECT_FALSE(map->predict_blocked(Vec2(0.0, 0.0)));  // unknown, and that is fine
  ASSERT_TRUE(test::fill_map(*map, -2, -2, 2, 2, [](const Vec2& p) {
    return (p - Vec2(0.05, 0.05)).norm() < 0.01 ? CellState::kOccupied : CellState::kUnknown;
  }));
  EXPECT_TRUE(map->predict_blocked(Vec2(0.25, 0.05)));
  EXPECT_FALSE(map->predict_blocked(Vec2(1.0, 1.0)));
  EXPECT_FALSE(
      map->near_unknown_at(map->geometry().index(map->geometry().cell_of(Vec2(1.0, 1.0)))));
}

// The window moves over a larger site: what it keeps, and both views, are exactly those of a map
// that was at the new place from the start and received the same patches (each cell of the new
// window compared, by world position).
TEST(MapStoreWindow, AMovedWindowIsTheMapThatWasThereFromTheStart) {
  const MapStoreConfig config{.clearance_m = 0.6};
  const auto moved = std::make_unique<MapStore>(config);
  const auto fresh = std::make_unique<MapStore>(config);
  const Vec2 to(-20.0 + 7.3, -20.0 - 12.0);  // +73 and -120 cells
  ASSERT_TRUE(fresh->move_to(to));
  Rng rng(5);
  const auto random_state = [&](const Vec2&) {
    const double u = rng.uniform();
    return u < 0.1 ? CellState::kOccupied : u < 0.8 ? CellState::kFree : CellState::kUnknown;
  };
  // The same random cells for both (the same seed), in a square both windows cover...
  Rng again = rng;
  ASSERT_TRUE(test::fill_map(*moved, -12.65, -19.95, 4.05, -4.05, random_state));
  rng = again;
  ASSERT_TRUE(test::fill_map(*fresh, -12.65, -19.95, 4.05, -4.05, random_state));
  // ...and some only the old window covers (gone after the move).
  ASSERT_TRUE(test::fill_map(*moved, 8.0, 8.0, 19.0, 19.0,
                             [](const Vec2&) { return CellState::kOccupied; }));
  ASSERT_TRUE(moved->move_to(to + Vec2(1e-9, -1e-9)));  // a rounding off the lattice is fine
  const GridGeometry2d& g = moved->geometry();
  EXPECT_NEAR(g.origin_x(), to.x(), 1e-12);
  EXPECT_NEAR(g.origin_y(), to.y(), 1e-12);
  int occupied = 0;
  for (int y = 0; y < g.cells_y(); ++y) {
    for (int x = 0; x < g.cells_x(); ++x) {
      const Vec2 p = g.center_of({x, y});
      const CellIndex f = fresh->geometry().cell_of(p);
      ASSERT_EQ(moved->state(CellIndex{x, y}), fresh->state(f)) << x << "," << y;
      ASSERT_EQ(moved->plan_blocked(CellIndex{x, y}), fresh->plan_blocked(f)) << x << "," << y;
      ASSERT_EQ(moved->predict_blocked(CellIndex{x, y}), fresh->predict_blocked(f))
          << x << "," << y;
      ASSERT_EQ(moved->near_occupied_at(g.index({x, y})),
                fresh->near_occupied_at(fresh->geometry().index(f)));
      ASSERT_EQ(moved->in_clearance_band_at(g.index({x, y})),
                fresh->in_clearance_band_at(fresh->geometry().index(f)));
      occupied += moved->state(CellIndex{x, y}) == CellState::kOccupied ? 1 : 0;
    }
  }
  EXPECT_GT(occupied, 1000);  // the kept part is not empty
  // The old window's far corner is outside now: unknown and blocked.
  EXPECT_EQ(moved->state(moved->geometry().cell_of(Vec2(15, 15))), CellState::kUnknown);
  EXPECT_TRUE(moved->plan_blocked(Vec2(15, 15)));
  // A patch where the window is now applies there.
  ASSERT_TRUE(test::fill_map(*moved, -12.0, -30.0, -10.0, -28.0,
                             [](const Vec2&) { return CellState::kFree; }));
  EXPECT_EQ(moved->state(moved->geometry().cell_of(Vec2(-11, -29))), CellState::kFree);
}

TEST(MapStoreWindow, MovesBackAndForthFarAwayAndRefusesOffTheLattice) {
  const auto map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*map, -5, -5, 5, 5, [](const Vec2&) { return CellState::kFree; }));
  // Off the lattice, or not finite: refused, nothing changes.
  EXPECT_EQ(map->move_to(Vec2(-19.95, -20.0)).code(), Errc::kInvalidArgument);
  EXPECT_EQ(map->move_to(Vec2(std::nan(""), 0.0)).code(), Errc::kInvalidArgument);
  EXPECT_EQ(map->state(map->geometry().cell_of(Vec2(0, 0))), CellState::kFree);
  // There and back: what stayed inside throughout is kept.
  ASSERT_TRUE(map->move_to(Vec2(-22.0, -17.0)));
  ASSERT_TRUE(map->move_to(Vec2(-20.0, -20.0)));
  EXPECT_EQ(map->state(map->geometry().cell_of(Vec2(0, 0))), CellState::kFree);
  EXPECT_FALSE(map->predict_blocked(Vec2(0, 0)));
  // Further than its own size: everything unknown (and blocked for prediction), planning free.
  ASSERT_TRUE(map->move_to(Vec2(480.0, -20.0)));
  EXPECT_EQ(map->state(map->geometry().cell_of(Vec2(500, 0))), CellState::kUnknown);
  EXPECT_TRUE(map->predict_blocked(Vec2(500, 0)));
  EXPECT_FALSE(map->plan_blocked(Vec2(500, 0)));
  EXPECT_TRUE(map->plan_blocked(Vec2(0, 0)));  // outside now
}
