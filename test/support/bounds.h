#pragma once
// The bound of a measured mission-level figure from test/bounds.yaml (issue 30): one place for each, beside the runs
// it was set from (test/bounds_measured.yaml, ./scripts/measure_bounds). Tests run from the repository root.
#include <string>

#include "offshore_gnc/common/param_yaml.h"

namespace offshore_gnc::testing_bounds {

// cases/<c>/bounds/<figure>/<which> ("max" or "min"); ConfigError naming it when the file has none.
inline double bound(const std::string& c, const std::string& figure, const std::string& which) {
  static const YAML::Node root = loadYamlFile("test/bounds.yaml");
  const YAML::Node n = yamlAt(root, "cases/" + c + "/bounds/" + figure + "/" + which);
  if (!n.IsDefined() || !n.IsScalar()) throw ConfigError("test/bounds.yaml has no " + which + " for " + c + "/" + figure);
  return n.as<double>();
}
inline double upper(const std::string& c, const std::string& figure) { return bound(c, figure, "max"); }
inline double lower(const std::string& c, const std::string& figure) { return bound(c, figure, "min"); }

}  // namespace offshore_gnc::testing_bounds
