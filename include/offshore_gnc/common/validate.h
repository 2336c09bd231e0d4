#pragma once
// One place for value validation, used by parameter loading (ROS layer), scenario files and the cores'
// own constructors. Errors name the value and the accepted range so that a user can fix the file.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace offshore_gnc {

class ConfigError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Throws ConfigError unless lo <= v <= hi and v is finite.
inline double requireRange(const std::string& name, double v, double lo, double hi) {
  if (!std::isfinite(v) || v < lo || v > hi) {
    std::ostringstream os;
    os << "parameter '" << name << "' = " << v << " is out of range [" << lo << ", " << hi << "]";
    throw ConfigError(os.str());
  }
  return v;
}

inline double requirePositive(const std::string& name, double v) {
  if (!std::isfinite(v) || v <= 0.0) {
    std::ostringstream os;
    os << "parameter '" << name << "' = " << v << " must be a finite number > 0";
    throw ConfigError(os.str());
  }
  return v;
}

}  // namespace offshore_gnc
