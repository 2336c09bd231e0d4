// YAML parameter files for the models. Every scalar is range-checked here with the file and key in the
// message; the params' own validate() then checks the cross-field rules (also prefixed with the file).
#include "offshore_gnc/models/params_yaml.h"

#include <set>

#include <yaml-cpp/yaml.h>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/csv_table.h"

namespace offshore_gnc {
namespace models {

namespace {

class Reader {
 public:
  Reader(const YAML::Node& node, std::string source) : node_(node), source_(std::move(source)) {
    if (!node_.IsMap()) fail("", "must be a YAML map");
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw ConfigError(source_ + ": parameter '" + key + "' " + what);
  }
  // Required scalar within [lo, hi].
  double num(const std::string& key, double lo, double hi) {
    used_.insert(key);
    const YAML::Node n = node_[key];
    if (!n) fail(key, "is missing");
    double v;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(key, "is not a number");
    }
    try {
      return requireRange(key, v, lo, hi);
    } catch (const ConfigError& e) {
      throw ConfigError(source_ + ": " + e.what());
    }
  }
  bool has(const std::string& key) const { return static_cast<bool>(node_[key]); }
  // Optional scalar: keeps `v` when absent.
  void opt(const std::string& key, double& v, double lo, double hi) {
    if (node_[key]) v = num(key, lo, hi);
  }
  void optVec(const std::string& key, std::vector<double>& v) {
    used_.insert(key);
    const YAML::Node n = node_[key];
    if (!n) return;
    try {
      v = n.as<std::vector<double>>();
    } catch (const YAML::Exception&) {
      fail(key, "is not a list of numbers");
    }
  }
  std::string str(const std::string& key, const std::set<std::string>& allowed) {
    used_.insert(key);
    const YAML::Node n = node_[key];
    if (!n) fail(key, "is missing");
    const std::string v = n.as<std::string>("");
    if (!allowed.count(v)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(key, "= '" + v + "' is not one of: " + list);
    }
    return v;
  }
  YAML::Node child(const std::string& key) {
    used_.insert(key);
    return node_[key];
  }
  // Unknown keys are refused so that a typo does not silently keep a default.
  void noUnknown() const {
    for (const auto& kv : node_) {
      const std::string k = kv.first.as<std::string>("");
      if (!used_.count(k)) fail(k, "is not a known parameter");
    }
  }
  const std::string& source() const { return source_; }

 private:
  YAML::Node node_;
  std::string source_;
  std::set<std::string> used_;
};

YAML::Node parse(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source + ": not valid YAML: " + e.what());
  }
}

template <class P>
void validateWithSource(const P& p, const std::string& source) {
  try {
    p.validate();
  } catch (const ConfigError& e) {
    throw ConfigError(source + ": " + e.what());
  }
}

Eigen::Vector3d vec3(Reader& parent, const YAML::Node& n, const std::string& key) {
  std::vector<double> v;
  try {
    v = n.as<std::vector<double>>();
  } catch (const YAML::Exception&) {
    parent.fail(key, "is missing or not a list of 3 numbers");
  }
  if (v.size() != 3) parent.fail(key, "must have 3 numbers");
  return {v[0], v[1], v[2]};
}

}  // namespace

UsvParams usvParamsFromYaml(const std::string& text, const std::string& source) {
  Reader r(parse(text, source), source);
  UsvParams p;
  p.type = r.str("model", {"dynamic_3dof", "nomoto"}) == "nomoto" ? UsvModelType::Nomoto : UsvModelType::Dynamic3Dof;
  p.mass = r.num("mass", 10, 1e6);
  p.m_pt = r.num("m_pt", 0, 1e6);
  p.m_hull = r.num("m_hull", 0, 1e6);
  p.length = r.num("length", 0.5, 200);
  p.l_pivot = r.num("l_pivot", 0, 200);
  p.l_pt = r.num("l_pt", 0, 200);
  p.kappa = r.num("kappa", 0, 2);
  p.c_g = r.num("c_g", 0, 1);
  p.i_cor = r.num("i_cor", 0.01, 10);
  p.x_g = r.num("x_g", -200, 200);
  for (auto [k, v] : {std::pair<const char*, double*>{"X_u", &p.X_u}, {"X_udot", &p.X_udot}, {"X_uu", &p.X_uu},
                      {"N_r", &p.N_r}, {"N_rdot", &p.N_rdot}, {"N_rr", &p.N_rr}, {"Y_v", &p.Y_v},
                      {"Y_vdot", &p.Y_vdot}, {"Y_vv", &p.Y_vv}, {"Y_r", &p.Y_r}, {"Y_rdot", &p.Y_rdot}})
    *v = r.num(k, -1e7, 1e7);
  r.optVec("table_speed_kt", p.table_speed_kt);
  r.optVec("table_thrust_kn", p.table_thrust_kn);
  p.rpm_ref = r.num("rpm_ref", 1, 1e5);
  p.rpm_min = r.num("rpm_min", 0, 1e5);
  p.rpm_max = r.num("rpm_max", 1, 1e5);
  r.optVec("joy_u", p.joy_u);
  r.optVec("joy_u_rpm", p.joy_u_rpm);
  r.optVec("joy_r", p.joy_r);
  r.optVec("joy_r_nozzle", p.joy_r_nozzle);
  p.joy_u_full = r.num("joy_u_full", 1, 1e6);
  p.joy_r_full = r.num("joy_r_full", 1, 1e6);
  p.bucket_band = r.num("bucket_band", 1e-3, 1);
  p.reverse_efficiency = r.num("reverse_efficiency", 0, 1);
  // twin jets (optional: files written before the per-jet model keep their meaning with its defaults)
  if (r.has("propulsion")) p.propulsion = r.str("propulsion", {"twin", "lumped"}) == "lumped" ? UsvPropulsion::Lumped
                                                                                              : UsvPropulsion::Twin;
  r.opt("jet_y", p.jet_y, 0.01, 10);
  r.opt("bucket_rate", p.bucket_rate, 0.01, 100);
  r.opt("yaw_rpm_share", p.yaw_rpm_share, 0, 1);
  r.optVec("rpm_num", p.rpm_num);
  r.optVec("rpm_den", p.rpm_den);
  p.nozzle_delay = r.num("nozzle_delay", 0, 10);
  p.nozzle_time_constant = r.num("nozzle_time_constant", 1e-3, 100);
  p.nozzle_max = r.num("nozzle_max", 1, 1e6);
  p.nozzle_max_angle = deg2rad(r.num("nozzle_max_angle_deg", 0, 90));
  p.nozzle_eff_a = r.num("nozzle_eff_a", 0, 2);
  p.nozzle_eff_b = r.num("nozzle_eff_b", -1, 0);
  p.surge_kp = r.num("surge_kp", -1, 1);
  p.surge_tz = r.num("surge_tz", -100, 100);
  p.surge_tp1 = r.num("surge_tp1", 1e-6, 1e3);
  p.surge_tp2 = r.num("surge_tp2", 1e-6, 1e3);
  p.surge_td = r.num("surge_td", 0, 10);
  p.yaw_kp = r.num("yaw_kp", -1, 1);
  p.yaw_tz = r.num("yaw_tz", -100, 100);
  p.yaw_tp1 = r.num("yaw_tp1", 1e-6, 1e3);
  p.yaw_tp2 = r.num("yaw_tp2", 1e-6, 1e3);
  p.wind_area_front = r.num("wind_area_front", 0, 1e4);
  p.wind_area_side = r.num("wind_area_side", 0, 1e4);
  p.wind_cx = r.num("wind_cx", 0, 5);
  p.wind_cy = r.num("wind_cy", 0, 5);
  p.wind_cn = r.num("wind_cn", -1, 1);
  p.max_step = r.num("max_step", 1e-4, 0.1);
  r.noUnknown();
  validateWithSource(p, source);
  return p;
}

AuvParams auvParamsFromYaml(const std::string& text, const std::string& source) {
  Reader r(parse(text, source), source);
  AuvParams p = r.str("type", {"girona500", "acolor"}) == "acolor" ? AuvParams::aColor() : AuvParams::girona500();
  p.mass = r.num("mass", 0.1, 1e5);
  p.volume = r.num("volume", 1e-5, 1e3);
  p.I_z = r.num("I_z", 1e-4, 1e6);
  r.opt("gravity", p.gravity, 9.0, 10.0);
  for (auto [k, v] : {std::pair<const char*, double*>{"X_u", &p.X_u}, {"X_udot", &p.X_udot}, {"X_uu", &p.X_uu},
                      {"Y_v", &p.Y_v}, {"Y_vdot", &p.Y_vdot}, {"Y_vv", &p.Y_vv}, {"Z_w", &p.Z_w},
                      {"Z_wdot", &p.Z_wdot}, {"Z_ww", &p.Z_ww}, {"N_r", &p.N_r}, {"N_rdot", &p.N_rdot},
                      {"N_rr", &p.N_rr}})
    *v = r.num(k, -1e6, 1e6);
  p.max_step = r.num("max_step", 1e-4, 0.1);
  const YAML::Node th = r.child("thrusters");
  if (!th || !th.IsSequence() || th.size() == 0) r.fail("thrusters", "is missing or not a non-empty list");
  // Default curve: the T200-like chart of Thruster unless the file gives one.
  const Thruster defaults;
  p.thrusters.clear();
  for (std::size_t i = 0; i < th.size(); ++i) {
    const std::string prefix = "thrusters[" + std::to_string(i) + "]";
    Reader t(th[i], source + ": " + prefix);
    Thruster x = defaults;
    const YAML::Node name = t.child("name");
    x.name = name ? name.as<std::string>("") : prefix;
    x.position = vec3(t, t.child("position"), "position");
    x.direction = vec3(t, t.child("direction"), "direction");
    t.optVec("curve_command", x.curve_command);
    t.optVec("curve_thrust", x.curve_thrust);
    t.noUnknown();
    p.thrusters.push_back(x);
  }
  r.noUnknown();
  validateWithSource(p, source);
  return p;
}

EnvironmentParams environmentParamsFromYaml(const std::string& text, const std::string& source) {
  const YAML::Node root = parse(text, source);
  if (!root || root.IsNull()) return EnvironmentParams();  // empty file: calm water
  Reader r(root, source);
  for (const char* k : {"sea_state", "current", "wind", "waves", "air_density", "water_density"}) r.child(k);
  r.noUnknown();
  return environmentFromYaml(root, source);
}

UsvParams loadUsvParams(const std::string& path) { return usvParamsFromYaml(readTextFile(path), path); }
AuvParams loadAuvParams(const std::string& path) { return auvParamsFromYaml(readTextFile(path), path); }
EnvironmentParams loadEnvironmentParams(const std::string& path) {
  return environmentParamsFromYaml(readTextFile(path), path);
}

}  // namespace models
}  // namespace offshore_gnc
