#include "offshore_gnc/models/joystick_allocation.h"

#include <algorithm>
#include <cmath>

namespace offshore_gnc {
namespace models {

namespace {
const UsvParams& validated(const UsvParams& p) {
  p.validate();  // before the lookups and the thrust table are built from it (a bad rpm_max crashed there)
  return p;
}
}  // namespace

JoystickAllocation::JoystickAllocation(const UsvParams& p)
    : p_(validated(p)),
      joy_rpm_("joy_u", p.joy_u, p.joy_u_rpm),
      joy_nozzle_("joy_r", p.joy_r, p.joy_r_nozzle),
      forces_(p) {
  rpm_full_ = joy_rpm_(p_.joy_u_full);
  // At full sway the engines run at rpm_full with the buckets split around neutral (g0 = 0: one ahead, the
  // other astern, dg = 2 reverse_efficiency), the most side force whose moment they can balance.
  const double sin_full = 2.0 * p_.reverse_efficiency * p_.jet_y / (2.0 * p_.l_pivot);
  side_full_ = 2.0 * sin_full *
               forces_.grossThrust(0.0, rpm_full_, std::asin(sin_full) / p_.nozzle_max_angle * p_.nozzle_max);
}

bool JoystickAllocation::tryAllocate(const UsvCommand& c, JetCommands& out) const {
  const JetForces& f = forces_;
  // eq. 3.25: the nozzle position is the negated lookup value (P < 0 turns to starboard)
  const double p_r = -std::copysign(joy_nozzle_(std::abs(c.yaw) * p_.joy_r_full), c.yaw);
  // The surge axis asks for the thesis' force: rpm(|surge|) through the bucket b0. The engines run at least as
  // fast as the sway and yaw axes need (a nozzle turns the boat in proportion to the jet's thrust), the buckets
  // then trimmed so that the surge force stays what the surge axis asked for.
  const double rpm_s = joy_rpm_(std::abs(c.surge) * p_.joy_u_full);
  // Sway asks for a side force in proportion, sway = +-1 being sideForceFull(): thrust grows with rpm^2
  // (eq. 3.11), so its engine speed is rpm_full sqrt(|sway|). (Through the surge axis' rpm table a small sway
  // gave almost nothing at idle and DP's lateral corrections came 5-7 times weaker than asked.)
  const double rpm_y = rpm_full_ * std::sqrt(std::abs(c.sway));
  const double rpm_sy = joy_rpm_(std::max(std::abs(c.surge), p_.yaw_rpm_share * std::abs(c.yaw)) * p_.joy_u_full);
  const double rpm = std::max(rpm_y, rpm_sy);
  // Yaw asks for the moment the thesis' nozzles give at the surge and yaw axes' own rpm: where sway runs the
  // engines faster, the yaw's nozzle angle shrinks to match (else the same yaw turned the boat up to ten times
  // harder at full sway and the heading loop rang at 2 s in station keeping).
  const double a_r = std::asin(std::clamp(std::sin(f.angle(p_r)) * f.grossThrust(0.0, rpm_sy, p_r) /
                                              f.grossThrust(0.0, rpm, p_r), -1.0, 1.0));
  const double b0 = std::clamp(c.surge / p_.bucket_band, -1.0, 1.0);
  const double t_rpm = f.grossThrust(0.0, rpm, p_r);
  const double g0 = f.bucketGain(b0) * f.grossThrust(0.0, rpm_s, p_r) / t_rpm;
  // Differential bucket the buckets can still give around g0 (ahead at most 1, astern at most reverse_efficiency).
  const double dg_max = 2.0 * std::max(0.0, std::min(1.0 - g0, g0 + p_.reverse_efficiency));
  // Sway: the side force asked for at this rpm, sin(a) = q for sway alone (Y = 2 T(a) q, the nozzle's own
  // efficiency, eq. 3.12, in T); more than the buckets can balance fails below and the whole command is scaled down.
  double q = 0.0;
  for (int i = 0; i < 4 && t_rpm > 0.0; ++i) {
    const double a_q = std::asin(std::clamp(q, -1.0, 1.0));
    q = c.sway * side_full_ / (2.0 * f.grossThrust(0.0, rpm, a_q / p_.nozzle_max_angle * p_.nozzle_max));
  }
  // Under way (|surge| beyond bucket_band): the nozzles steer as the thesis' jets do, turned further for sway with
  // the buckets balancing the sway's moment: sin(a) - sin(a_r) = q cos(a).
  const double a_way = std::atan(q) + std::asin(std::clamp(std::sin(a_r) / std::sqrt(1.0 + q * q), -1.0, 1.0));
  const double dg_way = c.sway * dg_max;  // = 2 l (sin a - sin a_r) / (jet_y cos a)
  // At low speed (the buckets near neutral, station keeping): the differential buckets give the yaw's moment
  // M = -2 l T sin(a_r) and balance the side force's, and the nozzles give the side force, so that turning does
  // not push the stern sideways (M = T (-2 l sin a + jet_y cos a dg)). Yaw comes first: turning into the current
  // is what makes holding possible, so the side force is cut to what the buckets can still balance, and when the
  // buckets alone cannot turn the boat the nozzles add their moment too (and the side force that comes with it).
  auto dgFor = [&](double a) { return 2.0 * p_.l_pivot * (std::sin(a) - std::sin(a_r)) / (p_.jet_y * std::cos(a)); };
  double a_low = std::asin(std::clamp(q, -1.0, 1.0)), dg_low = dgFor(a_low);
  if (std::abs(dgFor(0.0)) >= dg_max) {
    const double dg_lim = std::copysign(dg_max, dgFor(0.0)), m = -2.0 * p_.l_pivot * std::sin(a_r);
    const double rr = std::hypot(2.0 * p_.l_pivot, p_.jet_y * dg_lim);
    a_low = std::atan2(p_.jet_y * dg_lim, 2.0 * p_.l_pivot) - std::asin(std::clamp(m / rr, -1.0, 1.0));
    dg_low = dg_lim;
  } else if (std::abs(dg_low) > dg_max) {
    double lo = 0.0, hi = 1.0;  // the largest share of the side force the buckets can still balance
    for (int i = 0; i < 30; ++i) {
      const double k = 0.5 * (lo + hi);
      (std::abs(dgFor(std::asin(std::clamp(k * q, -1.0, 1.0)))) <= dg_max ? lo : hi) = k;
    }
    a_low = std::asin(std::clamp(lo * q, -1.0, 1.0));
    dg_low = dgFor(a_low);
  }
  // under way from 1.5 bucket_band of surge, at low speed below half of it (station keeping's small surge demands)
  const double way = std::clamp(std::abs(c.surge) / p_.bucket_band - 0.5, 0.0, 1.0);
  const double a = way * a_way + (1.0 - way) * a_low;
  const double dg = way * dg_way + (1.0 - way) * dg_low;
  if (std::abs(a) > p_.nozzle_max_angle + 1e-12 || std::abs(dg) > dg_max + 1e-9) return false;
  const double nozzle = a / p_.nozzle_max_angle * p_.nozzle_max;
  auto bucketOf = [&](double g) { return g >= 0.0 ? std::min(g, 1.0) : std::max(g / p_.reverse_efficiency, -1.0); };
  out[0] = JetCommand{rpm, nozzle, bucketOf(g0 + dg / 2.0)};  // port: ahead turns the bow to starboard
  out[1] = JetCommand{rpm, nozzle, bucketOf(g0 - dg / 2.0)};
  return true;
}

JetCommands JoystickAllocation::allocate(const UsvCommand& in) const {
  UsvCommand c{std::isfinite(in.surge) ? std::clamp(in.surge, -1.0, 1.0) : 0.0,
               std::isfinite(in.sway) ? std::clamp(in.sway, -1.0, 1.0) : 0.0,
               std::isfinite(in.yaw) ? std::clamp(in.yaw, -1.0, 1.0) : 0.0};
  JetCommands out;
  last_scale_ = 1.0;
  if (tryAllocate(c, out)) return out;
  // A nozzle at its stop: the largest common scale that fits (bisection; k = 0 always fits).
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 30; ++i) {
    const double k = 0.5 * (lo + hi);
    JetCommands tmp;
    (tryAllocate({k * c.surge, k * c.sway, k * c.yaw}, tmp) ? lo : hi) = k;
  }
  last_scale_ = lo;
  tryAllocate({lo * c.surge, lo * c.sway, lo * c.yaw}, out);
  return out;
}

double JoystickAllocation::surgeFor(double force) const {
  if (!std::isfinite(force) || force == 0.0) return 0.0;
  const double sign = force > 0.0 ? 1.0 : -1.0;
  auto push = [&](double surge) { return sign * staticForce(allocate({sign * surge, 0.0, 0.0})).x(); };
  if (push(1.0) <= std::abs(force)) return sign;  // beyond full: full
  double lo = 0.0, hi = 1.0;  // the force grows with |surge| (rpm and bucket both)
  for (int i = 0; i < 40; ++i) {
    const double m = 0.5 * (lo + hi);
    (push(m) < std::abs(force) ? lo : hi) = m;
  }
  return sign * 0.5 * (lo + hi);
}

Eigen::Vector3d JoystickAllocation::staticForce(const JetCommands& c) const {
  std::array<JetState, 2> s;
  for (int i = 0; i < 2; ++i) s[i] = JetState{c[i].rpm, c[i].nozzle, c[i].bucket, 0.0};
  return forces_.force(s, 0.0);
}

}  // namespace models
}  // namespace offshore_gnc
