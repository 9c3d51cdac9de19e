#pragma once
// A world profile from a YAML scenario file (see config/worlds/field.yaml for every key, its
// unit and where its default comes from). `base: ideal | field` (default field) gives the values
// the file does not set. Unknown keys, wrong types and values out of range are refused with
// "FILE: key.path: problem".
#include <string>

#include "colag/sim/world/world_profile.hpp"

namespace colag::mission {

bool load_world_file(const std::string& file, sim::WorldProfile& out, std::string& error);
// "ideal", "field", or a YAML file.
bool world_from_name(const std::string& name, sim::WorldProfile& out, std::string& error);

}  // namespace colag::mission
