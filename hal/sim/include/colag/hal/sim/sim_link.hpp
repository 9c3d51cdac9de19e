#pragma once
// SITL (software in the loop): the DDS link between colag_world (the simulated world as its own
// process) and the robots' "sim" HAL (idl/sim.idl). One participant on the sim domain — the
// robots' domain + 1 — so the simulator's traffic never mixes with the robot-to-robot topics,
// and network faults can be injected on the robots' traffic alone. A UGV's link reads only the
// CAN frames addressed to it (a topic filter; Cyclone applies a topic's filter to its writers
// too, hence one topic per direction).
#include <dds/dds.h>

#include <array>
#include <cstdint>

#include "colag/common/status.hpp"
#include "colag/msg/robot_id.hpp"

namespace colag::hal::sim {

enum class SimTopic : std::uint8_t {
  kCanToRobot,    // motor controller -> UGV
  kCanFromRobot,  // UGV -> motor controller
  kUavState,
  kSetpoint,
  kLidar,
  kRpe,
};
inline constexpr std::size_t kSimTopicCount = 6;

// The sim domain for a robot domain (Cyclone's port mapping keeps domains 250 ports apart).
inline std::uint32_t sim_domain_for(std::uint32_t robot_domain) {
  return robot_domain + 1;
}

class SimLink {
 public:
  enum class Side : std::uint8_t { kWorld, kUgv, kUav };

  SimLink() = default;
  ~SimLink();  // deletes the participant and everything under it
  SimLink(const SimLink&) = delete;
  SimLink& operator=(const SimLink&) = delete;

  // `robot`: the UGV's id (kUgv), for the CAN filter.
  Status init(std::uint32_t sim_domain, Side side, RobotId robot = 0);

  // The writer / reader of a topic (created at init for what the side uses; 0 otherwise).
  dds_entity_t writer(SimTopic t) const { return writers_[static_cast<std::size_t>(t)]; }
  dds_entity_t reader(SimTopic t) const { return readers_[static_cast<std::size_t>(t)]; }
  dds_return_t last_error() const { return last_error_; }

 private:
  Status fail(dds_return_t rc, const char* what);
  Status endpoints(SimTopic t, bool write, bool read);

  dds_entity_t participant_ = 0;
  std::array<dds_entity_t, kSimTopicCount> topics_{};
  std::array<dds_entity_t, kSimTopicCount> writers_{};
  std::array<dds_entity_t, kSimTopicCount> readers_{};
  RobotId robot_ = 0;  // a UGV's link: the only robot whose frames it reads
  dds_return_t last_error_ = 0;
};

}  // namespace colag::hal::sim
