#pragma once
#include <cstdint>

namespace colag {

// UGVs are numbered 0 .. limits::kMaxUgvs-1; the UAV has its own id space (normally just 0).
using RobotId = std::uint16_t;
inline constexpr RobotId kAnyRobot = 0xFFFF;  // subscription filter: every robot

}  // namespace colag
