#include "colag/board/config.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <utility>

namespace colag::board {

bool load_document(const std::string& name, const std::string* text, YAML::Node& doc,
                   std::string& error) {
  std::error_code ec;
  if (text == nullptr && std::filesystem::exists(name, ec) &&
      !std::filesystem::is_regular_file(name, ec)) {
    error = name + ": not a file";
    return false;
  }
  try {
    doc = text != nullptr ? YAML::Load(*text) : YAML::LoadFile(name);
  } catch (const YAML::BadFile&) {
    error = name + ": cannot open the configuration file";
    return false;
  } catch (const YAML::Exception& e) {
    error = name + ": line " + std::to_string(e.mark.line + 1) + ": " + e.msg;
    return false;
  } catch (const std::exception& e) {  // an I/O error under yaml-cpp (a device, a FIFO)
    error = name + ": cannot read the configuration file (" + e.what() + ")";
    return false;
  }
  if (doc.IsNull()) doc = YAML::Node(YAML::NodeType::Map);  // an empty file: all defaults
  return true;
}

std::string relative_to(const std::string& config_file, const std::string& path) {
  if (path.empty() || path[0] == '/') return path;
  const auto slash = config_file.find_last_of('/');
  return slash == std::string::npos ? path : config_file.substr(0, slash + 1) + path;
}

void read_dds_security(Reader& r, const YAML::Node& sec, const std::string& where,
                       platform::DdsSecurityConfig& s) {
  r.only(sec, where,
         {"identity_ca", "certificate", "private_key", "permissions_ca", "governance",
          "permissions", "plugin_dir"});
  const std::pair<const char*, std::string*> files[] = {
      {"identity_ca", &s.identity_ca}, {"certificate", &s.certificate},
      {"private_key", &s.private_key}, {"permissions_ca", &s.permissions_ca},
      {"governance", &s.governance},   {"permissions", &s.permissions},
  };
  for (const auto& [key, value] : files) {
    r.get(sec, where, key, *value);
    *value = relative_to(r.file(), *value);
  }
  r.get(sec, where, "plugin_dir", s.plugin_dir);
  if (s.enabled()) {
    for (const auto& [key, value] : files)
      if (value->empty()) r.fail(where + "." + key, "required when security is on");
    for (const auto& [key, value] : files)  // --check-config must catch a wrong path
      if (r.ok() && !std::ifstream(*value)) r.fail(where + "." + key, "cannot read " + *value);
  }
}

bool read_security_file(const std::string& file, platform::DdsSecurityConfig& out,
                        std::string& error) {
  error.clear();
  YAML::Node doc;
  if (!load_document(file, nullptr, doc, error)) return false;
  Reader r(file, error);
  r.only(doc, "", {"security"});
  platform::DdsSecurityConfig s;
  read_dds_security(r, child(doc, "security"), "security", s);
  if (r.ok() && !s.enabled()) r.fail("security", "missing");
  if (!r.ok()) return false;
  out = s;
  return true;
}

void read_common(Reader& r, const YAML::Node& doc, const std::vector<std::string>& robot_sections,
                 CommonBoardConfig& out) {
  std::set<std::string> sections(robot_sections.begin(), robot_sections.end());
  sections.insert({"dds", "realtime", "ros2"});
  r.only(doc, "", sections);
  const YAML::Node dds = child(doc, "dds");
  r.only(dds, "dds", {"domain", "partition", "security"});
  r.get(dds, "dds", "domain", out.dds_domain, 0u, 232u);  // DDS allows domain ids 0..232
  r.get(dds, "dds", "partition", out.dds_partition);
  // dds.security: the files scripts/security/make-pki writes for this robot.
  read_dds_security(r, child(dds, "security"), "dds.security", out.dds_security);
  const YAML::Node rt = child(doc, "realtime");
  r.only(rt, "realtime", {"fifo_priority", "lock_memory"});
  r.get(rt, "realtime", "fifo_priority", out.realtime.fifo_priority, 0, 99);
  r.get(rt, "realtime", "lock_memory", out.realtime.lock_memory);

  const YAML::Node ros2 = child(doc, "ros2");
  r.only(ros2, "ros2", {"enabled", "namespace", "status_period_s", "map_period_s", "commands"});
  Ros2Config& o = out.ros2;
  r.get(ros2, "ros2", "enabled", o.enabled);
  r.get(ros2, "ros2", "namespace", o.ns);
  r.get(ros2, "ros2", "status_period_s", o.status_period_s, 0.05, 60.0);
  r.get(ros2, "ros2", "map_period_s", o.map_period_s, 0.1, 600.0);
  r.get(ros2, "ros2", "commands", o.commands);
  // A ROS name: letters, digits, '_' and '/', not starting with a digit.
  const bool name_ok =
      std::all_of(o.ns.begin(), o.ns.end(),
                  [](char c) {
                    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '/';
                  }) &&
      (o.ns.empty() || !std::isdigit(static_cast<unsigned char>(o.ns[0])));
  if (!name_ok) r.fail("ros2.namespace", "not a ROS name (letters, digits, _ and /)");
}

}  // namespace colag::board
