#pragma once
// Why a UGV stands still before its goal, in the parts a user asks about: waiting for the UAV's
// support, for another UGV, for a path, at start-up (no fleet time, no relative pose, no plan
// yet), in a fault, held by its operator (paused, aborted), or manoeuvring (turning on the spot,
// pulling away: driving, but slower than kStillSpeed). Every control period its wheels turn slower
// than kStillSpeed before its goal goes into exactly one part, so the parts sum to its waiting
// time, and the ground truth's "speed below kStillSpeed" agrees with it to within a control period
// per stop (the odometry's delay).
#include <array>
#include <cstdint>

#include "colag/common/time.hpp"
#include "colag/msg/ugv_status.hpp"

namespace colag::ugv {

enum class WaitPart : std::uint8_t {
  kSupport,
  kOtherUgv,
  kNoPath,
  kStartup,
  kFault,
  kManoeuvre,
  kOperator,
};
inline constexpr std::size_t kWaitParts = 7;
inline constexpr double kStillSpeed_mps = 0.05;

inline const char* to_string(WaitPart p) {
  switch (p) {
    case WaitPart::kSupport:
      return "support";
    case WaitPart::kOtherUgv:
      return "other_ugv";
    case WaitPart::kNoPath:
      return "no_path";
    case WaitPart::kStartup:
      return "startup";
    case WaitPart::kFault:
      return "fault";
    case WaitPart::kManoeuvre:
      return "manoeuvre";
    case WaitPart::kOperator:
      return "operator";
  }
  return "unknown";
}

// The part a stop in `mode` belongs to (`planned`: it has found a path before; `tracking`: it is
// following one). No path before the first one was found is start-up: the UAV has not mapped
// around it yet.
constexpr WaitPart wait_part(msg::UgvMode mode, msg::BlockedReason why, bool planned,
                             bool tracking) {
  switch (mode) {
    case msg::UgvMode::kWaitingForSupport:
    case msg::UgvMode::kUavUnavailable:  // waiting for the UAV to fly again
      return WaitPart::kSupport;
    case msg::UgvMode::kWaitingForRobot:
      return WaitPart::kOtherUgv;
    case msg::UgvMode::kNoPath:
      return planned ? WaitPart::kNoPath : WaitPart::kStartup;
    case msg::UgvMode::kFault:
      return WaitPart::kFault;
    case msg::UgvMode::kPaused:
    case msg::UgvMode::kAborted:
      return WaitPart::kOperator;
    case msg::UgvMode::kBlocked:
      switch (why) {
        case msg::BlockedReason::kNotCleared:
          return WaitPart::kSupport;
        case msg::BlockedReason::kRobotInTheWay:
          return WaitPart::kOtherUgv;
        case msg::BlockedReason::kNoPath:
          return WaitPart::kNoPath;
        case msg::BlockedReason::kNotLocalised:
        case msg::BlockedReason::kNone:
          return WaitPart::kStartup;
      }
      return WaitPart::kStartup;
    case msg::UgvMode::kWaitingForInit:
    case msg::UgvMode::kArrived:
      return WaitPart::kStartup;
    case msg::UgvMode::kDriving:
      if (tracking) return WaitPart::kManoeuvre;
      // Without a trajectory: its first plan, or a replan that failed.
      return planned ? WaitPart::kNoPath : WaitPart::kStartup;
  }
  return WaitPart::kStartup;
}

using WaitingParts = std::array<Duration, kWaitParts>;

// The support part, by what the UGV called the UAV for: ground its map does not know yet, its
// estimate too uncertain for the known obstacles along its path (or, already now, for those
// beside it), or a last fix at its goal. Waiting for support is put under the latest cause the
// collision prediction gave (before any, ground not known: the UAV has mapped nothing there).
enum class SupportCause : std::uint8_t {
  kUnknownGround,
  kNearObstacle,
  kUncertainNow,
  kGoalFix,
};
inline constexpr std::size_t kSupportCauses = 4;

inline const char* to_string(SupportCause c) {
  switch (c) {
    case SupportCause::kUnknownGround:
      return "unknown_ground";
    case SupportCause::kNearObstacle:
      return "near_obstacle";
    case SupportCause::kUncertainNow:
      return "uncertain_now";
    case SupportCause::kGoalFix:
      return "goal_fix";
  }
  return "unknown";
}

using SupportCauses = std::array<Duration, kSupportCauses>;

}  // namespace colag::ugv
