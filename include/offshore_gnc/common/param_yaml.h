#pragma once
// Parameter files read through the parameter tables (common/param_table.h) without ROS: the same YAML a launch
// file loads into a nodelet's namespace, read by the ROS-free loops with the same names, ranges and defaults.
// Header-only; users link yaml-cpp.
#include <yaml-cpp/yaml.h>

#include <sstream>
#include <string>
#include <vector>

#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {

// A parameter file; ConfigError naming it when it cannot be read or is not YAML.
inline YAML::Node loadYamlFile(const std::string& path) {
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw ConfigError("cannot read '" + path + "': " + e.what());
  }
}

// The node at "a/b/c" under root (an undefined node when any part is missing).
inline YAML::Node yamlAt(const YAML::Node& root, const std::string& path) {
  YAML::Node n = YAML::Clone(root);
  std::stringstream ss(path);
  std::string part;
  while (std::getline(ss, part, '/')) {
    if (!n.IsMap() || !n[part]) return YAML::Node(YAML::NodeType::Undefined);
    n = n[part];
  }
  return n;
}

// Fills `p` from `root` through its table: each key present replaces the struct's value (type and range
// checked, ConfigError naming `source` and the key); then the table validates the whole struct.
template <class P>
void readParamsYaml(const YAML::Node& root, const ParamTable<P>& t, P& p, const std::string& source,
                    const std::string& prefix = "") {
  for (const auto& s : t.specs()) {
    const std::string key = prefix + s.name;
    const YAML::Node n = yamlAt(root, key);
    if (!n.IsDefined() || n.IsNull()) continue;
    const std::string where = source + ": parameter '" + key + "'";
    try {
      switch (s.kind) {
        case ParamKind::kNumber: s.number(p) = s.scale * requireRange(where, n.as<double>(), s.lo, s.hi); break;
        case ParamKind::kInteger: s.integer(p) = static_cast<int>(requireRange(where, n.as<int>(), s.lo, s.hi)); break;
        case ParamKind::kFlag: s.flag(p) = n.as<bool>(); break;
        case ParamKind::kNumbers: s.set_numbers(p, n.as<std::vector<double>>()); break;
        case ParamKind::kChoice: s.choice(p) = n.as<std::string>(); break;
        case ParamKind::kText: s.string(p) = n.as<std::string>(); break;
      }
    } catch (const YAML::Exception&) {
      throw ConfigError(where + " has the wrong type");
    }
  }
  try {
    t.validate(p, prefix);
  } catch (const ConfigError& e) {
    throw ConfigError(source + ": " + e.what());
  }
}

}  // namespace offshore_gnc
