// AUV navigation: Kalman filter on [position; velocity; current] in NED with delayed USBL fixes applied at their
// stamp by rolling back over a short history of inputs and filter states and replaying the later inputs.
//
// The current: the commands' velocity is a speed through the water, the DVL and the fixes see the motion over
// ground. With a DVL the current has no measurement and stays apart (no cross-covariance ever forms), so the
// Girona500's estimate is the same as without it; on commands it is what the fixes correct the model with
// (a 0.2 m/s cross current otherwise biased the aColor's velocity towards the water-relative one).
//
// Yaw is not a filter state: the AHRS yaw is far better than anything the USBL fixes could tell about it, and
// keeping it out keeps the filter linear (no EKF linearisation), so a replay reproduces the on-time filter
// exactly. Yaw is carried beside the filter (in each history entry, so a replayed DVL sample is rotated by the
// yaw of its own time) and extrapolated with the AHRS rate up to heading_timeout. Its bias b is a state: a
// velocity w measured along the AHRS heading is really w rotated back by b, i.e. w = v + b J w to first order (J
// the quarter turn about z), linear in the state with J w known from the measurement. The fixes see the drift a
// bias causes across the direction of travel, so b converges while the vehicle moves; the yaw given out is the
// AHRS's less b (the sonar places its targets with it too).
#include "offshore_gnc/navigation/auv_navigator.h"

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace navigation {

namespace {
constexpr double kClockJump = 60.0;  // [s] a stamp this far back is a restarted clock, not a late sample
}  // namespace

const ParamTable<AuvNavigatorConfig>& AuvNavigatorConfig::table() {
  using P = AuvNavigatorConfig;
  static const ParamTable<P> t = ParamTable<P>()
      .number("history_s", &P::history_s, 0.5, 60.0, "s",
              "inputs kept to apply delayed USBL fixes at their stamp; an older fix is refused")
      .number("fix_timeout", &P::fix_timeout, 0.1, 3600.0, "s", "no fix accepted for longer: status fix lost")
      .number("heading_timeout", &P::heading_timeout, 0.01, 10.0, "s",
              "no AHRS heading for longer: status no heading, DVL and commanded speed unusable")
      .number("dvl_timeout", &P::dvl_timeout, 0.01, 60.0, "s",
              "no DVL sample for longer: the commanded-speed motion model is used instead")
      .number("gate_chi2", &P::gate_chi2, 1.0, 1e4, "",
              "chi-square gate on a fix's squared Mahalanobis distance (3 dof: 16.27 = 99.9 %)")
      .integer("max_rejects_in_row", &P::max_rejects_in_row, 1, 1000,
               "gated fixes in a row after which the next gated fix re-initialises the filter, if they agree")
      .integer("confirm_fixes", &P::confirm_fixes, 1, 10,
               "fixes agreeing with a start that confirm it; before, two gated fixes in a row that agree restart it")
      .number("accel_psd_h", &P::accel_psd_h, 1e-6, 100.0, "m^2/s^3",
              "process noise: white-acceleration spectral density, north and east")
      .number("accel_psd_v", &P::accel_psd_v, 1e-6, 100.0, "m^2/s^3",
              "process noise: white-acceleration spectral density, down")
      .number("position_psd", &P::position_psd, 0.0, 10.0, "m^2/s",
              "horizontal position random walk for unmodelled DVL scale, misalignment and heading errors")
      .number("dvl_sigma", &P::dvl_sigma, 1e-4, 10.0, "m/s", "DVL velocity noise, each axis")
      .number("depth_sigma", &P::depth_sigma, 1e-4, 10.0, "m", "depth sensor noise")
      .number("cmd_sigma", &P::cmd_sigma, 1e-3, 10.0, "m/s",
              "error of the velocity from the commands (no DVL), each horizontal axis, per command")
      .number("current_sigma", &P::current_sigma, 1e-3, 10.0, "m/s",
              "water current (estimated with the commanded-speed model): standard deviation, first-order Markov")
      .number("current_tau", &P::current_tau, 1.0, 1e6, "s", "water current: correlation time")
      .number("init_velocity_sigma", &P::init_velocity_sigma, 1e-3, 100.0, "m/s",
              "velocity uncertainty when the first fix initialises the filter")
      .degrees("heading_bias_sigma_deg", &P::heading_bias_sigma, 0.01, 45.0,
               "the AHRS heading's bias (a filter state): standard deviation, first-order Markov")
      .number("heading_bias_tau", &P::heading_bias_tau, 1.0, 1e6, "s", "the heading bias: correlation time")
      .number("surface_depth", &P::surface_depth, 0.0, 100.0, "m",
              "within this of the surface the wind sets the hull: the drift is re-learnt once on arrival")
      .number("surface_drift_sigma", &P::surface_drift_sigma, 0.0, 10.0, "m/s",
              "arriving at the surface, the current's standard deviation grows by this (the wind's leeway; 0: off)");
  return t;
}

AuvNavigator::AuvNavigator(const AuvNavigatorConfig& cfg) : cfg_(cfg) { AuvNavigatorConfig::table().validate(cfg); }

// ---- inputs: checked here, then queued in time order by submit() ----

bool AuvNavigator::usblFix(double t_taken, const Eigen::Vector3d& ned, const Eigen::Matrix3d& cov) {
  // a covariance that is not symmetric positive definite would make the gate and the gain meaningless
  const bool ok = std::isfinite(t_taken) && ned.allFinite() && cov.allFinite() &&
                  (cov - cov.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * (1.0 + cov.cwiseAbs().maxCoeff()) &&
                  cov.llt().info() == Eigen::Success;
  if (!ok) return refuse(true, "bad_input");
  Input in{Kind::kFix, t_taken};
  in.v = ned;
  in.cov = 0.5 * (cov + cov.transpose());
  return submit(in);
}

bool AuvNavigator::depth(double t, double z) {
  if (!std::isfinite(t) || !std::isfinite(z)) return refuse(true, "bad_input");
  Input in{Kind::kDepth, t};
  in.a = z;
  return submit(in);
}

bool AuvNavigator::heading(double t, double yaw, double yaw_rate) {
  if (!std::isfinite(t) || !std::isfinite(yaw) || !std::isfinite(yaw_rate)) return refuse(true, "bad_input");
  Input in{Kind::kHeading, t};
  in.a = wrapAngle(yaw);
  in.b = yaw_rate;
  return submit(in);
}

bool AuvNavigator::dvl(double t, const Eigen::Vector3d& v_body) {
  if (!std::isfinite(t) || !v_body.allFinite()) return refuse(true, "bad_input");
  Input in{Kind::kDvl, t};
  in.v = v_body;
  return submit(in);
}

bool AuvNavigator::commandedVelocity(double t, double surge, double sway) {
  if (!std::isfinite(t) || !std::isfinite(surge) || !std::isfinite(sway)) return refuse(true, "bad_input");
  Input in{Kind::kCommand, t};
  in.a = surge;
  in.b = sway;
  return submit(in);
}

bool AuvNavigator::gpsFix(double t, const Eigen::Vector2d& ne, double sigma) {
  if (!std::isfinite(sigma)) return refuse(true, "bad_input");
  const double var = std::max(sigma * sigma, 1e-4);
  return usblFix(t, Eigen::Vector3d(ne.x(), ne.y(), 0.0), Eigen::Vector3d(var, var, 100.0).asDiagonal());
}

bool AuvNavigator::predict(double t) {
  if (!std::isfinite(t)) return refuse(true, "bad_input");
  return submit(Input{Kind::kPredict, t});
}

// ---- history: in-order inputs are applied and appended; a late one is inserted at its stamp and the inputs
// after it are replayed from the state stored before it. Every input is logged (a predict too), so the current
// state is always the newest entry's. ----

bool AuvNavigator::submit(const Input& in) {
  if (in.t < latest_t_ - cfg_.history_s) {
    if (in.kind == Kind::kFix) return refuse(true, "fix_too_old");
    // One late sample is refused; a stamp far older than the history means the clock went back (simulation
    // or bag restart): start over.
    if (in.t > latest_t_ - std::max(kClockJump, 3.0 * cfg_.history_s)) return refuse(true, "input_too_old");
    count(true, "time_reset");
    state_ = base_ = Filter{};
    history_.clear();
    latest_t_ = -1e300;
  }
  latest_t_ = std::max(latest_t_, in.t);
  bool ok;
  if (history_.empty() || in.t >= history_.back().in.t) {
    ok = apply(state_, in, true);
    history_.push_back({in, state_});
  } else {
    // after the inputs of the same stamp, as if it had arrived last at that time
    const auto pos = std::upper_bound(history_.begin(), history_.end(), in.t,
                                      [](double t, const Entry& e) { return t < e.in.t; });
    const std::size_t i0 = static_cast<std::size_t>(pos - history_.begin());
    Filter f = i0 == 0 ? base_ : history_[i0 - 1].after;
    history_.insert(pos, Entry{in, f});
    ok = apply(f, in, true);
    history_[i0].after = f;
    for (std::size_t i = i0 + 1; i < history_.size(); ++i) {
      apply(f, history_[i].in, false);
      history_[i].after = f;
    }
    state_ = f;
  }
  // anything older than latest - history_s can no longer be rolled back to (see the check above)
  while (!history_.empty() && history_.front().in.t < latest_t_ - cfg_.history_s) {
    base_ = history_.front().after;
    history_.pop_front();
  }
  return ok;
}

bool AuvNavigator::headingAt(const Filter& f, double t, double& yaw) const {
  if (std::abs(t - f.heading_t) > cfg_.heading_timeout) return false;
  yaw = wrapAngle(f.yaw + f.yaw_rate * (t - f.heading_t));
  return true;
}

bool AuvNavigator::apply(Filter& f, const Input& in, bool first) {
  switch (in.kind) {
    case Kind::kFix: return applyFix(f, in, first);
    case Kind::kHeading:  // context only, x and P untouched
      f.yaw = in.a;
      f.yaw_rate = in.b;
      f.heading_t = in.t;
      return true;
    case Kind::kPredict: propagate(f, in.t); return true;
    case Kind::kDepth: {
      propagate(f, in.t);
      if (!f.initialised) return true;  // the first fix sets z, the next depth sample corrects it
      Eigen::Matrix<double, 1, kNavStates> H = Eigen::Matrix<double, 1, kNavStates>::Zero();
      H(0, kPos + 2) = 1.0;
      update<1>(f, H, Eigen::Matrix<double, 1, 1>(in.a - f.x(2)),
                Eigen::Matrix<double, 1, 1>(cfg_.depth_sigma * cfg_.depth_sigma));
      const bool up = f.x(2) < cfg_.surface_depth;
      const double leeway = cfg_.surface_drift_sigma;
      if (up && !f.at_surface) f.P.block<2, 2>(kCur, kCur) += Eigen::Matrix2d::Identity() * leeway * leeway;
      f.at_surface = up;
      return true;
    }
    case Kind::kDvl: {
      double yaw;
      if (!headingAt(f, in.t, yaw)) return refuse(first, "velocity_without_heading");
      f.dvl_t = in.t;
      propagate(f, in.t);
      if (!f.initialised) return true;
      // body FRD -> NED by the AHRS yaw only (the AUV keeps roll and pitch near zero): w = v + b J w
      const Eigen::Vector3d w = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * in.v;
      Eigen::Matrix<double, 3, kNavStates> H = Eigen::Matrix<double, 3, kNavStates>::Zero();
      H.middleCols<3>(kVel).setIdentity();
      H.col(kBias) << -w.y(), w.x(), 0.0;
      update<3>(f, H, w - H * f.x, Eigen::Matrix3d::Identity() * cfg_.dvl_sigma * cfg_.dvl_sigma);
      return true;
    }
    case Kind::kCommand: {
      // The aColor's motion model from its commands: the horizontal velocity through the water (over ground
      // minus the current) is the body's (surge, sway) turned by the yaw. It enters as a velocity pseudo-measurement with an
      // error (cmd_sigma) rather than replacing the constant-velocity prediction, so the fixes can still correct
      // the velocity (speed error) and reveal the current.
      if (in.t - f.dvl_t <= cfg_.dvl_timeout) return true;  // the DVL measures what the commands only suggest
      double yaw;
      if (!headingAt(f, in.t, yaw)) return refuse(first, "velocity_without_heading");
      propagate(f, in.t);
      if (!f.initialised) return true;
      Eigen::Matrix<double, 2, kNavStates> H = Eigen::Matrix<double, 2, kNavStates>::Zero();
      const double c = std::cos(yaw), sn = std::sin(yaw);  // by the AHRS heading: w = v - c + b J w
      const Eigen::Vector2d w(c * in.a - sn * in.b, sn * in.a + c * in.b);
      H(0, kVel) = H(1, kVel + 1) = 1.0;
      H(0, kCur) = H(1, kCur + 1) = -1.0;
      H(0, kBias) = -w.y();
      H(1, kBias) = w.x();
      update<2>(f, H, w - H * f.x, Eigen::Matrix2d::Identity() * cfg_.cmd_sigma * cfg_.cmd_sigma);
      return true;
    }
  }
  return false;
}

bool AuvNavigator::applyFix(Filter& f, const Input& in, bool first) {
  propagate(f, in.t);
  bool reinit = false;
  int n_agreeing = 1;
  if (f.initialised) {
    const Eigen::Vector3d y = in.v - f.x.segment<3>(kPos);
    const Eigen::Matrix3d S = f.P.topLeftCorner<3, 3>() + in.cov;
    const double d2 = y.dot(S.ldlt().solve(y));
    if (d2 <= cfg_.gate_chi2) {
      Eigen::Matrix<double, 3, kNavStates> H = Eigen::Matrix<double, 3, kNavStates>::Zero();
      H.middleCols<3>(kPos).setIdentity();
      update<3>(f, H, y, in.cov);
      f.rejects_in_row = 0;
      ++f.agreeing;
      f.fix_t = in.t;
      count(first, "fix_accepted");
      return true;
    }
    // Outliers (a reflected acoustic path) are gated one by one. A streak of gated fixes that agree with each other
    // says the estimate is wrong instead (a missed jump, a diverged dead reckoning): after max_rejects_in_row of
    // them the filter starts again from this fix, so the gate cannot lock it out forever. Scattered ones do not.
    // A start no fix has yet agreed with may itself have been an outlier: there two agreeing gated fixes suffice.
    const bool confirmed = f.agreeing >= cfg_.confirm_fixes;
    const int needed = confirmed ? cfg_.max_rejects_in_row : 1;
    const int n = std::min({f.rejects_in_row + 1, needed + 1, static_cast<int>(f.streak.size())});
    f.streak[static_cast<std::size_t>(f.rejects_in_row) % f.streak.size()] << y, in.cov.trace() / 3.0;
    const bool enough = f.rejects_in_row >= needed;
    if (!enough || !streakAgrees(f, n)) {
      if (enough) count(first, "reinit_refused_scattered");
      ++f.rejects_in_row;
      count(first, "fix_rejected_gate");
      return false;
    }
    reinit = true;
    n_agreeing = n;
    count(first, "reinit");
    if (!confirmed) count(first, "reinit_unconfirmed");
  }
  // The DVL's velocity is independent of a position jump: keep it when the DVL is measuring, else start at rest.
  // The current and the heading bias are too: a re-initialisation keeps them, the first fix starts them at zero
  // with their prior spread.
  const bool keep_velocity = reinit && in.t - f.dvl_t <= cfg_.dvl_timeout;
  const Eigen::Matrix3d Pvv = f.P.block<3, 3>(kVel, kVel);
  Eigen::Matrix3d Pcb = f.P.block<3, 3>(kCur, kCur);  // current and bias
  if (!reinit) {
    f.x.segment<3>(kCur).setZero();
    Pcb = Eigen::Vector3d(cfg_.current_sigma * cfg_.current_sigma, cfg_.current_sigma * cfg_.current_sigma,
                          cfg_.heading_bias_sigma * cfg_.heading_bias_sigma).asDiagonal();
  }
  f.P.setZero();
  f.P.block<3, 3>(kPos, kPos) = in.cov;
  f.P.block<3, 3>(kCur, kCur) = Pcb;
  f.x.segment<3>(kPos) = in.v;
  if (keep_velocity) {
    f.P.block<3, 3>(kVel, kVel) = Pvv;
  } else {
    f.x.segment<3>(kVel).setZero();
    f.P.block<3, 3>(kVel, kVel) = Eigen::Matrix3d::Identity() * cfg_.init_velocity_sigma * cfg_.init_velocity_sigma;
  }
  f.initialised = true;
  f.agreeing = reinit ? n_agreeing : 1;  // a re-initialisation on a streak: its fixes agreed with each other
  f.rejects_in_row = 0;
  f.fix_t = in.t;
  count(first, "fix_accepted");
  return true;
}

// The latest n innovations of the streak (the current fix's included) each within the gate of their mean (by the
// fix's own variance).
bool AuvNavigator::streakAgrees(const Filter& f, int n) const {
  const std::size_t size = f.streak.size();
  const auto at = [&](int k) -> const Eigen::Vector4d& {  // k-th latest
    return f.streak[(static_cast<std::size_t>(f.rejects_in_row) + size - static_cast<std::size_t>(k)) % size];
  };
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) mean += at(k).head<3>() / n;
  for (int k = 0; k < n; ++k)
    if ((at(k).head<3>() - mean).squaredNorm() > cfg_.gate_chi2 * at(k)[3]) return false;
  return true;
}

// Constant velocity with white acceleration plus a horizontal position random walk; the current and the heading
// bias first-order Markov. Exact discretisations: splitting an interval changes nothing.
void AuvNavigator::propagate(Filter& f, double t) const {
  const double dt = t - f.t;
  if (!(dt > 0.0)) return;
  f.t = t;
  if (!f.initialised) return;
  NavMatrix F = NavMatrix::Identity();
  F.block<3, 3>(kPos, kVel) = Eigen::Matrix3d::Identity() * dt;
  const double decay = std::exp(-dt / cfg_.current_tau), decay_b = std::exp(-dt / cfg_.heading_bias_tau);
  F.block<2, 2>(kCur, kCur) *= decay;
  F(kBias, kBias) = decay_b;
  f.x = F * f.x;
  NavMatrix Q = NavMatrix::Zero();
  const double q[3] = {cfg_.accel_psd_h, cfg_.accel_psd_h, cfg_.accel_psd_v};
  for (int i = 0; i < 3; ++i) {
    Q(i, i) = q[i] * dt * dt * dt / 3.0;
    Q(i, i + 3) = Q(i + 3, i) = q[i] * dt * dt / 2.0;
    Q(i + 3, i + 3) = q[i] * dt;
  }
  Q(0, 0) += cfg_.position_psd * dt;
  Q(1, 1) += cfg_.position_psd * dt;
  const double var_c = cfg_.current_sigma * cfg_.current_sigma, var_b = cfg_.heading_bias_sigma * cfg_.heading_bias_sigma;
  Q.block<2, 2>(kCur, kCur) = Eigen::Matrix2d::Identity() * var_c * (1.0 - decay * decay);
  Q(kBias, kBias) = var_b * (1.0 - decay_b * decay_b);
  f.P = F * f.P * F.transpose() + Q;
}

// Joseph form: keeps P symmetric positive definite whatever the rounding.
template <int M>
void AuvNavigator::update(Filter& f, const Eigen::Matrix<double, M, kNavStates>& H,
                          const Eigen::Matrix<double, M, 1>& innovation, const Eigen::Matrix<double, M, M>& R) const {
  const Eigen::Matrix<double, M, M> S = H * f.P * H.transpose() + R;
  const Eigen::Matrix<double, kNavStates, M> K = f.P * H.transpose() * S.inverse();  // S: at most 3 x 3, SPD
  f.x += K * innovation;
  const NavMatrix IKH = NavMatrix::Identity() - K * H;
  f.P = IKH * f.P * IKH.transpose() + K * R * K.transpose();
  f.P = 0.5 * (f.P + f.P.transpose()).eval();
}

AuvNavEstimate AuvNavigator::estimate(double t) const {
  if (!std::isfinite(t)) t = state_.t;
  Filter f = state_;
  if (t < state_.t) {  // from the history: the state after the last input at or before t
    const auto pos = std::upper_bound(history_.begin(), history_.end(), t,
                                      [](double tt, const Entry& e) { return tt < e.in.t; });
    f = pos == history_.begin() ? base_ : std::prev(pos)->after;
  }
  propagate(f, t);
  AuvNavEstimate e;
  e.t = t;
  e.position = f.x.segment<3>(kPos);
  e.velocity = f.x.segment<3>(kVel);
  e.covariance = f.P.topLeftCorner<6, 6>();
  e.current = f.x.segment<2>(kCur);
  e.current_covariance = f.P.block<2, 2>(kCur, kCur);
  e.heading_bias = f.initialised ? f.x(kBias) : 0.0;
  e.heading_bias_sigma = f.initialised ? std::sqrt(f.P(kBias, kBias)) : cfg_.heading_bias_sigma;
  e.yaw_rate = f.yaw_rate;
  if (!headingAt(f, t, e.yaw)) e.yaw = f.yaw;
  e.yaw = wrapAngle(e.yaw - e.heading_bias);
  if (!f.initialised)
    e.status = NavStatus::kNoFix;
  else if (t - f.heading_t > cfg_.heading_timeout)
    e.status = NavStatus::kNoHeading;  // worse than a lost fix: the dead reckoning itself has stopped
  else if (t - f.fix_t > cfg_.fix_timeout)
    e.status = NavStatus::kFixLost;
  else
    e.status = NavStatus::kOk;
  return e;
}

}  // namespace navigation
}  // namespace offshore_gnc
