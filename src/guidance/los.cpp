#include "offshore_gnc/guidance/los.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace guidance {

const ParamTable<LosParams>& LosParams::table() {
  using P = LosParams;
  static const ParamTable<P> t = ParamTable<P>()
      .number("kp", &P::kp, 1e-4, 10.0, "1/m", "look-ahead gain 1/Delta (Table 4.1 LOS K_P)")
      .number("ki", &P::ki, 0.0, 1.0, "1/(m s)", "ILOS integral gain (Table 4.1 LOS K_I)")
      .number("integral_limit", &P::integral_limit, 0.0, kPi / 2, "rad", "anti-windup: largest integral steering")
      .flag("adaptive_crab", &P::adaptive_crab, "estimate the crab (sideslip) angle (adaptive LOS)")
      .number("crab_gain", &P::crab_gain, 0.0, 1.0, "1/m^2", "gain of the crab-angle estimate (per m/s of speed)")
      .number("crab_limit", &P::crab_limit, 0.0, kPi / 2, "rad", "largest magnitude of the crab-angle estimate")
      .flag("measured_crab", &P::measured_crab,
            "the crab angle from the velocity over ground, atan2(v, u), instead of estimated (GPS velocity)")
      .number("crab_tf", &P::crab_tf, 0.01, 100.0, "s", "low-pass time constant of the measured crab angle")
      .number("crab_band", &P::crab_band, 0.0, 1000.0, "m",
              "the crab estimate learns only within this cross-track (0 = always; farther off is the approach)")
      .number("crab_min_speed", &P::crab_min_speed, 0.0, 10.0, "m/s", "below this speed the crab angle is kept")
      .flag("crab_ned", &P::crab_ned,
            "keep the crab estimate as a NED vector (current over speed), so legs of other directions get their own")
      .number("acceptance_radius", &P::acceptance_radius, 0.01, 1000.0, "m",
              "circle (USV, 2 L_USV) or sphere (AUV) of acceptance")
      .flag("sphere", &P::sphere, "3-D sphere of acceptance (AUV) instead of the 2-D circle")
      .number("surge_speed", &P::surge_speed, 0.0, 20.0, "m/s", "cruise surge reference")
      .number("min_leg_length", &P::min_leg_length, 1e-6, 10.0, "m", "closer consecutive waypoints are merged")
      .number("final_radius", &P::final_radius, 0.0, 1000.0, "m",
              "the last waypoint is reached within this (0: acceptance_radius)")
      .number("detour_radius", &P::detour_radius, 0.0, 1000.0, "m",
              "safety-box corners are reached within this (0: acceptance_radius)")
      .number("approach_distance", &P::approach_distance, 0.0, 1e4, "m",
              "slow down over this distance before the last waypoint (0: off)")
      .number("approach_speed", &P::approach_speed, 0.0, 20.0, "m/s", "surge reference at the last waypoint");
  return t;
}

void LosParams::validate() const { table().validate(*this, "los/"); }

MotionReference referenceOf(const LosOutput& o) {
  MotionReference r;
  r.heading = o.desired_heading;
  r.surge = o.desired_surge;
  r.depth = o.desired_depth;
  r.path_angle = o.path_angle;
  switch (o.mode) {
    case Mode::kFollowPath:
      r.mode = ReferenceMode::kFollow;
      r.point = o.path_point;
      break;
    case Mode::kStationKeeping:
    case Mode::kHoldFault:
      r.mode = ReferenceMode::kHold;
      r.point = o.hold_position;
      break;
    default:
      r.mode = ReferenceMode::kIdle;
  }
  return r;
}

double legGeometry(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p, double* e,
                   double* s) {
  const double chi_p = std::atan2(b.y() - a.y(), b.x() - a.x());  // eq. 4.11
  const double c = std::cos(chi_p), sn = std::sin(chi_p);
  if (e) *e = -(p.x() - a.x()) * sn + (p.y() - a.y()) * c;  // eq. 4.12
  if (s) *s = (p.x() - a.x()) * c + (p.y() - a.y()) * sn;
  return chi_p;
}

LosGuidance::LosGuidance(const LosParams& p) { setParams(p); }

void LosGuidance::setParams(const LosParams& p) {
  p.validate();
  p_ = p;
  beta_hat_ = std::clamp(beta_hat_, -p_.crab_limit, p_.crab_limit);
}

void LosGuidance::clear() {
  wp_.clear();
  detour_.clear();
  path_error_.clear();
  leg_ = 1;
  finished_ = false;
  integral_ = 0.0;
}

bool LosGuidance::setPath(const std::vector<Eigen::Vector3d>& waypoints, bool resume,
                          const std::vector<bool>& detour) {
  // A replan of a path already finished (station keeping at its end) keeps holding when the end stays where it
  // was: following the lead-in leg again from wherever the current had set the boat sent it round in circles. So
  // does a new path that ends where the vehicle holds (horizontally): the AUV mission's ascent moves the held depth
  // every half second, and each restart on the lead-in turned the hold into path following for a moment.
  const bool same_end = !wp_.empty() && !waypoints.empty() &&
                        (resume ? (waypoints.back() - wp_.back()).norm()
                                : (waypoints.back() - wp_.back()).head<2>().norm()) <= p_.min_leg_length + 1e-9;
  const bool was_holding = finished_ && same_end;
  clear();
  if (!detour.empty() && detour.size() != waypoints.size()) {
    counters_.increment("bad_path");
    path_error_ = "path rejected: detour flags do not match the waypoints";
    return false;
  }
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const Eigen::Vector3d& w = waypoints[i];
    const bool corner = !detour.empty() && detour[i];
    if (!w.allFinite()) {
      counters_.increment("bad_path");
      path_error_ = "path rejected: non-finite waypoint";
      wp_.clear();
      detour_.clear();
      return false;
    }
    if (!wp_.empty() && (w - wp_.back()).norm() < p_.min_leg_length) {
      counters_.increment("duplicate_waypoints");  // merged, not an error
      if (corner) detour_.back() = true;
      continue;
    }
    wp_.push_back(w);
    detour_.push_back(corner);
  }
  if (wp_.empty()) {
    if (!waypoints.empty()) counters_.increment("bad_path");
    path_error_ = waypoints.empty() ? "" : "path rejected: no usable waypoint";
    return waypoints.empty();
  }
  if (wp_.size() == 1) {
    counters_.increment("bad_path");
    path_error_ = "path rejected: a single waypoint (or all duplicates) gives no leg to follow";
    wp_.clear();
    detour_.clear();
    return false;
  }
  if (was_holding) {
    leg_ = wp_.size() - 1;
    finished_ = true;
    return true;
  }
  if (resume && have_pose_) {
    // Nearest leg to the vehicle; ties go to the later leg so that progress is never undone.
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < wp_.size(); ++k) {
      const Eigen::Vector2d a = wp_[k - 1].head<2>(), b = wp_[k].head<2>(), p = last_pos_.head<2>();
      const Eigen::Vector2d ab = b - a;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const double d = (a + t * ab - p).norm();
      if (d <= best + 1e-9) {
        best = d;
        leg_ = k;
      }
    }
  }
  return true;
}

double LosGuidance::remaining(const Eigen::Vector3d& pos) const {
  if (leg_ >= wp_.size()) return 0.0;
  double d = (wp_[leg_].head<2>() - pos.head<2>()).norm();
  for (std::size_t k = leg_ + 1; k < wp_.size(); ++k) d += (wp_[k] - wp_[k - 1]).head<2>().norm();
  return d;
}

LosOutput LosGuidance::hold(Mode mode, const std::string& why) {
  LosOutput o;
  o.mode = mode;
  o.num_waypoints = wp_.size();
  o.active_leg = leg_;
  o.hold_position = last_pos_;
  o.path_point = last_pos_;
  o.desired_heading = last_yaw_;
  o.desired_depth = last_pos_.z();
  o.desired_surge = 0.0;
  o.crab_angle = beta_hat_;
  o.acceptance_radius = p_.acceptance_radius;
  o.status_text = why;
  return o;
}

LosOutput LosGuidance::update(const VehicleState& s, double dt) {
  if (!s.position.allFinite() || !std::isfinite(s.yaw)) {
    counters_.increment("nan_pose");
    return hold(Mode::kHoldFault, have_pose_ ? "non-finite pose: holding the last good position"
                                             : "non-finite pose and no previous pose: holding (neutral)");
  }
  if (!std::isfinite(dt) || dt < 0.0 || dt > 10.0) {
    counters_.increment("bad_dt");
    dt = 0.0;  // integrators do not move on a bad time step
  }
  have_pose_ = true;
  last_pos_ = s.position;
  last_yaw_ = wrapAngle(s.yaw);

  if (wp_.empty()) {
    return path_error_.empty() ? hold(Mode::kIdle, "no path") : hold(Mode::kHoldFault, path_error_);
  }

  const Eigen::Vector2d p = s.position.head<2>();
  double e = 0.0, along = 0.0;
  // Station keeping at the end holds the last leg's angle (the hold's heading until a current is learnt), on
  // every step: with 0 after the first, a controller that first saw the hold one step late turned to north.
  double chi_p = std::atan2(wp_[leg_].y() - wp_[leg_ - 1].y(), wp_[leg_].x() - wp_[leg_ - 1].x());
  // Switching (eq. 4.13/4.14) plus the passed-waypoint rule: along-track beyond the leg length.
  while (!finished_) {
    const Eigen::Vector3d& a = wp_[leg_ - 1];
    const Eigen::Vector3d& b = wp_[leg_];
    chi_p = legGeometry(a.head<2>(), b.head<2>(), p, &e, &along);
    const double leg_len = (b - a).head<2>().norm();
    const double dist = p_.sphere ? (s.position - b).norm() : (p - b.head<2>()).norm();
    // A purely vertical leg has no horizontal length: only the sphere switches it.
    const bool passed = leg_len > p_.min_leg_length && along >= leg_len;
    const bool last = leg_ + 1 >= wp_.size();
    double radius = p_.acceptance_radius;
    if (last && p_.final_radius > 0.0)
      radius = final_run_blocked_ && p_.detour_radius > 0.0 ? std::min(p_.detour_radius, p_.final_radius)
                                                            : p_.final_radius;
    else if (detour_[leg_] && p_.detour_radius > 0.0)
      radius = p_.detour_radius;
    if (dist > radius && !passed) break;
    if (leg_ + 1 >= wp_.size()) {
      finished_ = true;
      counters_.increment("path_finished");
    } else {
      ++leg_;
    }
  }

  LosOutput o;
  o.num_waypoints = wp_.size();
  o.active_leg = leg_;
  o.acceptance_radius = p_.acceptance_radius;
  o.path_angle = chi_p;
  o.cross_track_error = e;
  o.along_track_distance = along;
  o.crab_angle = beta_hat_;
  if (finished_) {
    o.mode = Mode::kStationKeeping;
    o.hold_position = wp_.back();
    o.path_point = wp_.back();
    o.desired_heading = chi_p;
    o.desired_depth = wp_.back().z();
    o.desired_surge = 0.0;
    o.distance_to_go = 0.0;
    o.status_text = "end of path reached: station keeping at the last waypoint";
    return o;
  }

  const double delta = 1.0 / p_.kp;
  // ILOS with anti-windup: the integral term is clamped to +-integral_limit of steering.
  if (p_.ki > 0.0 && !hold_integral_) {
    integral_ += e * dt;
    const double imax = p_.integral_limit / p_.ki;
    integral_ = std::clamp(integral_, -imax, imax);
  }
  const double speed = std::hypot(s.velocity.x(), s.velocity.y());
  if (p_.measured_crab) {
    if (speed > p_.crab_min_speed) {
      const double beta = std::atan2(s.velocity.y(), s.velocity.x());
      beta_hat_ += angleDiff(beta, beta_hat_) * std::min(1.0, dt / p_.crab_tf);
    }
    beta_hat_ = std::clamp(beta_hat_, -p_.crab_limit, p_.crab_limit);
  } else if (p_.adaptive_crab && (p_.crab_band <= 0.0 || std::abs(e) < p_.crab_band)) {
    // Fossen's ALOS: the update scales with the speed U, as the cross-track rate does; without it the
    // estimate outran the look-ahead at low speed (the mission's transit lies in the slowdown: ringing at ~40 s).
    const double step = dt * p_.crab_gain * speed * delta / std::sqrt(delta * delta + e * e) * e;
    if (p_.crab_ned) {
      // the same update along the leg's starboard normal; the component along the leg is not observable on it
      const Eigen::Vector2d n(-std::sin(chi_p), std::cos(chi_p));
      crab_ned_ += step * n;
      if (crab_ned_.norm() > p_.crab_limit) crab_ned_ *= p_.crab_limit / crab_ned_.norm();
      beta_hat_ = crab_ned_.dot(n);
    } else {
      beta_hat_ = std::clamp(beta_hat_ + step, -p_.crab_limit, p_.crab_limit);
    }
  }
  const double chi_r = std::atan(-p_.kp * e - p_.ki * integral_);  // eq. 4.10
  o.mode = Mode::kFollowPath;
  o.crab_angle = beta_hat_;
  o.desired_heading = wrapAngle(chi_p + chi_r - beta_hat_);      // eq. 4.9 with beta estimated
  o.desired_depth = wp_[leg_].z();                                // constant-depth legs, depth apart
  o.desired_surge = p_.surge_speed;
  o.distance_to_go = remaining(s.position);
  if (p_.approach_distance > 0.0 && o.distance_to_go < p_.approach_distance) {
    // linear slowdown to approach_speed at the last waypoint, so that station keeping starts from low speed
    const double f = o.distance_to_go / p_.approach_distance;
    o.desired_surge = std::min(p_.surge_speed, p_.approach_speed + f * (p_.surge_speed - p_.approach_speed));
  }
  o.hold_position = s.position;
  {
    const Eigen::Vector3d& a = wp_[leg_ - 1];
    const Eigen::Vector2d pp = a.head<2>() + along * Eigen::Vector2d(std::cos(chi_p), std::sin(chi_p));
    o.path_point = Eigen::Vector3d(pp.x(), pp.y(), o.desired_depth);
  }
  o.status_text = "following leg " + std::to_string(leg_) + " of " + std::to_string(wp_.size() - 1);
  return o;
}

}  // namespace guidance
}  // namespace offshore_gnc
