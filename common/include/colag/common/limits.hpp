#pragma once
// Every fixed capacity of ColAG-fw, in one place. Memory for all of them is reserved before a
// task's first step; nothing grows at run time. Change a number here and everything that
// depends on it (buffers, message sizes, IDL bounds via static_asserts) follows or fails to
// compile.
#include <cstddef>
#include <cstdint>

namespace colag::limits {

// --- Robots -----------------------------------------------------------------------------------
inline constexpr std::size_t kMaxUgvs = 32;
inline constexpr std::size_t kMaxUavs = 4;  // UAVs sharing the support of one fleet
inline constexpr std::size_t kMaxRobots = kMaxUgvs + kMaxUavs;
inline constexpr std::size_t kMaxSupportRequests = 64;  // live CollisionInfo requests at the UAV
inline constexpr std::size_t kMaxNearbyUgvs = 12;       // other UGVs the UAV relays to one UGV

// --- World grids (UAV 3-D map, UGV 2-D map) ----------------------------------------------------
inline constexpr double kGridResolution_m = 0.1;
// Each map is a window of this size that moves over the site with its robot (map_window.hpp);
// it starts at this origin, covering [-20, 20] x [-20, 20] x [0, 3] m.
inline constexpr double kGridOriginX_m = -20.0;
inline constexpr double kGridOriginY_m = -20.0;
inline constexpr double kGridOriginZ_m = 0.0;
inline constexpr int kGridCellsX = 400;
inline constexpr int kGridCellsY = 400;
inline constexpr int kGridCellsZ = 30;
inline constexpr std::size_t kGridCells2d = std::size_t{kGridCellsX} * kGridCellsY;
inline constexpr std::size_t kGridCells3d = kGridCells2d * kGridCellsZ;
// Sites span at most this far from the world frame's origin along x or y (goals beyond it are
// refused): far more than a battery's range, close enough that every float32 position on the
// wire stays exact to a millimetre.
inline constexpr double kMaxSiteHalf_m = 10'000.0;

// --- Map sharing -------------------------------------------------------------------------------
inline constexpr int kMaxPatchSideCells = 64;  // 6.4 m: the 5 m send box plus rounding margin
inline constexpr std::size_t kMaxPatchCells = std::size_t{kMaxPatchSideCells} * kMaxPatchSideCells;
inline constexpr std::size_t kMaxPatchBytes = kMaxPatchCells / 4;  // 2 bits per cell, worst case

// --- Planning ----------------------------------------------------------------------------------
inline constexpr std::size_t kMaxPathPoints = 2048;  // raw grid path
inline constexpr std::size_t kMaxWaypoints = 256;    // after smoothing
inline constexpr std::size_t kMaxRouteVias = 16;     // a mission's points passed before its goal
inline constexpr std::size_t kMaxTrajectorySamples = 1024;
inline constexpr std::size_t kMaxPredictionSteps = 256;  // collision-prediction ellipses

// --- Sensors -----------------------------------------------------------------------------------
inline constexpr std::size_t kMaxLidarBeams = 32;
inline constexpr std::size_t kMaxLidarColumns = 1200;  // 0.3 deg horizontal resolution
inline constexpr std::size_t kMaxLidarPoints = kMaxLidarBeams * kMaxLidarColumns;
// Voxels one ray's updates are held for while the mapper may still undo them (an inferred miss
// that meets an occupied voxel; see uav/mapper.hpp): a 15 m ray crosses at most 3 x 150.
inline constexpr std::size_t kMaxRayUndo = 512;
inline constexpr std::size_t kMaxRpeDetectionsPerFrame = kMaxUgvs;
inline constexpr std::size_t kMaxRpeTags = 2 * kMaxUgvs;  // tags the camera knows (2 per UGV)
inline constexpr std::size_t kUavOdometryHistory = 64;    // UGV side, for RPE time matching
inline constexpr std::size_t kCanRxQueue = 64;       // frames queued per simulated CAN endpoint
inline constexpr std::size_t kCanFilters = 8;        // kernel receive filters per SocketCAN bus
inline constexpr std::size_t kOdometryBacklog = 32;  // wheel samples awaiting the task's poll

// --- Estimation --------------------------------------------------------------------------------
inline constexpr std::size_t kEkfHistory = 64;       // UGV EKF odometry steps kept (1.28 s)
inline constexpr std::size_t kClockFilterBins = 32;  // clock-offset bins (8 s each: ~4 min)
inline constexpr std::size_t kClockStepRun = 4;      // unexplained exchanges held (step: 3)

// --- Runtime -----------------------------------------------------------------------------------
// A board runs a handful of tasks; the host simulator puts a whole fleet in one table: each
// UGV's 2 loops (3 with the self-perception baseline's LiDAR), each UAV's 4, and the world,
// transport, monitors and fault watches.
inline constexpr std::size_t kMaxTasksPerExecutor = 3 * kMaxUgvs + 4 * kMaxUavs + 8;
inline constexpr std::size_t kMaxSubscriptions = 8 * kMaxUgvs;         // per transport instance
inline constexpr std::size_t kLoopbackMaxInFlight = 16 * kMaxUgvs;     // samples held
inline constexpr std::size_t kLoopbackMaxDeliveries = 256 * kMaxUgvs;  // (sample, reader) pending
inline constexpr std::size_t kDefaultReaderDepth = 8;
inline constexpr std::size_t kLaneOutboxSamples = 8;  // one simulated robot's samples per instant
// The UAV's scheduling step publishes a nearby list and a patch for each UGV at once.
inline constexpr std::size_t kDdsOutboxDepth = 4 * kMaxUgvs;  // samples awaiting the writer thread
// DDS readers of one participant: a listener of every per-UGV topic reads each UGV's partition.
inline constexpr std::size_t kMaxDdsReaders = 8 * kMaxUgvs;
inline constexpr std::size_t kRos2CommandQueue = 8;  // ROS 2 commands awaiting a UGV's step

}  // namespace colag::limits
