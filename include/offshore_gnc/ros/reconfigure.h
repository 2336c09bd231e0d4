#pragma once
// dynamic_reconfigure through the parameter tables: a .cfg parameter is the table entry of the same name with
// '/' written '_' ("los/kp" -> los_kp), so the server starts from the loaded values and a change goes back into
// the struct without a hand-written list of fields (test/unit/guidance/test_ros_params.cpp holds the .cfg ranges
// and defaults to the tables).
#include <dynamic_reconfigure/Config.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/common/reconfigure_form.h"

namespace offshore_gnc {
namespace ros_util {

template <class P>
const ParamSpec<P>* specForCfg(const ParamTable<P>& t, const std::string& cfg_name) {
  for (const auto& s : t.specs())
    if (cfgName(s.name) == cfg_name) return &s;
  return nullptr;
}

// The range each parameter of a .cfg declares, by name (bools as 0..1).
template <class Config>
std::map<std::string, std::pair<double, double>> cfgRanges() {
  dynamic_reconfigure::Config lo, hi;
  Config::__getMin__().__toMessage__(lo);
  Config::__getMax__().__toMessage__(hi);
  std::map<std::string, std::pair<double, double>> r;
  for (std::size_t i = 0; i < lo.doubles.size(); ++i) r[lo.doubles[i].name] = {lo.doubles[i].value, hi.doubles[i].value};
  for (std::size_t i = 0; i < lo.ints.size(); ++i) r[lo.ints[i].name] = {lo.ints[i].value, hi.ints[i].value};
  for (std::size_t i = 0; i < lo.bools.size(); ++i) r[lo.bools[i].name] = {0, 1};
  return r;
}

// The default each parameter of a .cfg declares, by name (bools as 0 or 1).
template <class Config>
std::map<std::string, double> cfgDefaults() {
  dynamic_reconfigure::Config d;
  Config::__getDefault__().__toMessage__(d);
  std::map<std::string, double> r;
  for (const auto& v : d.doubles) r[v.name] = v.value;
  for (const auto& v : d.ints) r[v.name] = v.value;
  for (const auto& v : d.bools) r[v.name] = v.value ? 1 : 0;
  return r;
}

// A .cfg default that differs from the value in `p` (the struct's default, or a preset), or "" when they agree
// or the table has no such entry. The form starts from the loaded values, but a default that drifted from the
// code's misleads whoever reads the .cfg.
template <class P>
std::string cfgDefaultMismatch(const std::string& cfg_name, double cfg_default, const ParamTable<P>& t, P p) {
  const ParamSpec<P>* s = specForCfg(t, cfg_name);
  if (!s) return "";
  double v = cfg_default;
  if (s->number) v = s->number(p) / s->scale;
  else if (s->integer) v = s->integer(p);
  else if (s->flag) v = s->flag(p) ? 1 : 0;
  if (std::abs(v - cfg_default) <= 1e-9 * std::max(1.0, std::abs(v))) return "";
  return cfg_name + ": .cfg default " + std::to_string(cfg_default) + ", the code's " + std::to_string(v);
}

// A .cfg range that differs from its table entry's, or "" when they agree; `found` is set when the table has it.
template <class P>
std::string cfgMismatch(const std::string& cfg_name, const std::pair<double, double>& range, const ParamTable<P>& t,
                        bool& found) {
  const ParamSpec<P>* s = specForCfg(t, cfg_name);
  if (!s) return "";
  found = true;
  if (s->kind == ParamKind::kFlag || (range.first == s->lo && range.second == s->hi)) return "";
  return cfg_name + ": .cfg range [" + std::to_string(range.first) + ", " + std::to_string(range.second) +
         "], table [" + std::to_string(s->lo) + ", " + std::to_string(s->hi) + "]";
}

// The .cfg's Config with every parameter the table knows set from `p` (the others keep their .cfg defaults).
template <class Config, class P>
Config toReconfigure(const ParamTable<P>& t, const P& p) {
  Config c = Config::__getDefault__();
  dynamic_reconfigure::Config msg;
  c.__toMessage__(msg);
  P q = p;
  for (auto& d : msg.doubles)
    if (auto s = specForCfg(t, d.name); s && s->number) d.value = s->number(q) / s->scale;
  for (auto& b : msg.bools)
    if (auto s = specForCfg(t, b.name); s && s->flag) b.value = s->flag(q);
  for (auto& i : msg.ints)
    if (auto s = specForCfg(t, i.name); s && s->integer) i.value = s->integer(q);
  c.__fromMessage__(msg);
  return c;
}

// A reconfigure request into a copy of `p` (validate it before use).
template <class Config, class P>
P fromReconfigure(const Config& c, const ParamTable<P>& t, P p) {
  dynamic_reconfigure::Config msg;
  c.__toMessage__(msg);
  for (const auto& d : msg.doubles)
    if (auto s = specForCfg(t, d.name); s && s->number) s->number(p) = d.value * s->scale;
  for (const auto& b : msg.bools)
    if (auto s = specForCfg(t, b.name); s && s->flag) s->flag(p) = b.value;
  for (const auto& i : msg.ints)
    if (auto s = specForCfg(t, i.name); s && s->integer) s->integer(p) = i.value;
  return p;
}

}  // namespace ros_util
}  // namespace offshore_gnc
