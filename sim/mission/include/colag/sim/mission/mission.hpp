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
#include "colag/sim/world/sim_world.hpp"
#include "colag/uav/uav_supervisor_task.hpp"
#include "colag/ugv/ugv_nav_task.hpp"

namespace colag::mission {

class Mission;

// Sees the mission every 100 ms of simulated time, after the robots ran (e.g. the MCAP
// recorder). Read-only: watching never changes the outcome.
class MissionWatcher {
 public:
  virtual void watch(const Mission& mission) = 0;

 protected:
  ~MissionWatcher() = default;
};

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
  void fly(MissionTrace* trace = nullptr, MissionWatcher* watcher = nullptr);
  // The metrics; completes `trace` (collisions, what the UAV never saw).
  MissionOutcome collect(MissionTrace* trace = nullptr) const;

  const platform::LockstepExecutor& executor() const;
  // What a watcher sees.
  TimePoint now() const { return executor().now(); }
  const MissionConfig& config() const;
  const sim::SimWorld& world() const;
  // UAV k (the first by default); null in the self-perception baseline or past the last.
  const uav::UavSupervisorTask* uav(std::size_t k = 0) const;
  std::size_t uav_count() const;
  std::size_t ugv_count() const;
  const ugv::UgvNavTask& ugv(std::size_t i) const;

 private:
  struct Parts;
  explicit Mission(std::unique_ptr<Parts> parts);
  std::unique_ptr<Parts> parts_;
};

// check, compose, fly, collect. Fails (with a message) only on a bad configuration or map file.
Result<MissionOutcome> run_mission(const MissionConfig& cfg, MissionTrace* trace = nullptr,
                                   std::string* error_out = nullptr,
                                   MissionWatcher* watcher = nullptr);

}  // namespace colag::mission
