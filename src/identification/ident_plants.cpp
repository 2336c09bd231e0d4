// The vehicles as the identification sees them: their fittable coefficients (one table per model type) and
// their simulation, which is always the models module's models::UsvModel / models::AuvModel.
#include <algorithm>
#include <cmath>
#include <limits>

#include "ident_plant.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"

namespace offshore_gnc {
namespace identification {
namespace ident {

bool isAngle(const std::string& signal) { return signal == "yaw_rad"; }

std::string groupSignal(const std::string& group) {
  static const std::map<std::string, std::string> m{{"surge", "u"},   {"sway", "v"},   {"heave", "w"},
                                                    {"yaw", "r_rad_s"}, {"rpm", "rpm"}, {"nozzle", "nozzle"}};
  const auto it = m.find(group);
  return it == m.end() ? "" : it->second;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Field access by YAML key ("X_uu", "rpm_num[1]") into a parameter struct.
template <class P>
struct Fields {
  std::map<std::string, double P::*> scalars;
  std::map<std::string, std::vector<double> P::*> lists;
  double& ref(P& p, const std::string& key) const {
    const auto s = scalars.find(key);
    if (s != scalars.end()) return p.*(s->second);
    const auto b = key.find('[');
    if (b != std::string::npos && key.back() == ']') {
      const auto l = lists.find(key.substr(0, b));
      const std::size_t i = std::stoul(key.substr(b + 1));
      if (l != lists.end() && i < (p.*(l->second)).size()) return (p.*(l->second))[i];
    }
    throw ConfigError("no fittable parameter '" + key + "'");
  }
};

// The measured value at row i, else the next one within 2 s (rows of other sensors in between), else 0.
double measured(const IdentLog& log, const char* s, std::size_t i) {
  const auto it = log.measured.find(s);
  if (it == log.measured.end()) return 0.0;
  for (std::size_t j = i; j < log.rows() && log.t[j] <= log.t[i] + 2.0; ++j)
    if (std::isfinite(it->second[j])) return it->second[j];
  return 0.0;
}

VehicleState measuredState(const IdentLog& log, std::size_t i) {
  VehicleState s;
  s.t = log.t[i];
  s.position = {measured(log, "north", i), measured(log, "east", i), measured(log, "down", i)};
  s.yaw = measured(log, "yaw_rad", i);
  s.velocity = {measured(log, "u", i), measured(log, "v", i), measured(log, "w", i)};
  s.angular_rate.z() = measured(log, "r_rad_s", i);
  return s;
}

// Sets the named state components (kLogSignals names) from x.
void applyState(VehicleState& s, const std::vector<std::string>& names, const double* x) {
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string& n = names[k];
    if (n == "north") s.position.x() = x[k];
    else if (n == "east") s.position.y() = x[k];
    else if (n == "down") s.position.z() = x[k];
    else if (n == "yaw_rad") s.yaw = x[k];
    else if (n == "u") s.velocity.x() = x[k];
    else if (n == "v") s.velocity.y() = x[k];
    else if (n == "w") s.velocity.z() = x[k];
    else if (n == "r_rad_s") s.angular_rate.z() = x[k];
  }
}

// Advances a model over one row interval with the command held: equal steps no longer than dt.
template <class M>
void advance(M& m, double span, double dt, const models::Environment& env) {
  if (!(span > 0.0)) return;
  const int n = std::max(1, static_cast<int>(std::ceil(span / dt - 1e-9)));
  for (int k = 0; k < n; ++k) m.step(span / n, env);
}

bool allFinite(const double* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// ---------------------------------------------------------------- USV (both model types)
const Fields<models::UsvParams>& usvFields() {
  static const Fields<models::UsvParams> f{
      {{"X_u", &models::UsvParams::X_u},         {"X_uu", &models::UsvParams::X_uu},       {"X_udot", &models::UsvParams::X_udot},
       {"N_r", &models::UsvParams::N_r},         {"N_rr", &models::UsvParams::N_rr},       {"N_rdot", &models::UsvParams::N_rdot},
       {"Y_v", &models::UsvParams::Y_v},         {"Y_vv", &models::UsvParams::Y_vv},       {"Y_vdot", &models::UsvParams::Y_vdot},
       {"nozzle_delay", &models::UsvParams::nozzle_delay},
       {"nozzle_time_constant", &models::UsvParams::nozzle_time_constant},
       {"surge_kp", &models::UsvParams::surge_kp}, {"surge_tz", &models::UsvParams::surge_tz},
       {"surge_tp1", &models::UsvParams::surge_tp1}, {"surge_tp2", &models::UsvParams::surge_tp2},
       {"surge_td", &models::UsvParams::surge_td}, {"yaw_kp", &models::UsvParams::yaw_kp},   {"yaw_tz", &models::UsvParams::yaw_tz},
       {"yaw_tp1", &models::UsvParams::yaw_tp1},   {"yaw_tp2", &models::UsvParams::yaw_tp2}},
      {{"rpm_num", &models::UsvParams::rpm_num}, {"rpm_den", &models::UsvParams::rpm_den}}};
  return f;
}

// Rows of the USV's parameter tables: key, group, stage, magnitude, delay, nominal, lower bound.
std::vector<FitParameter> usvParameters(const models::UsvParams& p) {
  std::vector<FitParameter> v;
  // eq. 3.24: engine rpm / set-point, second order (the leading denominator coefficient stays as given)
  for (std::size_t i = 0; i < p.rpm_num.size(); ++i)
    v.push_back({"rpm_num[" + std::to_string(i) + "]", "rpm", "rpm", false, false, 1.0, 0.0});
  for (std::size_t i = 1; i < p.rpm_den.size(); ++i)
    v.push_back({"rpm_den[" + std::to_string(i) + "]", "rpm", "rpm", false, false, 1.0, 0.0});
  // eq. 3.25: nozzle delay + first-order lag
  v.push_back({"nozzle_delay", "nozzle", "nozzle", false, true, 0.25, 0.0});
  v.push_back({"nozzle_time_constant", "nozzle", "nozzle", false, false, 0.1, 1e-3});
  if (p.type == models::UsvModelType::Dynamic3Dof) {  // Table 3.4 (+ the sway terms the thesis left open)
    for (const char* k : {"X_u", "X_uu", "X_udot"}) v.push_back({k, "surge", "hull", true, false, 100.0, 0.0});
    for (const char* k : {"Y_v", "Y_vv", "Y_vdot"}) v.push_back({k, "sway", "hull", true, false, 100.0, 0.0});
    for (const char* k : {"N_r", "N_rr", "N_rdot"}) v.push_back({k, "yaw", "hull", true, false, 100.0, 0.0});
  } else {  // Table 3.2
    v.push_back({"surge_kp", "surge", "hull", false, false, 1e-3, -1e300});
    v.push_back({"surge_tz", "surge", "hull", false, false, 0.1, -1e300});
    v.push_back({"surge_tp1", "surge", "hull", false, false, 1.0, 1e-6});
    v.push_back({"surge_tp2", "surge", "hull", false, false, 0.1, 1e-6});
    v.push_back({"surge_td", "surge", "hull", false, true, 0.5, 0.0});
    v.push_back({"yaw_kp", "yaw", "hull", false, false, 1e-5, -1e300});
    v.push_back({"yaw_tz", "yaw", "hull", false, false, 0.1, -1e300});
    v.push_back({"yaw_tp1", "yaw", "hull", false, false, 1.0, 1e-6});
    v.push_back({"yaw_tp2", "yaw", "hull", false, false, 0.01, 1e-6});
  }
  return v;
}

class UsvPlant : public Plant {
 public:
  explicit UsvPlant(const models::UsvParams& p) : p_(p), params_(usvParameters(p)) {
    free_ = p_.type == models::UsvModelType::Dynamic3Dof
                ? std::vector<std::string>{"north", "east", "yaw_rad", "u", "v", "r_rad_s"}
                : std::vector<std::string>{"north", "east", "yaw_rad"};
  }
  std::unique_ptr<Plant> clone() const override { return std::make_unique<UsvPlant>(*this); }
  std::string model() const override { return p_.type == models::UsvModelType::Nomoto ? "nomoto" : "dynamic_3dof"; }
  const std::vector<FitParameter>& parameters() const override { return params_; }
  double get(const std::string& key) const override { return usvFields().ref(const_cast<models::UsvParams&>(p_), key); }
  void set(const std::string& key, double v) override { usvFields().ref(p_, key) = v; }
  const std::vector<std::string>& commands() const override {
    static const std::vector<std::string> c{"surge", "sway", "yaw"};
    return c;
  }
  const std::vector<std::string>& outputs() const override {
    static const std::vector<std::string> o{"north", "east", "yaw_rad", "u", "v", "r_rad_s", "rpm", "nozzle"};
    return o;
  }
  const std::vector<std::string>& freeState() const override { return free_; }
  double warmup(const FitOptions& opt) const override { return opt.warmup; }
  void validate() const override { p_.validate(); }

  bool simulate(const IdentLog& log, const models::Environment& env, double dt, std::size_t warm, std::size_t begin,
                std::size_t end, const double* x0, double* out) const override {
    std::unique_ptr<models::UsvModel> m;
    try {
      m = std::make_unique<models::UsvModel>(p_);
    } catch (const ConfigError&) {
      return false;  // e.g. a trial step made a coefficient invalid: the optimiser tries a smaller step
    }
    m->reset(measuredState(log, warm));
    double* o = out;
    for (std::size_t i = warm; i < end; ++i) {
      if (i == begin && x0) {
        VehicleState s = m->lowFrequencyState();
        applyState(s, free_, x0);
        m->setState(s);
      }
      if (i >= begin) {
        const VehicleState& s = m->state();
        const models::JetState j = m->jet(0);
        const double row[8] = {s.position.x(), s.position.y(), s.yaw, s.velocity.x(), s.velocity.y(),
                               s.angular_rate.z(), j.rpm, j.nozzle};
        std::copy(row, row + 8, o);
        o += 8;
      }
      if (i + 1 < end) {
        const auto c = log.commands.row(static_cast<Eigen::Index>(i));
        m->setCommand({c(0), c(1), c(2)});
        advance(*m, log.t[i + 1] - log.t[i], dt, env);
      }
    }
    return m->counters().get("non_finite_state") == 0 && allFinite(out, (end - begin) * 8);
  }

  std::map<std::string, std::vector<double>> excitation(const IdentLog& log, const models::Environment& env, double dt,
                                                        std::size_t begin, std::size_t end) const override {
    std::map<std::string, std::vector<double>> x;
    models::UsvModel m(p_);
    m.reset(measuredState(log, begin));
    for (std::size_t i = begin; i < end; ++i) {
      const auto c = log.commands.row(static_cast<Eigen::Index>(i));
      m.setCommand({c(0), c(1), c(2)});
      x["rpm"].push_back(m.rpmSetpoint(c(0)));
      x["nozzle"].push_back(m.nozzleSetpoint(c(2)));
      if (i + 1 < end) advance(m, log.t[i + 1] - log.t[i], dt, env);
      if (p_.type == models::UsvModelType::Dynamic3Dof) {
        x["surge"].push_back(m.tau()(0));
        x["yaw"].push_back(m.tau()(2));
      } else {  // the identified transfer functions' inputs: bucket-signed rpm, nozzle position
        x["surge"].push_back(m.jet(0).rpm * m.jet(0).bucket);
        x["yaw"].push_back(m.jet(0).nozzle);
      }
    }
    return x;
  }

 private:
  models::UsvParams p_;
  std::vector<FitParameter> params_;
  std::vector<std::string> free_;
};

// ---------------------------------------------------------------- AUV (Girona500, aColor)
const Fields<models::AuvParams>& auvFields() {
  static const Fields<models::AuvParams> f{{{"X_u", &models::AuvParams::X_u},       {"X_uu", &models::AuvParams::X_uu},
                                    {"X_udot", &models::AuvParams::X_udot}, {"Y_v", &models::AuvParams::Y_v},
                                    {"Y_vv", &models::AuvParams::Y_vv},     {"Y_vdot", &models::AuvParams::Y_vdot},
                                    {"Z_w", &models::AuvParams::Z_w},       {"Z_ww", &models::AuvParams::Z_ww},
                                    {"Z_wdot", &models::AuvParams::Z_wdot}, {"N_r", &models::AuvParams::N_r},
                                    {"N_rr", &models::AuvParams::N_rr},     {"N_rdot", &models::AuvParams::N_rdot}},
                                   {}};
  return f;
}

class AuvPlant : public Plant {
 public:
  explicit AuvPlant(const models::AuvParams& p) : p_(p) {
    const std::pair<const char*, const char*> axes[4] = {{"X", "surge"}, {"Y", "sway"}, {"Z", "heave"}, {"N", "yaw"}};
    const char* vel[4] = {"u", "v", "w", "r"};
    for (int a = 0; a < 4; ++a) {  // Table 3.4: linear, quadratic damping and added mass per axis
      const std::string base = std::string(axes[a].first) + "_" + vel[a];
      for (const std::string& k : {base, base + vel[a], std::string(axes[a].first) + "_" + vel[a] + "dot"})
        params_.push_back({k, axes[a].second, "hull", true, false, 10.0, 0.0});
    }
    for (std::size_t i = 0; i < p_.thrusters.size(); ++i) commands_.push_back("c" + std::to_string(i + 1));
  }
  std::unique_ptr<Plant> clone() const override { return std::make_unique<AuvPlant>(*this); }
  std::string model() const override { return "auv_4dof"; }
  const std::vector<FitParameter>& parameters() const override { return params_; }
  double get(const std::string& key) const override { return auvFields().ref(const_cast<models::AuvParams&>(p_), key); }
  void set(const std::string& key, double v) override { auvFields().ref(p_, key) = v; }
  const std::vector<std::string>& commands() const override { return commands_; }
  const std::vector<std::string>& outputs() const override {
    static const std::vector<std::string> o{"north", "east", "down", "yaw_rad", "u", "v", "w", "r_rad_s"};
    return o;
  }
  const std::vector<std::string>& freeState() const override { return outputs(); }
  double warmup(const FitOptions&) const override { return 0.0; }  // thrusters act at once (static curves)
  void validate() const override { p_.validate(); }

  bool simulate(const IdentLog& log, const models::Environment& env, double dt, std::size_t warm, std::size_t begin,
                std::size_t end, const double* x0, double* out) const override {
    std::unique_ptr<models::AuvModel> m;
    try {
      m = std::make_unique<models::AuvModel>(p_);
    } catch (const ConfigError&) {
      return false;
    }
    m->reset(measuredState(log, warm));
    const Eigen::Index n = static_cast<Eigen::Index>(commands_.size());
    double* o = out;
    for (std::size_t i = warm; i < end; ++i) {
      if (i == begin && x0) {
        VehicleState s = m->lowFrequencyState();
        applyState(s, outputs(), x0);
        m->reset(s);
      }
      if (i >= begin) {
        const VehicleState& s = m->state();
        const double row[8] = {s.position.x(), s.position.y(), s.position.z(), s.yaw,
                               s.velocity.x(), s.velocity.y(), s.velocity.z(), s.angular_rate.z()};
        std::copy(row, row + 8, o);
        o += 8;
      }
      if (i + 1 < end) {
        m->setCommand(log.commands.row(static_cast<Eigen::Index>(i)).head(n).transpose());
        advance(*m, log.t[i + 1] - log.t[i], dt, env);
      }
    }
    return allFinite(out, (end - begin) * 8);
  }

  std::map<std::string, std::vector<double>> excitation(const IdentLog& log, const models::Environment&, double,
                                                        std::size_t begin, std::size_t end) const override {
    const models::AuvModel m(p_);
    std::map<std::string, std::vector<double>> x;
    const char* groups[4] = {"surge", "sway", "heave", "yaw"};
    Eigen::VectorXd f(m.thrusters());
    for (std::size_t i = begin; i < end; ++i) {
      for (int k = 0; k < m.thrusters(); ++k) f(k) = m.thrust(k, log.commands(static_cast<Eigen::Index>(i), k));
      const Eigen::Vector4d tau = m.tcm() * f;  // eq. 3.16
      for (int a = 0; a < 4; ++a) x[groups[a]].push_back(tau(a));
    }
    return x;
  }

 private:
  models::AuvParams p_;
  std::vector<FitParameter> params_;
  std::vector<std::string> commands_;
};

}  // namespace

std::unique_ptr<Plant> makePlant(FitVehicle v, const std::string& yaml_text, const std::string& source) {
  if (v == FitVehicle::Usv) return std::make_unique<UsvPlant>(models::usvParamsFromYaml(yaml_text, source));
  const models::AuvParams p = models::auvParamsFromYaml(yaml_text, source);
  const bool acolor = p.type == models::AuvType::AColor;
  if (acolor != (v == FitVehicle::AColor))
    throw ConfigError(source + ": the file is for the " + (acolor ? "acolor" : "girona500") +
                      ", not the vehicle asked for (" + fitVehicleName(v) + ")");
  return std::make_unique<AuvPlant>(p);
}

}  // namespace ident
}  // namespace identification
}  // namespace offshore_gnc
