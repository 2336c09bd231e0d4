#pragma once
// The one place where nodelets read parameters. Every read names the parameter, applies the default and
// validates the range; an unusable value throws offshore_gnc::ConfigError, which the nodelet turns into a
// fatal error naming the parameter and the accepted range (ARCHITECTURE.md conventions).
#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <string>
#include <vector>

#include "offshore_gnc/common/param_table.h"
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
  std::string full(const std::string& name) const;

 private:
  ros::NodeHandle nh_;
};

// One parameter of `p`'s table: present on the server (under `prefix`), it replaces the struct's value, checked
// against the table's range.
template <class P>
void readSpec(const ParamReader& r, const ParamSpec<P>& s, P& p, const std::string& prefix = "") {
  const std::string n = prefix + s.name;
  switch (s.kind) {
    case ParamKind::kNumber: s.number(p) = s.scale * r.number(n, s.number(p) / s.scale, s.lo, s.hi); break;
    case ParamKind::kInteger:
      s.integer(p) = r.integer(n, s.integer(p), static_cast<int>(s.lo), static_cast<int>(s.hi));
      break;
    case ParamKind::kFlag: s.flag(p) = r.flag(n, s.flag(p)); break;
    case ParamKind::kNumbers: s.set_numbers(p, r.numbers(n, s.get_numbers(p), s.size, s.lo, s.hi)); break;
    case ParamKind::kChoice: s.choice(p) = r.choice(n, s.choice(p), s.choices); break;
    case ParamKind::kText: s.string(p) = r.text(n, s.string(p)); break;
  }
}

// Fills `p` through its table: each parameter present on the server (under `prefix`) replaces the struct's value,
// checked against the table's range.
template <class P>
void readParams(const ParamReader& r, const ParamTable<P>& t, P& p, const std::string& prefix = "") {
  for (const auto& s : t.specs()) readSpec(r, s, p, prefix);
}

// Only the table's parameter `name`: one that decides the others' defaults (a vehicle's preset), read first.
template <class P>
void readParam(const ParamReader& r, const ParamTable<P>& t, const std::string& name, P& p) {
  const ParamSpec<P>* s = t.find(name);
  if (!s) throw ConfigError("no parameter '" + name + "' in its table");  // a programming error, named
  readSpec(r, *s, p);
}

// One map of a list parameter (an entry of the relay's `topics`, say), read through a table like readParams:
// each key present replaces the struct's value, type and range checked; `where` ("topics[2]") names the entry.
// The ConfigError of a bad value names where/key.
double entryNumber(XmlRpc::XmlRpcValue& v, const std::string& where);
int entryInteger(XmlRpc::XmlRpcValue& v, const std::string& where);
bool entryFlag(XmlRpc::XmlRpcValue& v, const std::string& where);
std::string entryText(XmlRpc::XmlRpcValue& v, const std::string& where);
std::vector<double> entryNumbers(XmlRpc::XmlRpcValue& v, const std::string& where);

template <class P>
void readEntry(XmlRpc::XmlRpcValue& entry, const ParamTable<P>& t, P& p, const std::string& where) {
  if (entry.getType() != XmlRpc::XmlRpcValue::TypeStruct) throw ConfigError("parameter '" + where + "' must be a map");
  for (const auto& s : t.specs()) {
    if (!entry.hasMember(s.name)) continue;
    XmlRpc::XmlRpcValue& v = entry[s.name];
    const std::string n = where + "/" + s.name;
    switch (s.kind) {
      case ParamKind::kNumber: s.number(p) = s.scale * requireRange(n, entryNumber(v, n), s.lo, s.hi); break;
      case ParamKind::kInteger: s.integer(p) = static_cast<int>(requireRange(n, entryInteger(v, n), s.lo, s.hi)); break;
      case ParamKind::kFlag: s.flag(p) = entryFlag(v, n); break;
      case ParamKind::kNumbers: s.set_numbers(p, entryNumbers(v, n)); break;
      case ParamKind::kChoice: s.choice(p) = entryText(v, n); break;
      case ParamKind::kText: s.string(p) = entryText(v, n); break;
    }
  }
  t.validate(p, where + "/");
}

}  // namespace ros_util
}  // namespace offshore_gnc
