// 4-DOF AUV (eq. 3.14-3.22) with thruster curves and the thruster configuration matrix (eq. 3.16-3.18).
#include "offshore_gnc/models/auv.h"

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/integrator.h"

namespace offshore_gnc {
namespace models {

namespace {
using Vec8 = Eigen::Matrix<double, 8, 1>;
constexpr double kEmergence = 0.1;  // [m] of hull above the water over which the buoyancy fades out

Thruster makeThruster(const char* name, Eigen::Vector3d pos, Eigen::Vector3d dir) {
  Thruster t;
  t.name = name;
  t.position = pos;
  t.direction = dir;
  return t;
}
}  // namespace

Eigen::VectorXd mixAxes(const Eigen::MatrixXd& tcm, const Eigen::Vector4d& axes) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(tcm.cols());
  for (int axis = 0; axis < 4; ++axis) {
    const double scale = tcm.row(axis).cwiseAbs().maxCoeff();
    if (scale > 1e-9) out += (axes[axis] / scale) * tcm.row(axis).transpose();
  }
  return out.cwiseMax(-1.0).cwiseMin(1.0);
}

AuvParams AuvParams::girona500() {
  AuvParams p;
  const double ly1 = 0.2432, ly2 = 0.2432;  // Table 3.3
  // eq. 3.18: surge thrusters push astern for a positive command (-1 in the X row), heave thrusters up.
  p.thrusters = {makeThruster("T1_port_surge", {-0.5, -ly1, 0.0}, {-1, 0, 0}),
                 makeThruster("T2_starboard_surge", {-0.5, ly2, 0.0}, {-1, 0, 0}),
                 makeThruster("T3_heave_bow", {0.4, 0.0, 0.0}, {0, 0, -1}),
                 makeThruster("T4_heave_stern", {-0.4, 0.0, 0.0}, {0, 0, -1}),
                 makeThruster("T5_sway", {0.0, 0.0, 0.0}, {0, 1, 0})};
  // The surge propellers are mounted to be efficient ahead, which eq. 3.18 calls a negative command: mirror
  // their curve so the strong branch drives the vehicle forward.
  for (int i = 0; i < 2; ++i) {
    auto& t = p.thrusters[i];
    const std::vector<double> thrust = t.curve_thrust;
    for (std::size_t k = 0; k < thrust.size(); ++k) t.curve_thrust[k] = -thrust[thrust.size() - 1 - k];
  }
  return p;
}

AuvParams AuvParams::aColor() {
  // Assumed: a BlueROV2 Heavy-class frame with 6 T200 thrusters (Wu 2018 identification), because the
  // thesis gives no aColor mass or damping (Table 3.3/3.4 cover the Girona500 only). See docs/models.md.
  AuvParams p;
  p.type = AuvType::AColor;
  p.mass = 11.5;
  p.volume = 0.0116;  // slightly positive in fresh water: W = 112.8 N, B = 113.8 N
  p.I_z = 0.26;
  p.X_u = 4.03, p.X_udot = -5.5, p.X_uu = 62.0;  // X_uu: 1.5 m/s top speed (docs)
  p.Y_v = 6.22, p.Y_vdot = -12.7, p.Y_vv = 21.66;
  p.Z_w = 5.18, p.Z_wdot = -14.57, p.Z_ww = 36.99;
  p.N_r = 0.07, p.N_rdot = -0.12, p.N_rr = 1.55;
  const double c = std::sqrt(0.5);
  // T1..T4 vectored at 45 degrees in the horizontal plane (surge, sway, yaw), T5/T6 vertical (heave, roll).
  p.thrusters = {makeThruster("T1_front_starboard", {0.156, 0.111, 0.0}, {c, -c, 0}),
                 makeThruster("T2_front_port", {0.156, -0.111, 0.0}, {c, c, 0}),
                 makeThruster("T3_rear_starboard", {-0.156, 0.111, 0.0}, {c, c, 0}),
                 makeThruster("T4_rear_port", {-0.156, -0.111, 0.0}, {c, -c, 0}),
                 makeThruster("T5_vertical_starboard", {0.0, 0.218, 0.0}, {0, 0, -1}),
                 makeThruster("T6_vertical_port", {0.0, -0.218, 0.0}, {0, 0, -1})};
  return p;
}

void AuvParams::validate() const {
  requireRange("mass", mass, 0.1, 1e5);
  requireRange("volume", volume, 1e-5, 1e3);
  requireRange("I_z", I_z, 1e-4, 1e6);
  requireRange("gravity", gravity, 9.0, 10.0);
  for (auto [n, v] : {std::pair<const char*, double>{"X_u", X_u}, {"X_udot", X_udot}, {"X_uu", X_uu},
                      {"Y_v", Y_v}, {"Y_vdot", Y_vdot}, {"Y_vv", Y_vv}, {"Z_w", Z_w}, {"Z_wdot", Z_wdot},
                      {"Z_ww", Z_ww}, {"N_r", N_r}, {"N_rdot", N_rdot}, {"N_rr", N_rr}})
    requireRange(n, v, -1e6, 1e6);
  if (std::abs(X_u) + std::abs(X_uu) <= 0 || std::abs(Y_v) + std::abs(Y_vv) <= 0 ||
      std::abs(Z_w) + std::abs(Z_ww) <= 0 || std::abs(N_r) + std::abs(N_rr) <= 0)
    throw ConfigError("parameter 'X_u'/'Y_v'/'Z_w'/'N_r': every axis needs linear or quadratic damping");
  if (thrusters.empty() || thrusters.size() > 16)
    throw ConfigError("parameter 'thrusters' must list 1..16 thrusters");
  for (std::size_t i = 0; i < thrusters.size(); ++i) {
    const Thruster& t = thrusters[i];
    const std::string n = "thrusters[" + std::to_string(i) + "]";
    if (!t.position.allFinite() || t.position.norm() > 100.0)
      throw ConfigError("parameter '" + n + "/position' must be finite and within 100 m");
    if (!t.direction.allFinite() || std::abs(t.direction.norm() - 1.0) > 1e-3)
      throw ConfigError("parameter '" + n + "/direction' must be a unit vector");
    Lookup1D(n + "/curve_command", t.curve_command, t.curve_thrust);
    if (t.curve_command.front() > -1.0 + 1e-9 || t.curve_command.back() < 1.0 - 1e-9)
      throw ConfigError("parameter '" + n + "/curve_command' must cover -1..1");
    for (std::size_t k = 1; k < t.curve_thrust.size(); ++k)
      if (t.curve_thrust[k] < t.curve_thrust[k - 1])
        throw ConfigError("parameter '" + n + "/curve_thrust' must be non-decreasing");
    for (double f : t.curve_thrust) requireRange(n + "/curve_thrust", f, -1e5, 1e5);
  }
  requireRange("max_step", max_step, 1e-4, 0.1);
}

Eigen::MatrixXd AuvParams::tcm() const {
  Eigen::MatrixXd t(4, thrusters.size());
  for (std::size_t i = 0; i < thrusters.size(); ++i) {
    const auto& p = thrusters[i].position;
    const auto& d = thrusters[i].direction;
    t.col(i) << d.x(), d.y(), d.z(), p.x() * d.y() - p.y() * d.x();  // N = (r x F)_z
  }
  return t;
}

Eigen::VectorXd AuvParams::maxThrust() const {
  Eigen::VectorXd m(thrusters.size());
  for (std::size_t i = 0; i < thrusters.size(); ++i)
    m(i) = std::max(std::abs(thrusters[i].curve_thrust.front()), std::abs(thrusters[i].curve_thrust.back()));
  return m;
}

AuvModel::AuvModel(const AuvParams& p) : p_(p) {
  p_.validate();
  tcm_ = p_.tcm();
  // eq. 3.15 (diagonal), 3.19, 3.20; magnitudes of Table 3.4 (docs/models.md)
  m_ << p_.mass + std::abs(p_.X_udot), p_.mass + std::abs(p_.Y_vdot), p_.mass + std::abs(p_.Z_wdot),
      p_.I_z + std::abs(p_.N_rdot);
  d_lin_ << std::abs(p_.X_u), std::abs(p_.Y_v), std::abs(p_.Z_w), std::abs(p_.N_r);
  d_quad_ << std::abs(p_.X_uu), std::abs(p_.Y_vv), std::abs(p_.Z_ww), std::abs(p_.N_rr);
  for (std::size_t i = 0; i < p_.thrusters.size(); ++i)
    curves_.emplace_back("thrusters[" + std::to_string(i) + "]", p_.thrusters[i].curve_command,
                         p_.thrusters[i].curve_thrust);
  reset(VehicleState());
}

Eigen::Vector2d AuvModel::waterVelocityStep(const Eigen::Vector2d& v, const Eigen::Vector2d& force, double dt) const {
  auto step = [dt](double u, double f, double mass, double lin, double quad) {
    return (u + dt * f / mass) / (1.0 + dt * (std::abs(lin) + std::abs(quad) * std::abs(u)) / mass);
  };
  return {step(v.x(), force.x(), p_.mass - p_.X_udot, p_.X_u, p_.X_uu),
          step(v.y(), force.y(), p_.mass - p_.Y_vdot, p_.Y_v, p_.Y_vv)};
}

double AuvModel::thrust(int i, double command) const {
  if (i < 0 || i >= thrusters() || !std::isfinite(command)) return 0.0;
  return curves_[i](std::clamp(command, -1.0, 1.0));  // the curve's ends are the saturation
}

double AuvModel::commandFor(int i, double f) const {
  if (i < 0 || i >= thrusters() || !std::isfinite(f) || f == 0.0) return 0.0;
  const auto& c = curves_[i].x();
  const auto& t = curves_[i].y();
  // First segment (searching away from the dead band) whose thrust range contains f.
  if (f > 0.0) {
    for (std::size_t k = 0; k + 1 < t.size(); ++k)
      if (t[k + 1] >= f && t[k + 1] > t[k] && t[k] <= f) return c[k] + (f - t[k]) / (t[k + 1] - t[k]) * (c[k + 1] - c[k]);
  } else {
    for (std::size_t k = t.size() - 1; k > 0; --k)
      if (t[k - 1] <= f && t[k] > t[k - 1] && t[k] >= f) return c[k] + (f - t[k]) / (t[k - 1] - t[k]) * (c[k - 1] - c[k]);
  }
  return f > 0.0 ? (t.back() > 0.0 ? c.back() : 0.0) : (t.front() < 0.0 ? c.front() : 0.0);  // saturated
}

void AuvModel::reset(const VehicleState& s) {
  if (!isFinite(s)) {
    counters_.increment("rejected_states");
    return;
  }
  lf_ = s;
  lf_.roll = lf_.pitch = 0.0;
  lf_.angular_rate.x() = lf_.angular_rate.y() = 0.0;
  lf_.yaw = wrapAngle(lf_.yaw);
  cmd_ = Eigen::VectorXd::Zero(thrusters());
  f_ = Eigen::VectorXd::Zero(thrusters());
  for (int i = 0; i < thrusters(); ++i) f_(i) = thrust(i, 0.0);
  out_ = lf_;
}

bool AuvModel::setCommand(const Eigen::VectorXd& c) {
  if (c.size() != thrusters() || !c.allFinite()) {
    counters_.increment("rejected_commands");
    return false;
  }
  if ((c.array().abs() > 1.0).any()) counters_.increment("clamped_commands");
  cmd_ = c.cwiseMax(-1.0).cwiseMin(1.0);
  for (int i = 0; i < thrusters(); ++i) f_(i) = thrust(i, cmd_(i));
  return true;
}

void AuvModel::step(double dt, const Environment& env) {
  if (!std::isfinite(dt) || dt <= 0.0 || dt > 10.0) {
    counters_.increment("rejected_steps");
    return;
  }
  const double t0 = lf_.t;
  const Eigen::Vector4d tau = tcm_ * f_;  // eq. 3.16
  const Eigen::Vector3d vc = env.current(t0);
  const double weight = p_.weight(), buoyancy = p_.buoyancy(env.params().water_density);  // eq. 3.21
  // Mean wave drift only while the hull pierces the surface: a submerged body reflects (almost) nothing and a
  // submerged circular cylinder feels no mean drift at all (Ogilvie 1963); fading out as it dives its draft deep.
  const Hull hull = AuvModel::hull(p_);
  drift_ = std::clamp(1.0 - lf_.position.z() / hull.draft, 0.0, 1.0) * env.driftForce(lf_.yaw, hull);
  auto deriv = [&](const Vec8& x) {
    // x = [N, E, D, psi, u, v, w, r]; (u, v, w) over ground; damping on the velocity relative to the water.
    const double c = std::cos(x(3)), s = std::sin(x(3));
    Eigen::Vector4d nu_r(x(4) - (c * vc.x() + s * vc.y()), x(5) - (-s * vc.x() + c * vc.y()), x(6) - vc.z(), x(7));
    const Eigen::Vector4d drift(c * drift_.x() + s * drift_.y(), -s * drift_.x() + c * drift_.y(), 0.0, 0.0);
    const Eigen::Vector4d damping = d_lin_.cwiseProduct(nu_r) + d_quad_.cwiseProduct(nu_r.cwiseAbs().cwiseProduct(nu_r));
    // g(eta) = [0, 0, -(W - B), 0] on the left of eq. 3.14 is +(W - B) on the right: heavier sinks (z down).
    // Buoyancy fades as the hull leaves the water (over kEmergence) while the weight stays, so a buoyant AUV
    // floats at the surface and one pushed above it (thrust, momentum) falls back; never flies.
    const double immersed = std::clamp(1.0 + x(2) / kEmergence, 0.0, 1.0);
    Eigen::Vector4d g(0, 0, weight - immersed * buoyancy, 0);
    const Eigen::Vector4d nu_dot = (tau + drift - damping + g).cwiseQuotient(m_);
    Vec8 d;
    d << c * x(4) - s * x(5), s * x(4) + c * x(5), x(6), x(7), nu_dot;
    return d;
  };
  Vec8 x;
  x << lf_.position, lf_.yaw, lf_.velocity, lf_.angular_rate.z();
  const int n = substeps(dt, p_.max_step);
  for (int k = 0; k < n; ++k) x = rk4(x, dt / n, deriv);
  if (!x.allFinite()) {
    counters_.increment("non_finite_state");
  } else {
    lf_.position = x.head<3>();
    lf_.yaw = wrapAngle(x(3));
    lf_.velocity = x.segment<3>(4);
    lf_.angular_rate.z() = x(7);
  }
  lf_.t = t0 + dt;
  out_ = withWave(lf_, env.wave(lf_.t, lf_, hull));
}

}  // namespace models
}  // namespace offshore_gnc
