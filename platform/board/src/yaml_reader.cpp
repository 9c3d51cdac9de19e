#include "yaml_reader.hpp"

namespace colag::board {

bool parse(const std::string& path, YAML::Node& root, std::string& error) {
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    error = path + ": cannot open the configuration file";
    return false;
  } catch (const YAML::Exception& e) {
    error = path + ": line " + std::to_string(e.mark.line + 1) + ": " + e.msg;
    return false;
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);  // an empty file: all defaults
  return true;
}

void read_common(Reader& r, const YAML::Node& doc, CommonBoardConfig& c) {
  const YAML::Node dds = child(doc, "dds");
  r.only(dds, "dds", {"domain", "partition"});
  r.get(dds, "dds", "domain", c.dds_domain, 0u, 232u);  // DDS allows domain ids 0..232
  r.get(dds, "dds", "partition", c.dds_partition);
  const YAML::Node rt = child(doc, "realtime");
  r.only(rt, "realtime", {"fifo_priority", "lock_memory"});
  r.get(rt, "realtime", "fifo_priority", c.realtime.fifo_priority, 0, 99);
  r.get(rt, "realtime", "lock_memory", c.realtime.lock_memory);
}

}  // namespace colag::board
