#pragma once
// dynamic_reconfigure through the parameter tables: a .cfg parameter is the table entry of the same name with
// '/' written '_' ("los/kp" -> los_kp), so the server starts from the loaded values and a change goes back into
// the struct without a hand-written list of fields. The .cfg scripts are generated from the same tables
// (common/reconfigure_form.h), so every field has its entry.
#include <dynamic_reconfigure/Config.h>

#include <string>

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
