#include "offshore_gnc/ros/params.h"

#include <sstream>

namespace offshore_gnc {
namespace ros_util {

std::string ParamReader::full(const std::string& name) const { return nh_.resolveName(name); }

double ParamReader::number(const std::string& name, double def, double lo, double hi) const {
  double v = def;
  if (nh_.hasParam(name) && !nh_.getParam(name, v)) {
    throw ConfigError("parameter '" + full(name) + "' is not a number");
  }
  return requireRange(full(name), v, lo, hi);
}

double ParamReader::requiredNumber(const std::string& name, double lo, double hi) const {
  if (!nh_.hasParam(name)) throw ConfigError("required parameter '" + full(name) + "' is missing");
  return number(name, 0.0, lo, hi);
}

int ParamReader::integer(const std::string& name, int def, int lo, int hi) const {
  int v = def;
  if (nh_.hasParam(name) && !nh_.getParam(name, v)) {
    throw ConfigError("parameter '" + full(name) + "' is not an integer");
  }
  return static_cast<int>(requireRange(full(name), v, lo, hi));
}

bool ParamReader::flag(const std::string& name, bool def) const {
  bool v = def;
  if (nh_.hasParam(name) && !nh_.getParam(name, v)) {
    throw ConfigError("parameter '" + full(name) + "' is not a boolean");
  }
  return v;
}

std::string ParamReader::text(const std::string& name, const std::string& def) const {
  std::string v = def;
  if (nh_.hasParam(name) && !nh_.getParam(name, v)) {
    throw ConfigError("parameter '" + full(name) + "' is not a string");
  }
  return v;
}

std::string ParamReader::choice(const std::string& name, const std::string& def,
                                const std::vector<std::string>& allowed) const {
  const std::string v = text(name, def);
  for (const auto& a : allowed)
    if (a == v) return v;
  std::ostringstream os;
  os << "parameter '" << full(name) << "' = '" << v << "' is not one of:";
  for (const auto& a : allowed) os << " " << a;
  throw ConfigError(os.str());
}

std::vector<double> ParamReader::numbers(const std::string& name, const std::vector<double>& def, std::size_t size,
                                         double lo, double hi) const {
  std::vector<double> v = def;
  if (nh_.hasParam(name) && !nh_.getParam(name, v)) {
    throw ConfigError("parameter '" + full(name) + "' is not a list of numbers");
  }
  if (size != 0 && v.size() != size) {
    std::ostringstream os;
    os << "parameter '" << full(name) << "' has " << v.size() << " elements, expected " << size;
    throw ConfigError(os.str());
  }
  for (std::size_t i = 0; i < v.size(); ++i) requireRange(full(name) + "[" + std::to_string(i) + "]", v[i], lo, hi);
  return v;
}

double entryNumber(XmlRpc::XmlRpcValue& v, const std::string& where) {
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
  throw ConfigError("parameter '" + where + "' is not a number");
}

int entryInteger(XmlRpc::XmlRpcValue& v, const std::string& where) {
  if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) throw ConfigError("parameter '" + where + "' is not an integer");
  return static_cast<int>(v);
}

bool entryFlag(XmlRpc::XmlRpcValue& v, const std::string& where) {
  if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) throw ConfigError("parameter '" + where + "' is not a boolean");
  return static_cast<bool>(v);
}

std::string entryText(XmlRpc::XmlRpcValue& v, const std::string& where) {
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString) throw ConfigError("parameter '" + where + "' is not a string");
  return static_cast<std::string>(v);
}

std::vector<double> entryNumbers(XmlRpc::XmlRpcValue& v, const std::string& where) {
  if (v.getType() != XmlRpc::XmlRpcValue::TypeArray) throw ConfigError("parameter '" + where + "' is not a list of numbers");
  std::vector<double> out;
  for (int i = 0; i < v.size(); ++i) out.push_back(entryNumber(v[i], where + "[" + std::to_string(i) + "]"));
  return out;
}

}  // namespace ros_util
}  // namespace offshore_gnc
