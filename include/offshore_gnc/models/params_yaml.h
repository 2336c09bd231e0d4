#pragma once
// Model parameter files (config/models/*.yaml) without ROS: yaml-cpp, every value validated. A missing,
// mistyped or out-of-range key throws ConfigError naming the file and the key. Keys absent from the file
// keep the defaults only where docs/models.md says they are optional (tables); scalars are required.
#include <string>

#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/usv.h"

namespace offshore_gnc {
namespace models {

UsvParams loadUsvParams(const std::string& path);
AuvParams loadAuvParams(const std::string& path);
EnvironmentParams loadEnvironmentParams(const std::string& path);  // keys of EnvironmentParams, all optional
// Same from YAML text; `source` names it in error messages.
UsvParams usvParamsFromYaml(const std::string& text, const std::string& source = "<yaml>");
AuvParams auvParamsFromYaml(const std::string& text, const std::string& source = "<yaml>");
EnvironmentParams environmentParamsFromYaml(const std::string& text, const std::string& source = "<yaml>");

}  // namespace models
}  // namespace offshore_gnc
