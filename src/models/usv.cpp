// Twin-waterjet USV: waterjet chain (eq. 3.11-3.13, 3.24, 3.25) and 3-DOF dynamics (eq. 3.3-3.10), or the
// identified transfer functions (Table 3.2).
#include "offshore_gnc/models/usv.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/integrator.h"
#include "offshore_gnc/models/joystick_allocation.h"

namespace offshore_gnc {
namespace models {

namespace {
constexpr double kKnot = 1852.0 / 3600.0;  // [m/s]
using Vec6 = Eigen::Matrix<double, 6, 1>;

// (Tp1 s + 1)(Tp2 s + 1) and Kp (Tz s + 1): Table 3.2's transfer functions.
TransferFunction secondOrder(const char* name, double kp, double tz, double tp1, double tp2) {
  return TransferFunction(name, {kp * tz, kp}, {tp1 * tp2, tp1 + tp2, 1.0});
}
}  // namespace

double UsvParams::inertiaZ() const {
  const double rear = m_pt * l_pt * l_pt + (m_hull * c_g / 3.0) * l_pivot * l_pivot;            // eq. 3.5
  const double front = m_hull * (1.0 - c_g) / 3.0 * kappa * std::pow(length - l_pivot, 2);      // eq. 3.6
  return (rear + front) * i_cor;                                                                 // eq. 3.7
}

void UsvParams::validate() const {
  requireRange("mass", mass, 10.0, 1e6);
  requireRange("m_pt", m_pt, 0.0, mass);
  requireRange("m_hull", m_hull, 0.0, mass);
  requireRange("length", length, 0.5, 200.0);
  requireRange("l_pivot", l_pivot, 0.0, length);
  requireRange("l_pt", l_pt, 0.0, length);
  requireRange("kappa", kappa, 0.0, 2.0);
  requireRange("c_g", c_g, 0.0, 1.0);
  requireRange("i_cor", i_cor, 0.01, 10.0);
  requireRange("x_g", x_g, -length, length);
  for (auto [n, v] : {std::pair<const char*, double>{"X_u", X_u}, {"X_udot", X_udot}, {"X_uu", X_uu}, {"N_r", N_r},
                      {"N_rdot", N_rdot}, {"N_rr", N_rr}, {"Y_v", Y_v}, {"Y_vdot", Y_vdot}, {"Y_vv", Y_vv},
                      {"Y_r", Y_r}, {"Y_rdot", Y_rdot}})
    requireRange(n, v, -1e7, 1e7);
  if (std::abs(X_u) + std::abs(X_uu) <= 0.0) throw ConfigError("parameter 'X_u'/'X_uu': surge needs damping");
  if (std::abs(N_r) + std::abs(N_rr) <= 0.0) throw ConfigError("parameter 'N_r'/'N_rr': yaw needs damping");
  if (std::abs(Y_v) + std::abs(Y_vv) <= 0.0) throw ConfigError("parameter 'Y_v'/'Y_vv': sway needs damping");
  requireRange("rpm_ref", rpm_ref, 1.0, 1e5);
  requireRange("rpm_min", rpm_min, 0.0, rpm_ref);
  requireRange("rpm_max", rpm_max, rpm_ref, 1e5);
  if (table_speed_kt.size() < 2 || table_speed_kt.size() != table_thrust_kn.size())
    throw ConfigError("parameter 'table_speed_kt'/'table_thrust_kn': need >= 2 points of equal count");
  for (double f : table_thrust_kn) requireRange("table_thrust_kn", f, 0.0, 1e4);
  Lookup1D("table_speed_kt", table_speed_kt, table_thrust_kn);
  Lookup1D("joy_u", joy_u, joy_u_rpm);
  Lookup1D("joy_r", joy_r, joy_r_nozzle);
  for (double r : joy_u_rpm) requireRange("joy_u_rpm", r, 0.0, rpm_max);
  requireRange("joy_u_full", joy_u_full, 1.0, 1e6);
  requireRange("joy_r_full", joy_r_full, 1.0, 1e6);
  requireRange("bucket_band", bucket_band, 1e-3, 1.0);
  requireRange("jet_y", jet_y, 0.01, 10.0);
  requireRange("bucket_rate", bucket_rate, 0.01, 100.0);
  requireRange("yaw_rpm_share", yaw_rpm_share, 0.0, 1.0);
  requireRange("reverse_efficiency", reverse_efficiency, 0.0, 1.0);
  requireRange("nozzle_delay", nozzle_delay, 0.0, 10.0);
  requireRange("nozzle_time_constant", nozzle_time_constant, 1e-3, 100.0);
  requireRange("nozzle_max", nozzle_max, 1.0, 1e6);
  for (double p : joy_r_nozzle) requireRange("joy_r_nozzle", p, -nozzle_max, nozzle_max);
  requireRange("nozzle_max_angle", nozzle_max_angle, 0.0, kPi / 2);
  requireRange("nozzle_eff_a", nozzle_eff_a, 0.0, 2.0);
  requireRange("nozzle_eff_b", nozzle_eff_b, -1.0, 0.0);
  requireRange("surge_kp", surge_kp, -1.0, 1.0);
  requireRange("surge_tz", surge_tz, -100.0, 100.0);
  requirePositive("surge_tp1", surge_tp1);
  requirePositive("surge_tp2", surge_tp2);
  requireRange("surge_td", surge_td, 0.0, 10.0);
  requireRange("yaw_kp", yaw_kp, -1.0, 1.0);
  requireRange("yaw_tz", yaw_tz, -100.0, 100.0);
  requirePositive("yaw_tp1", yaw_tp1);
  requirePositive("yaw_tp2", yaw_tp2);
  requireRange("wind_area_front", wind_area_front, 0.0, 1e4);
  requireRange("wind_area_side", wind_area_side, 0.0, 1e4);
  requireRange("wind_cx", wind_cx, 0.0, 5.0);
  requireRange("wind_cy", wind_cy, 0.0, 5.0);
  requireRange("wind_cn", wind_cn, -1.0, 1.0);
  requireRange("max_step", max_step, 1e-4, 0.1);
  TransferFunction("rpm_tf", rpm_num, rpm_den);
}

// Table 3.1 (linearly extrapolated to 0 and 12 kt, never negative) x affinity law.
Lookup2D makeThrustTable(const UsvParams& p) {
  const Lookup1D ref("table_speed_kt", p.table_speed_kt, p.table_thrust_kn);
  const auto& sk = p.table_speed_kt;
  const auto& fk = p.table_thrust_kn;
  auto thrustAt = [&](double kt) {
    std::size_t i = kt < sk.front() ? 0 : (kt > sk.back() ? sk.size() - 2 : sk.size());
    if (i == sk.size()) return ref(kt) * 1000.0;
    const double slope = (fk[i + 1] - fk[i]) / (sk[i + 1] - sk[i]);
    return std::max(0.0, fk[i] + slope * (kt - sk[i])) * 1000.0;
  };
  std::vector<double> speeds, rpms, z;
  for (double kt = 0.0; kt <= std::max(12.0, sk.back()) + 1e-9; kt += 0.5) speeds.push_back(kt * kKnot);
  for (double r = p.rpm_min; r < p.rpm_max + 1e-9; r += (p.rpm_max - p.rpm_min) / 36.0) rpms.push_back(r);
  if (rpms.front() > 0.0) rpms.insert(rpms.begin(), 0.0);
  for (double s : speeds)
    for (double r : rpms) z.push_back(thrustAt(s / kKnot) * std::pow(r / p.rpm_ref, 2));  // eq. 3.11
  return Lookup2D("waterjet_thrust", speeds, rpms, z);
}

UsvModel::~UsvModel() = default;

UsvModel::UsvModel(const UsvParams& p) : p_(p) {
  p_.validate();
  const double iz = p_.inertiaZ();
  Eigen::Matrix3d m;
  const double mxg = p_.mass * p_.x_g + std::abs(p_.Y_rdot);
  m << p_.mass + std::abs(p_.X_udot), 0, 0,  //
      0, p_.mass + std::abs(p_.Y_vdot), mxg,  //
      0, mxg, iz + std::abs(p_.N_rdot);       // eq. 3.4
  if (std::abs(m.determinant()) < 1e-9) throw ConfigError("parameter 'mass': singular mass matrix");
  m_inv_ = m.inverse();
  joy_rpm_ = Lookup1D("joy_u", p_.joy_u, p_.joy_u_rpm);
  joy_nozzle_ = Lookup1D("joy_r", p_.joy_r, p_.joy_r_nozzle);
  thrust_ = makeThrustTable(p_);
  if (p_.propulsion == UsvPropulsion::Twin && p_.type == UsvModelType::Dynamic3Dof) {
    allocation_ = std::make_unique<JoystickAllocation>(p_);
    twin_ = std::make_unique<TwinWaterjets>(p_);
  }
  rpm_tf_ = TransferFunction("rpm_tf", p_.rpm_num, p_.rpm_den);
  nozzle_lag_ = TransferFunction("nozzle_lag", {1.0}, {p_.nozzle_time_constant, 1.0});
  nozzle_delay_ = TransportDelay(p_.nozzle_delay);
  surge_tf_ = secondOrder("surge_tf", p_.surge_kp, p_.surge_tz, p_.surge_tp1, p_.surge_tp2);
  yaw_tf_ = secondOrder("yaw_tf", p_.yaw_kp, p_.yaw_tz, p_.yaw_tp1, p_.yaw_tp2);
  surge_delay_ = TransportDelay(p_.surge_td);
  reset(VehicleState());
}

double UsvModel::jetThrust(double u, double rpm) const { return thrust_(std::max(0.0, u), rpm); }
double UsvModel::rpmSetpoint(double surge) const { return joy_rpm_(std::abs(surge) * p_.joy_u_full); }
double UsvModel::nozzleSetpoint(double yaw) const {
  return std::copysign(joy_nozzle_(std::abs(yaw) * p_.joy_r_full), yaw);
}
double UsvModel::bucket(double surge) const { return std::clamp(surge / p_.bucket_band, -1.0, 1.0); }
double UsvModel::nozzleEfficiency(double nozzle) const {
  return p_.nozzle_eff_a * std::exp(p_.nozzle_eff_b * std::abs(nozzle));  // eq. 3.12, symmetric
}

void UsvModel::reset(const VehicleState& s) {
  if (!isFinite(s)) {
    counters_.increment("rejected_states");
    return;
  }
  lf_ = s;
  lf_.roll = lf_.pitch = 0.0;
  lf_.position.z() = 0.0;
  lf_.velocity.z() = 0.0;
  lf_.angular_rate.x() = lf_.angular_rate.y() = 0.0;
  lf_.yaw = wrapAngle(lf_.yaw);
  cmd_ = UsvCommand();
  rpm_tf_.reset(p_.rpm_min);
  nozzle_lag_.reset(0.0);
  nozzle_delay_.reset(0.0);
  // Nomoto: start the identified transfer functions at the equilibrium of the initial speed and yaw rate.
  const double rpm_eq = std::abs(p_.surge_kp) > 0 ? lf_.velocity.x() / p_.surge_kp : 0.0;
  surge_tf_.reset(rpm_eq);
  surge_delay_.reset(rpm_eq);
  yaw_tf_.reset(std::abs(p_.yaw_kp) > 0 ? lf_.angular_rate.z() / p_.yaw_kp : 0.0);
  for (auto& j : jets_) j = JetState{p_.rpm_min, 0.0, 0.0, 0.0};
  if (twin_) twin_->reset();
  tau_.setZero();
  tau_wind_.setZero();
  drift_.setZero();
  updateOutput(Environment());
}

void UsvModel::setState(const VehicleState& s) {
  if (!isFinite(s)) {
    counters_.increment("rejected_states");
    return;
  }
  lf_.position = {s.position.x(), s.position.y(), 0.0};
  lf_.yaw = wrapAngle(s.yaw);
  if (p_.type == UsvModelType::Dynamic3Dof) {
    lf_.velocity = {s.velocity.x(), s.velocity.y(), 0.0};
    lf_.angular_rate.z() = s.angular_rate.z();
  }
  updateOutput(Environment());
}

bool UsvModel::setCommand(const UsvCommand& c) {
  if (!std::isfinite(c.surge) || !std::isfinite(c.sway) || !std::isfinite(c.yaw)) {
    counters_.increment("rejected_commands");
    return false;
  }
  if (std::abs(c.surge) > 1.0 || std::abs(c.sway) > 1.0 || std::abs(c.yaw) > 1.0)
    counters_.increment("clamped_commands");
  cmd_ = {std::clamp(c.surge, -1.0, 1.0), std::clamp(c.sway, -1.0, 1.0), std::clamp(c.yaw, -1.0, 1.0)};
  if (twin_) twin_->setCommands(allocation_->allocate(cmd_));  // the CCPilot's joystick allocation
  return true;
}

bool UsvModel::setJetCommands(const JetCommands& c) {
  if (!twin_) {
    counters_.increment("unsupported_jet_commands");
    return false;
  }
  for (const auto& j : c) {
    if (!std::isfinite(j.rpm) || !std::isfinite(j.nozzle) || !std::isfinite(j.bucket)) {
      counters_.increment("rejected_commands");
      return false;
    }
    if (j.rpm < p_.rpm_min || j.rpm > p_.rpm_max || std::abs(j.nozzle) > p_.nozzle_max || std::abs(j.bucket) > 1.0)
      counters_.increment("clamped_commands");
  }
  twin_->setCommands(c);
  return true;
}

JetState UsvModel::jet(int i) const { return twin_ ? twin_->state()[i == 0 ? 0 : 1] : jets_[i == 0 ? 0 : 1]; }

void UsvModel::step(double dt, const Environment& env) {
  if (!std::isfinite(dt) || dt <= 0.0 || dt > 10.0) {
    counters_.increment("rejected_steps");
    return;
  }
  const double t0 = lf_.t;
  const VehicleState before = lf_;
  // Actuator chains advance first with the command held over the step (zero-order hold, exact).
  const double bucket_pos = bucket(cmd_.surge);
  const double bucket_gain = bucket_pos >= 0.0 ? bucket_pos : bucket_pos * p_.reverse_efficiency;
  const double rpm = std::clamp(rpm_tf_.step(dt, rpmSetpoint(cmd_.surge)), 0.0, p_.rpm_max);
  const double nozzle = std::clamp(-nozzle_lag_.step(dt, nozzle_delay_.push(t0, nozzleSetpoint(cmd_.yaw))),
                                   -p_.nozzle_max, p_.nozzle_max);  // eq. 3.25 (minus sign)
  const double eff = nozzleEfficiency(nozzle);
  const double alpha = p_.nozzle_max_angle * nozzle / p_.nozzle_max;
  const Eigen::Vector3d vc = env.current(t0);

  if (p_.type == UsvModelType::Nomoto) {
    // Identified models: speed through the water from the (bucket-signed) rpm, yaw rate from the nozzle.
    const double u = surge_tf_.step(dt, surge_delay_.push(t0, rpm * bucket_gain));
    const double r = yaw_tf_.step(dt, nozzle);
    const double r0 = lf_.angular_rate.z();
    const double u0 = lf_.velocity.x();
    const int n = substeps(dt, p_.max_step);
    const double h = dt / n;
    for (int k = 0; k < n; ++k) {  // u, r interpolated linearly over the step (trapezoidal kinematics)
      const double a = (k + 0.5) / n;
      const double yaw_mid = lf_.yaw + 0.5 * h * (r0 + a * (r - r0));
      const double um = u0 + a * (u - u0);
      lf_.position.x() += h * (std::cos(yaw_mid) * um + vc.x());
      lf_.position.y() += h * (std::sin(yaw_mid) * um + vc.y());
      lf_.yaw += h * (r0 + a * (r - r0));
    }
    const double c = std::cos(lf_.yaw), sn = std::sin(lf_.yaw);  // report velocity over ground, body axes
    lf_.velocity = {u + c * vc.x() + sn * vc.y(), -sn * vc.x() + c * vc.y(), 0.0};
    lf_.angular_rate.z() = r;
    tau_.setZero();
  } else {
    const Eigen::Vector2d wind = env.wind(t0);
    const double rho_a = env.params().air_density;
    // the mean wave drift force, held over the step (it changes with the heading slowly)
    drift_ = env.driftForce(lf_.yaw, hull(p_));
    auto deriv = [&](const Vec6& x) {
      // x = [N, E, psi, u, v, r]; u, v over ground in body axes; damping acts on the relative velocity.
      const double c = std::cos(x(2)), s = std::sin(x(2));
      const double ur = x(3) - (c * vc.x() + s * vc.y());
      const double vr = x(4) - (-s * vc.x() + c * vc.y());
      const double r = x(5);
      Eigen::Vector3d tau;
      if (twin_) {
        tau = twin_->force(ur);  // jet by jet
      } else {
        const double f_total = 2.0 * jetThrust(ur, rpm) * bucket_gain * eff;
        tau = Eigen::Vector3d(f_total, 0.0, -p_.l_pivot * std::sin(alpha) * f_total);  // eq. 3.13
      }
      // Wind: quadratic drag on the relative air velocity (Fossen-style coefficients, docs/models.md).
      const double uw = c * wind.x() + s * wind.y() - x(3), vw = -s * wind.x() + c * wind.y() - x(4);
      const double q = 0.5 * rho_a * (uw * uw + vw * vw);
      const double gamma = std::atan2(vw, uw);
      const Eigen::Vector3d tw(0.5 * rho_a * p_.wind_cx * p_.wind_area_front * uw * std::abs(uw),
                               0.5 * rho_a * p_.wind_cy * p_.wind_area_side * vw * std::abs(vw),
                               p_.wind_cn * p_.wind_area_side * p_.length * q * std::sin(2.0 * gamma));
      const Eigen::Vector3d damping(std::abs(p_.X_u) * ur + std::abs(p_.X_uu) * std::abs(ur) * ur,
                                    std::abs(p_.Y_v) * vr + std::abs(p_.Y_vv) * std::abs(vr) * vr +
                                        std::abs(p_.Y_r) * r,
                                    std::abs(p_.Y_r) * vr + std::abs(p_.N_r) * r + std::abs(p_.N_rr) * std::abs(r) * r);
      const Eigen::Vector3d td(c * drift_.x() + s * drift_.y(), -s * drift_.x() + c * drift_.y(), 0.0);
      const Eigen::Vector3d nu_dot = m_inv_ * (tau + tw + td - damping);  // eq. 3.3 without C (thesis 3.2.2)
      Vec6 d;
      d << c * x(3) - s * x(4), s * x(3) + c * x(4), r, nu_dot;
      tau_ = tau;
      tau_wind_ = tw;
      return d;
    };
    if (twin_) twin_->step(t0, dt);  // the jets' chains, commands held over the step (as the lumped chain above)
    Vec6 x;
    x << lf_.position.x(), lf_.position.y(), lf_.yaw, lf_.velocity.x(), lf_.velocity.y(), lf_.angular_rate.z();
    const int n = substeps(dt, p_.max_step);
    for (int k = 0; k < n; ++k) x = rk4(x, dt / n, deriv);
    deriv(x);  // tau_ / tau_wind_ at the end of the step
    lf_.position.x() = x(0);
    lf_.position.y() = x(1);
    lf_.yaw = x(2);
    lf_.velocity = {x(3), x(4), 0.0};
    lf_.angular_rate.z() = x(5);
  }
  lf_.yaw = wrapAngle(lf_.yaw);
  lf_.t = t0 + dt;
  const double per_jet = jetThrust(lf_.velocity.x(), rpm) * bucket_gain * eff;
  for (auto& j : jets_) j = JetState{rpm, nozzle, bucket_pos, per_jet};
  if (twin_) twin_->updateThrust(lf_.velocity.x());
  if (!isFinite(lf_)) {  // cannot happen with validated parameters; never publish NaN if it does
    counters_.increment("non_finite_state");
    lf_ = before;
    lf_.t = t0 + dt;
  }
  updateOutput(env);
}

void UsvModel::updateOutput(const Environment& env) { out_ = withWave(lf_, env.wave(lf_.t, lf_, hull(p_))); }

}  // namespace models
}  // namespace offshore_gnc
