#include "colag/sim/mission/mission_outcome.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "colag/sim/world/sim_world.hpp"

namespace colag::mission {

namespace {

const char* doing(msg::UgvMode m) {
  switch (m) {
    case msg::UgvMode::kWaitingForInit:
      return "still waiting for its first relative pose";
    case msg::UgvMode::kDriving:
      return "still driving";
    case msg::UgvMode::kWaitingForSupport:
      return "waiting for support";
    case msg::UgvMode::kArrived:
      return "arrived";
    case msg::UgvMode::kNoPath:
      return "finding no path to its goal";
    case msg::UgvMode::kFault:
      return "in a fault (motors stopped)";
    case msg::UgvMode::kBlocked:
      return "blocked";
    case msg::UgvMode::kWaitingForRobot:
      return "waiting for another UGV";
    case msg::UgvMode::kUavUnavailable:
      return "stopped: the UAV's flight controller left the mission";
    case msg::UgvMode::kPaused:
      return "paused by its operator";
    case msg::UgvMode::kAborted:
      return "its mission aborted by its operator";
  }
  return "in an unknown mode";
}

// `time_limit_s`: the limit that ended the mission, or NaN if every UGV had finished before it.
std::string end_of(const UgvOutcome& o, double time_limit_s) {
  char text[256];
  if (o.collided) {
    char with[32] = "an obstacle";
    if (o.collided_with >= 0) std::snprintf(with, sizeof with, "UGV %d", o.collided_with);
    std::snprintf(text, sizeof text,
                  "collided with %s at %.1f s at (%.2f, %.2f); %.2f m from its goal", with,
                  o.collided_at_s, o.collided_where.x(), o.collided_where.y(), o.goal_distance_m);
  } else if (o.reached) {
    std::snprintf(text, sizeof text, "reached its goal");
  } else if (o.final_mode == msg::UgvMode::kArrived) {
    std::snprintf(text, sizeof text,
                  "stopped %.2f m from its goal, believing it had arrived (its estimate was off)",
                  o.goal_distance_m);
  } else {
    char when[64] = "the mission ended";
    if (std::isfinite(time_limit_s))
      std::snprintf(when, sizeof when, "the time limit (%.0f s) ended the mission", time_limit_s);
    std::snprintf(text, sizeof text, "%s when %s, %.2f m from its goal",
                  o.final_mode == msg::UgvMode::kBlocked
                      ? standing_reason(o.final_mode, o.blocked_reason).c_str()
                      : doing(o.final_mode),
                  when, o.goal_distance_m);
  }
  std::string end = text;
  if (!o.reached && o.blocked_s > 0.0) {
    std::snprintf(text, sizeof text, "; blocked %.0f s in all (%s)", o.blocked_s,
                  to_string(o.blocked_reason));
    end += text;
  }
  return end;
}

// Bytes per second by DDS topic name (the topics that carried any).
nlohmann::ordered_json by_topic(const std::array<double, msg::kTopicCount>& bytes_per_s) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < msg::kTopicCount; ++k) {
    if (bytes_per_s[k] > 0.0) j[msg::kTopicTable[k].name] = bytes_per_s[k];
  }
  return j;
}

}  // namespace

std::string standing_reason(msg::UgvMode mode, msg::BlockedReason blocked) {
  if (mode == msg::UgvMode::kBlocked) return std::string("blocked (") + to_string(blocked) + ")";
  if (mode == msg::UgvMode::kWaitingForInit) return "waiting for its first relative pose";
  return doing(mode);
}

void summarise(const sim::SimWorld& world, MissionOutcome& out) {
  double reach_sum = 0.0;
  int reached = 0;
  const auto n = static_cast<double>(out.ugvs.size());
  for (UgvOutcome& o : out.ugvs) {
    o.traj_length_m = world.ugv(o.id).travelled_m();
    o.min_clearance_m = world.min_clearance_m(o.id);
    o.goal_distance_m = (world.ugv(o.id).pose().p - ugv_goal(out.config, o.id)).norm();
    for (const auto& c : world.collisions()) {
      if (o.collided || (c.ugv != o.id && c.other_ugv != o.id)) continue;
      o.collided = true;
      o.collided_at_s = to_seconds(c.at);
      o.collided_where = c.where;
      o.collided_with = c.ugv == o.id ? c.other_ugv : c.ugv;
    }
    if (o.reached) {
      reach_sum += o.reach_time_s;
      ++reached;
    }
    out.waiting_time_s += o.stopped_s / n;
    out.max_waiting_time_s = std::max(out.max_waiting_time_s, o.stopped_s);
    for (std::size_t k = 0; k < ugv::kSupportCauses; ++k)
      out.support_causes_s[k] += o.support_causes[k] / n;
    out.nees_mean += o.nees_mean / n;
    out.bytes_in_per_ugv_per_s += o.bytes_in_per_s / n;
    for (std::size_t k = 0; k < msg::kTopicCount; ++k)
      out.bytes_in_per_ugv_by_topic_per_s[k] += o.bytes_in_by_topic_per_s[k] / n;
    out.ugv_traj_length_m += o.traj_length_m / n;
  }
  // The mission runs until every UGV reached, collided or is gone for good, or until its time
  // limit: one still on its way at the limit was stopped by the limit, not by the firmware.
  out.time_limit_reached = out.sim_time_s >= out.config.max_time_s - 1e-6 &&
                           std::any_of(out.ugvs.begin(), out.ugvs.end(), [](const UgvOutcome& o) {
                             return !o.reached && !o.collided;
                           });
  for (UgvOutcome& o : out.ugvs) {
    o.end = end_of(o, out.time_limit_reached ? out.config.max_time_s
                                             : std::numeric_limits<double>::quiet_NaN());
  }
  out.reach_time_s = reached > 0 ? reach_sum / reached : -1.0;
  out.reach_missing = static_cast<int>(out.ugvs.size()) - reached;
  out.all_reached = reached == static_cast<int>(out.ugvs.size());
  out.collisions = static_cast<int>(world.collisions().size());
}

namespace {
nlohmann::ordered_json support_causes(const std::array<double, ugv::kSupportCauses>& s) {
  nlohmann::ordered_json j;
  for (std::size_t k = 0; k < ugv::kSupportCauses; ++k)
    j[ugv::to_string(static_cast<ugv::SupportCause>(k))] = s[k];
  return j;
}
}  // namespace

std::string to_json(const MissionOutcome& o, bool include_wall_time) {
  nlohmann::ordered_json j;
  j["seed"] = o.config.seed;
  j["max_time_s"] = o.config.max_time_s;
  if (o.config.uavs > 1) j["uavs"] = o.config.uavs;  // one UAV: as before (the paper's)
  if (o.config.faults.uav_lost_at_s >= 0.0) {
    j["uav_lost_at_s"] = o.config.faults.uav_lost_at_s;
    j["uav_lost_id"] =
        o.config.faults.uav_lost_id >= 0 ? o.config.faults.uav_lost_id : o.config.uavs - 1;
  }
  if (o.config.faults.kill_ugv >= 0) {
    const FaultConfig& f = o.config.faults;
    j["kill_ugv"] = {{"id", f.kill_ugv}, {"at_s", f.kill_ugv_at_s}};
    if (f.restart_after_s >= 0.0) j["kill_ugv"]["restart_after_s"] = f.restart_after_s;
  }
  if (o.config.faults.any()) {
    const FaultConfig& f = o.config.faults;
    j["faults"] = {{"loss", f.loss},
                   {"latency_ms", f.latency_ms},
                   {"jitter_ms", f.jitter_ms},
                   {"blackout_s", {f.blackout.from_s, f.blackout.to_s}},
                   {"uav_blackout_s", {f.uav_blackout.from_s, f.uav_blackout.to_s}},
                   {"rpe_blackout_s", {f.rpe_blackout.from_s, f.rpe_blackout.to_s}},
                   {"odom_bias", f.odom_bias}};
  }
  if (o.config.clocks.any()) {
    const ClockConfig& c = o.config.clocks;
    j["clocks"] = {{"offset_s", c.offset_s}, {"drift_ppm", c.drift_ppm}};
    if (c.step_at_s >= 0.0) j["clocks"]["uav_step"] = {{"at_s", c.step_at_s}, {"by_s", c.step_s}};
  }
  j["world"] = o.config.world.name;
  j["ugv_base"] = hal::can::to_string(o.config.ugv_base);
  j["scenario"] = o.config.scenario == "file" ? o.config.map_file : o.config.scenario;
  if (!o.config.scenario_file.empty()) j["scenario_file"] = o.config.scenario_file;
  j["ablation"] = to_string(o.config.ablation);
  j["self_perception"] = o.config.self_perception;
  if (!o.warnings.empty()) j["warnings"] = o.warnings;
  nlohmann::ordered_json ugvs = nlohmann::ordered_json::array();
  for (const UgvOutcome& u : o.ugvs) {
    nlohmann::ordered_json ju;
    ju["id"] = u.id;
    ju["reached"] = u.reached;
    ju["collided"] = u.collided;
    ju["reach_time_s"] =
        u.reached ? nlohmann::ordered_json(u.reach_time_s) : nlohmann::ordered_json(nullptr);
    ju["stopped_s"] = u.stopped_s;
    ju["stops"] = u.stops;
    ju["waiting_time_s"] = u.waiting_time_s;
    nlohmann::ordered_json parts;
    for (std::size_t k = 0; k < ugv::kWaitParts; ++k)
      parts[ugv::to_string(static_cast<ugv::WaitPart>(k))] = u.waiting_parts[k];
    ju["waiting_parts"] = parts;
    ju["support_causes"] = support_causes(u.support_causes);
    ju["nees_mean"] = u.nees_mean;
    nlohmann::ordered_json cal;
    const char* const cal_names[kCalibrationDim] = {"scale", "turn_scale", "drift_per_m",
                                                    "drift_per_s", "slip_per_radps"};
    for (std::size_t k = 0; k < u.calibration.size(); ++k) {
      const double truth = u.calibration_true[k];
      cal[cal_names[k]] = {{"learnt", u.calibration[k]},
                           {"sigma", u.calibration_sigma[k]},
                           {"true", std::isfinite(truth) ? nlohmann::ordered_json(truth)
                                                         : nlohmann::ordered_json(nullptr)}};
    }
    ju["calibration"] = cal;
    if (o.config.clocks.any()) {
      ju["clock_steps"] = u.clock_steps;
      ju["clock_error_s"] = u.clock_error_s;
    }
    ju["blocked_s"] = u.blocked_s;
    if (u.blocked_s > 0.0) ju["blocked_reason"] = to_string(u.blocked_reason);
    ju["traj_length_m"] = u.traj_length_m;
    ju["min_clearance_m"] = u.min_clearance_m;
    if (u.collided) {
      ju["collision"] = {{"t_s", u.collided_at_s},
                         {"x_m", u.collided_where.x()},
                         {"y_m", u.collided_where.y()},
                         {"with", u.collided_with >= 0 ? nlohmann::ordered_json(u.collided_with)
                                                       : nlohmann::ordered_json("obstacle")}};
    }
    ju["support_requests"] = u.support_requests;
    ju["bytes_in_per_s"] = u.bytes_in_per_s;
    ju["bytes_in_by_topic"] = by_topic(u.bytes_in_by_topic_per_s);
    ju["goal_distance_m"] = u.goal_distance_m;
    ju["end"] = u.end;
    ugvs.push_back(ju);
  }
  j["ugvs"] = ugvs;
  nlohmann::ordered_json s;
  s["reach_time_s"] = o.reach_time_s >= 0.0 ? nlohmann::ordered_json(o.reach_time_s)
                                            : nlohmann::ordered_json(nullptr);
  s["reach_missing"] = o.reach_missing;
  s["waiting_time_s"] = o.waiting_time_s;
  s["max_waiting_time_s"] = o.max_waiting_time_s;
  s["support_causes_s"] = support_causes(o.support_causes_s);
  s["ugv_traj_length_m"] = o.ugv_traj_length_m;
  s["uav_traj_length_m"] = o.uav_traj_length_m;
  if (o.config.uavs > 1) s["uav_min_separation_m"] = o.uav_min_separation_m;
  s["nees_mean"] = o.nees_mean;
  s["bytes_in_per_ugv_per_s"] = o.bytes_in_per_ugv_per_s;
  s["bytes_in_per_ugv_by_topic"] = by_topic(o.bytes_in_per_ugv_by_topic_per_s);
  s["collisions"] = o.collisions;
  s["all_reached"] = o.all_reached;
  s["time_limit_reached"] = o.time_limit_reached;
  j["summary"] = s;
  if (o.base_fault.injected) {
    nlohmann::ordered_json f;
    f["ugv"] = 0;
    f["at_s"] = o.config.faults.base_fault_at_s;
    f["firmware_fault_after_s"] = o.base_fault.firmware_fault_after_s;
    f["still_after_s"] = o.base_fault.still_after_s;
    f["max_speed_after_still_mps"] = o.base_fault.max_speed_after_still;
    j["base_fault"] = f;
  }
  j["sim_time_s"] = o.sim_time_s;
  if (include_wall_time) {
    j["wall_time_s"] = o.wall_time_s;
    j["realtime_factor"] = o.wall_time_s > 0.0 ? o.sim_time_s / o.wall_time_s : 0.0;
  }
  j["uav_bytes_in_per_s"] = o.uav_bytes_in_per_s;
  j["uav_bytes_out_per_s"] = o.uav_bytes_out_per_s;
  j["map_patches"] = o.map_patches;
  j["map_patch_bytes"] = o.map_patch_bytes;
  j["schedules"] = o.schedules;
  j["schedules_exact"] = o.schedules_exact;
  j["plan_age_max_steps"] = o.plan_age_max;
  j["uav_time_s"] = {{"idle", o.uav_idle_s},
                     {"transit", o.uav_transit_s},
                     {"hover", o.uav_hover_s},
                     {"scout", o.uav_scout_s}};
  j["scout_timeouts"] = o.scout_timeouts;
  j["team_located"] = o.team_located;
  j["team_returns_dropped"] = o.team_returns_dropped;
  return j.dump(2);
}

}  // namespace colag::mission
