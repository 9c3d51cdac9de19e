#pragma once
// The board programs' configuration (ugv_fw / uav_fw --config robot.yaml), read with yaml-cpp
// at start-up: one loader for both robots. It reads the sections every robot has (dds,
// realtime) and hands the document to the robot's own reader for its sections (robot, can,
// camera, ...). Every key is optional and defaults to the documented value
// (config/*.example.yaml lists them all); a present key with a wrong type or an out-of-range
// value is an error that names the key ("can.interface: expected a string"), and so is an
// unknown key or section (a typo must not silently fall back to a default on a robot).
#include <string>
#include <vector>

#include "colag/board/yaml_reader.hpp"
#include "colag/platform/dds_security_config.hpp"
#include "colag/platform/realtime_executor.hpp"

namespace colag::board {

// `ros2`: the robot's telemetry under ROS 2 names and types on the fleet's DDS domain, for
// RViz2, Foxglove and `ros2 bag` (README "Watching a mission"). Off by default: off, nothing of
// it is built.
struct Ros2Config {
  bool enabled = false;
  std::string ns;                // `namespace`: "" = the robot's default (ugv<id>, uav)
  double status_period_s = 0.5;  // status, plan, prediction; odometry and /tf at the loop's rate
  double map_period_s = 1.0;     // the occupancy grid
  bool commands = true;          // a UGV takes goals (<ns>/goal_pose) and <ns>/command
};

// The sections every robot's file has.
struct CommonBoardConfig {
  std::uint32_t dds_domain = 0;
  std::string dds_partition;
  platform::DdsSecurityConfig dds_security;  // dds.security: all six files, or none (off)
  platform::RealtimeOptions realtime{.fifo_priority = 50, .lock_memory = true};
  Ros2Config ros2;
};

// A robot's own part of the file. Config must have a `CommonBoardConfig common` member.
template <class Config>
struct ConfigSchema {
  std::vector<std::string> sections;  // the robot's top-level sections, besides dds and realtime
  void (*read)(Reader& r, const YAML::Node& doc, Config& out);  // reads those sections
};

// Parses a document from the file `name` (text == nullptr) or from `text` (errors then name it
// `name`); an empty document is an empty mapping. False with `error` set on failure.
bool load_document(const std::string& name, const std::string* text, YAML::Node& doc,
                   std::string& error);
// A DDS Security section (`sec`, at `where`, e.g. "dds.security"): the six files, relative to
// the file being read, all or none, each readable.
void read_dds_security(Reader& r, const YAML::Node& sec, const std::string& where,
                       platform::DdsSecurityConfig& s);
// The file scripts/security/make-pki writes beside each identity (`<who>/security.yaml`, a
// `security:` section), for the tools that join a secured fleet (colag_record --security
// pki/operator/security.yaml). False with `error` ("FILE: security.key: problem").
bool read_security_file(const std::string& file, platform::DdsSecurityConfig& out,
                        std::string& error);
// Checks the top-level sections (the common ones and `robot_sections`) and reads dds, realtime.
void read_common(Reader& r, const YAML::Node& doc, const std::vector<std::string>& robot_sections,
                 CommonBoardConfig& out);

// All or nothing: `out` is written only when the whole document is valid; otherwise false with
// `error` = "FILE: key.path: problem".
template <class Config>
bool read_config(const std::string& name, const std::string* text,
                 const ConfigSchema<Config>& schema, Config& out, std::string& error) {
  error.clear();
  YAML::Node doc;
  if (!load_document(name, text, doc, error)) return false;
  Reader r(name, error);
  Config c;
  read_common(r, doc, schema.sections, c.common);
  schema.read(r, doc, c);
  if (!r.ok()) return false;
  out = c;
  return true;
}

// A configuration file.
template <class Config>
bool load_config(const std::string& path, const ConfigSchema<Config>& schema, Config& out,
                 std::string& error) {
  return read_config(path, nullptr, schema, out, error);
}
// A document in memory (tests, fuzzing); `name` stands for the file in errors.
template <class Config>
bool parse_config(const std::string& text, const std::string& name,
                  const ConfigSchema<Config>& schema, Config& out, std::string& error) {
  return read_config(name, &text, schema, out, error);
}

}  // namespace colag::board
