#pragma once
// The one place where nodelets read parameters. Every read names the parameter, applies the default and
// validates the range; an unusable value throws offshore_gnc::ConfigError, which the nodelet turns into a
// fatal error naming the parameter and the accepted range (ARCHITECTURE.md conventions).
#include <ros/node_handle.h>

#include <string>
#include <vector>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace ros_util {

class ParamReader {
 public:
  explicit ParamReader(const ros::NodeHandle& nh) : nh_(nh) {}

  // Optional number with default, checked against [lo, hi].
  double number(const std::string& name, double def, double lo, double hi) const;
  // Required number: missing is an error.
  double requiredNumber(const std::string& name, double lo, double hi) const;
  int integer(const std::string& name, int def, int lo, int hi) const;
  bool flag(const std::string& name, bool def) const;
  std::string text(const std::string& name, const std::string& def) const;
  // Text that must be one of `allowed`.
  std::string choice(const std::string& name, const std::string& def, const std::vector<std::string>& allowed) const;
  // Numeric list, optionally with a fixed size (0 = any) and element range.
  std::vector<double> numbers(const std::string& name, const std::vector<double>& def, std::size_t size, double lo,
                              double hi) const;

  const ros::NodeHandle& handle() const { return nh_; }

 private:
  std::string full(const std::string& name) const;
  ros::NodeHandle nh_;
};

}  // namespace ros_util
}  // namespace offshore_gnc
