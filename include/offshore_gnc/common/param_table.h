#pragma once
// One table per parameters struct: every parameter's name, range, unit and one line of doc, in one place. The
// default is the struct's own initial value (or a vehicle preset's), never repeated here. validate() checks a
// struct against its table; the ROS reader (ros_util::readParams) and the YAML reader (readParamsYaml) fill a
// struct through the same table, so a range or a name cannot differ between a nodelet, a YAML file loaded by a
// ROS-free tool, and the dynamic_reconfigure .cfg (generated from the tables: common/reconfigure_form.h).
#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {

// A number as the parameter files and docs write it: whole numbers in full (67108864, not 6.71089e+07), others
// with six significant digits.
inline std::string paramNumberText(double v) {
  char b[32];
  if (v == static_cast<double>(static_cast<long long>(v)) && v > -1e15 && v < 1e15)
    std::snprintf(b, sizeof b, "%lld", static_cast<long long>(v));
  else
    std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

enum class ParamKind { kNumber, kInteger, kFlag, kNumbers, kChoice, kText };

template <class P>
struct ParamSpec {
  ParamKind kind = ParamKind::kNumber;
  std::string name;  // relative name, '/' separates groups ("los/kp")
  double lo = 0.0, hi = 0.0;      // in the file's unit
  double scale = 1.0;             // kNumber: struct value = file value * scale (degrees in files, radians inside)
  std::string unit, doc;
  std::size_t size = 0;              // kNumbers: required length (0 = any)
  std::vector<std::string> choices;  // kChoice
  std::function<double&(P&)> number;
  std::function<int&(P&)> integer;
  std::function<bool&(P&)> flag;
  std::function<std::vector<double>(const P&)> get_numbers;  // kNumbers: lists are copied in and out, so a
  std::function<void(P&, const std::vector<double>&)> set_numbers;  // list can be an Eigen vector or fields
  std::function<std::string&(P&)> choice;
  std::function<std::string&(P&)> string;  // kText: any text (a device, a frame, a file)
};

template <class P>
class ParamTable {
 public:
  using Spec = ParamSpec<P>;

  ParamTable& number(const std::string& name, double P::*m, double lo, double hi, const char* unit,
                     const char* doc) {
    return add(ParamKind::kNumber, name, lo, hi, unit, doc, [m](Spec& s) { s.number = [m](P& p) -> double& { return p.*m; }; });
  }
  // An angle kept in radians, written in degrees in parameter files (name ends in _deg).
  ParamTable& degrees(const std::string& name, double P::*m, double lo_deg, double hi_deg, const char* doc) {
    return add(ParamKind::kNumber, name, lo_deg, hi_deg, "deg", doc, [m](Spec& s) {
      s.scale = 3.14159265358979323846 / 180.0;
      s.number = [m](P& p) -> double& { return p.*m; };
    });
  }
  // A field of a nested struct (e.g. PidGains::kp of UsvControlParams::yaw).
  template <class S>
  ParamTable& number(const std::string& name, S P::*outer, double S::*m, double lo, double hi, const char* unit,
                     const char* doc) {
    return add(ParamKind::kNumber, name, lo, hi, unit, doc,
               [outer, m](Spec& s) { s.number = [outer, m](P& p) -> double& { return (p.*outer).*m; }; });
  }
  // Any number reachable from P that is not a plain member (an Eigen vector's element, say); `scale` as degrees().
  ParamTable& numberAt(const std::string& name, std::function<double&(P&)> access, double lo, double hi,
                       const char* unit, const char* doc, double scale = 1.0) {
    return add(ParamKind::kNumber, name, lo, hi, unit, doc, [&](Spec& s) {
      s.scale = scale;
      s.number = std::move(access);
    });
  }
  ParamTable& integer(const std::string& name, int P::*m, int lo, int hi, const char* doc) {
    return add(ParamKind::kInteger, name, lo, hi, "", doc, [m](Spec& s) { s.integer = [m](P& p) -> int& { return p.*m; }; });
  }
  ParamTable& flag(const std::string& name, bool P::*m, const char* doc) {
    return add(ParamKind::kFlag, name, 0, 1, "", doc, [m](Spec& s) { s.flag = [m](P& p) -> bool& { return p.*m; }; });
  }
  template <class S>
  ParamTable& flag(const std::string& name, S P::*outer, bool S::*m, const char* doc) {
    return add(ParamKind::kFlag, name, 0, 1, "", doc,
               [outer, m](Spec& s) { s.flag = [outer, m](P& p) -> bool& { return (p.*outer).*m; }; });
  }
  template <class S>
  ParamTable& integer(const std::string& name, S P::*outer, int S::*m, int lo, int hi, const char* doc) {
    return add(ParamKind::kInteger, name, lo, hi, "", doc,
               [outer, m](Spec& s) { s.integer = [outer, m](P& p) -> int& { return (p.*outer).*m; }; });
  }
  ParamTable& numbers(const std::string& name, std::vector<double> P::*m, std::size_t size, double lo, double hi,
                      const char* unit, const char* doc) {
    return list(name, size, lo, hi, unit, doc, [m](const P& p) { return p.*m; },
                [m](P& p, const std::vector<double>& v) { p.*m = v; });
  }
  // Any list-like value: `get` and `set` convert (an Eigen vector, a few fields written as one list).
  ParamTable& list(const std::string& name, std::size_t size, double lo, double hi, const char* unit, const char* doc,
                   std::function<std::vector<double>(const P&)> get,
                   std::function<void(P&, const std::vector<double>&)> set) {
    return add(ParamKind::kNumbers, name, lo, hi, unit, doc, [&](Spec& s) {
      s.size = size;
      s.get_numbers = std::move(get);
      s.set_numbers = std::move(set);
    });
  }
  ParamTable& choice(const std::string& name, std::string P::*m, std::vector<std::string> choices, const char* doc) {
    return add(ParamKind::kChoice, name, 0, 0, "", doc, [m, choices](Spec& s) {
      s.choices = choices;
      s.choice = [m](P& p) -> std::string& { return p.*m; };
    });
  }
  // Free text: a device, a frame id, a file (its checks, e.g. "required", are the struct's own validate()).
  ParamTable& string(const std::string& name, std::string P::*m, const char* doc) {
    return add(ParamKind::kText, name, 0, 0, "", doc, [m](Spec& s) { s.string = [m](P& p) -> std::string& { return p.*m; }; });
  }
  template <class S>
  ParamTable& string(const std::string& name, S P::*outer, std::string S::*m, const char* doc) {
    return add(ParamKind::kText, name, 0, 0, "", doc,
               [outer, m](Spec& s) { s.string = [outer, m](P& p) -> std::string& { return (p.*outer).*m; }; });
  }
  // Another struct's table for a member of this one, under a prefix ("los/" + LosParams' names).
  template <class S>
  ParamTable& nest(const std::string& prefix, S P::*outer, const ParamTable<S>& inner) {
    for (const auto& is : inner.specs()) {
      Spec s;
      s.kind = is.kind;
      s.name = prefix + is.name;
      s.lo = is.lo, s.hi = is.hi, s.scale = is.scale, s.unit = is.unit, s.doc = is.doc, s.size = is.size;
      s.choices = is.choices;
      if (is.number) s.number = [outer, f = is.number](P& p) -> double& { return f(p.*outer); };
      if (is.integer) s.integer = [outer, f = is.integer](P& p) -> int& { return f(p.*outer); };
      if (is.flag) s.flag = [outer, f = is.flag](P& p) -> bool& { return f(p.*outer); };
      if (is.get_numbers) s.get_numbers = [outer, f = is.get_numbers](const P& p) { return f(p.*outer); };
      if (is.set_numbers)
        s.set_numbers = [outer, f = is.set_numbers](P& p, const std::vector<double>& v) { f(p.*outer, v); };
      if (is.choice) s.choice = [outer, f = is.choice](P& p) -> std::string& { return f(p.*outer); };
      if (is.string) s.string = [outer, f = is.string](P& p) -> std::string& { return f(p.*outer); };
      specs_.push_back(std::move(s));
    }
    return *this;
  }

  const std::vector<Spec>& specs() const { return specs_; }

  // A value as a parameter file writes it (degrees for angles kept in radians).
  static std::string text(const Spec& s, const P& p) {
    P q = p;
    auto num = [](double v) { return paramNumberText(v); };
    switch (s.kind) {
      case ParamKind::kNumber: return num(s.number(q) / s.scale);
      case ParamKind::kInteger: return std::to_string(s.integer(q));
      case ParamKind::kFlag: return s.flag(q) ? "true" : "false";
      case ParamKind::kChoice: return s.choice(q);
      case ParamKind::kText: return s.string(q).empty() ? "\"\"" : s.string(q);
      case ParamKind::kNumbers: {
        std::string o = "[";
        for (double v : s.get_numbers(q)) o += (o.size() > 1 ? ", " : "") + num(v);
        return o + "]";
      }
    }
    return "";
  }
  const Spec* find(const std::string& name) const {
    for (const auto& s : specs_)
      if (s.name == name) return &s;
    return nullptr;
  }

  // Throws ConfigError naming the first value outside its range ("parameter 'prefix+name' = v is out of ...").
  void validate(const P& p, const std::string& prefix = "") const {
    P q = p;  // the accessors give references: read a copy
    for (const auto& s : specs_) {
      const std::string n = prefix + s.name;
      switch (s.kind) {
        case ParamKind::kNumber: requireRange(n, s.number(q) / s.scale, s.lo, s.hi); break;
        case ParamKind::kInteger: requireRange(n, s.integer(q), s.lo, s.hi); break;
        case ParamKind::kFlag:
        case ParamKind::kText: break;
        case ParamKind::kNumbers: {
          const auto v = s.get_numbers(q);
          if (s.size && v.size() != s.size)
            throw ConfigError("parameter '" + n + "' needs " + std::to_string(s.size) + " values, has " +
                              std::to_string(v.size()));
          for (std::size_t i = 0; i < v.size(); ++i) requireRange(n + "[" + std::to_string(i) + "]", v[i], s.lo, s.hi);
          break;
        }
        case ParamKind::kChoice: {
          const auto& v = s.choice(q);
          bool ok = false;
          for (const auto& c : s.choices) ok = ok || c == v;
          if (!ok) {
            std::string all;
            for (const auto& c : s.choices) all += (all.empty() ? "" : ", ") + c;
            throw ConfigError("parameter '" + n + "' = '" + v + "' is not one of: " + all);
          }
          break;
        }
      }
    }
  }

 private:
  template <class F>
  ParamTable& add(ParamKind kind, const std::string& name, double lo, double hi, const char* unit, const char* doc,
                  F&& bind) {
    Spec s;
    s.kind = kind;
    s.name = name;
    s.lo = lo;
    s.hi = hi;
    s.unit = unit;
    s.doc = doc;
    bind(s);
    specs_.push_back(std::move(s));
    return *this;
  }
  std::vector<Spec> specs_;
};

}  // namespace offshore_gnc
