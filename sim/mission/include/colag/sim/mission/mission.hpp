#pragma once
// A simulated ColAG mission on the host: the real UavSupervisorTask and UgvNavTasks, behind the
// real CAN drivers, against the simulated world, over the loopback transport, under the
// lock-step executor. Same configuration and seed => the same outcome, bit for bit (only the
// wall-clock figures differ). Read top to bottom: check, compose, fly, collect.
#include <memory>
#include <string>

#include "colag/common/status.hpp"
#include "colag/platform/lockstep_executor.hpp"
#include "colag/sim/mission/mission_config.hpp"
#include "colag/sim/mission/mission_outcome.hpp"

namespace colag::mission {

class Mission {
 public:
  // Builds the world, the robots and the executor table (each robot's loops from its own
  // schedule table, each UGV in a lane). Null with `error` set on a bad configuration or map.
  static std::unique_ptr<Mission> compose(const MissionConfig& cfg, std::string& error);
  ~Mission();
  Mission(const Mission&) = delete;
  Mission& operator=(const Mission&) = delete;

  // Runs until every UGV has arrived or stopped for good, or the configured time is up,
  // watching the truth every 100 ms; fills `trace` (optional) for the mission figure.
  void fly(MissionTrace* trace = nullptr);
  // The metrics; completes `trace` (collisions, what the UAV never saw).
  MissionOutcome collect(MissionTrace* trace = nullptr) const;

  const platform::LockstepExecutor& executor() const;

 private:
  struct Parts;
  explicit Mission(std::unique_ptr<Parts> parts);
  std::unique_ptr<Parts> parts_;
};

// check, compose, fly, collect. Fails (with a message) only on a bad configuration or map file.
Result<MissionOutcome> run_mission(const MissionConfig& cfg, MissionTrace* trace = nullptr,
                                   std::string* error_out = nullptr);

}  // namespace colag::mission
