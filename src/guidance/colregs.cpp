#include "offshore_gnc/guidance/colregs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/geometry.h"

namespace offshore_gnc {
namespace guidance {

const ParamTable<ColregsParams>& ColregsParams::table() {
  using P = ColregsParams;
  static const ParamTable<P> t = ParamTable<P>()
      .flag("enabled", &P::enabled, "give way to and stand on for moving tracks (rules 13-17)")
      .number("min_speed", &P::min_speed, 0.0, 50.0, "m/s", "a track slower than this stands still (the SBB's)")
      .number("speed_sigmas", &P::speed_sigmas, 0.0, 100.0, "",
              "a track moves only when its speed is at least this many standard deviations of its velocity")
      .number("safe_distance", &P::safe_distance, 0.0, 1000.0, "m",
              "risk of collision: the hull-to-hull closest approach below this")
      .number("tcpa_horizon", &P::tcpa_horizon, 1.0, 3600.0, "s", "risk of collision: the closest approach within this")
      .degrees("head_on_sector_deg", &P::head_on_sector, 0.0, 45.0,
               "head-on: the contact within this of our bow, on a course within this of our reciprocal")
      .degrees("abaft_beam_deg", &P::abaft_beam, 0.0, 67.5,
               "overtaking: coming up from more than this abaft the other's beam (rule 13: 22.5)")
      .degrees("course_offset_deg", &P::course_offset, 5.0, 90.0,
               "give way: the least alteration to starboard of the path's course")
      .degrees("max_course_offset_deg", &P::max_course_offset, 5.0, 150.0,
               "give way: the largest alteration tried to clear the contact")
      .number("stand_on_tcpa", &P::stand_on_tcpa, 0.0, 3600.0, "s",
              "stand on: course and speed kept until the closest approach is this near in time (rule 17)")
      .number("obstacle_lookahead", &P::obstacle_lookahead, 0.0, 600.0, "s",
              "an alteration's course keeps static obstacles clear over this much travel");
  return t;
}

void ColregsParams::validate() const {
  table().validate(*this, "colregs/");
  if (max_course_offset < course_offset)
    throw ConfigError("colregs/max_course_offset_deg must be at least colregs/course_offset_deg");
}

const char* toString(Encounter e) {
  switch (e) {
    case Encounter::kNone: return "none";
    case Encounter::kHeadOn: return "head-on";
    case Encounter::kCrossingGiveWay: return "crossing from starboard";
    case Encounter::kCrossingStandOn: return "crossing from port";
    case Encounter::kOvertaking: return "overtaking";
    case Encounter::kOvertaken: return "being overtaken";
  }
  return "?";
}

Encounter classify(const Eigen::Vector2d& own, double own_course, const Eigen::Vector2d& contact, double contact_course,
                   const ColregsParams& p) {
  const Eigen::Vector2d d = contact - own;
  const double bearing = angleDiff(std::atan2(d.y(), d.x()), own_course);          // it off our bow, + starboard
  const double aspect = angleDiff(std::atan2(-d.y(), -d.x()), contact_course);     // we off its bow
  const double abaft = 0.5 * kPi + p.abaft_beam;
  if (std::abs(aspect) > abaft) return Encounter::kOvertaking;
  if (std::abs(bearing) > abaft) return Encounter::kOvertaken;
  if (std::abs(bearing) <= p.head_on_sector && std::abs(angleDiff(contact_course + kPi, own_course)) <= p.head_on_sector)
    return Encounter::kHeadOn;
  return bearing >= 0.0 ? Encounter::kCrossingGiveWay : Encounter::kCrossingStandOn;
}

Cpa closestApproach(const Eigen::Vector2d& p_own, const Eigen::Vector2d& v_own, const Eigen::Vector2d& p_c,
                    const Eigen::Vector2d& v_c) {
  const Eigen::Vector2d dp = p_c - p_own, dv = v_c - v_own;
  const double dv2 = dv.squaredNorm();
  Cpa c;
  c.tcpa = dv2 < 1e-12 ? 0.0 : -dp.dot(dv) / dv2;  // no relative motion: the range stays as it is
  c.distance = (dp + std::max(c.tcpa, 0.0) * dv).norm();
  return c;
}

bool crossesAhead(const Eigen::Vector2d& p_own, const Eigen::Vector2d& v_own, const Eigen::Vector2d& p_c,
                  const Eigen::Vector2d& v_c) {
  // p_own + v_own s = p_c + v_c u: we reach the crossing point at s, the contact at u
  const double det = v_c.x() * v_own.y() - v_own.x() * v_c.y();
  if (std::abs(det) < 1e-9) return false;  // parallel tracks: no crossing
  const Eigen::Vector2d r = p_c - p_own;
  const double s = (v_c.x() * r.y() - r.x() * v_c.y()) / det;
  const double u = (v_own.x() * r.y() - r.x() * v_own.y()) / det;
  return s > 0.0 && u > s;
}

ColregsAvoidance::ColregsAvoidance(const ColregsParams& p) : p_(p) { p_.validate(); }

void ColregsAvoidance::setParams(const ColregsParams& p) {
  p.validate();
  p_ = p;
}

bool ColregsAvoidance::moving(const Contact& c) const {
  if (!c.confirmed) return false;
  const double speed = c.velocity.norm();
  if (speed < p_.min_speed || speed <= 0.0) return false;
  const Eigen::Vector2d u = c.velocity / speed;
  const double var = u.dot(c.covariance.block<2, 2>(2, 2) * u);
  return speed >= p_.speed_sigmas * std::sqrt(std::max(var, 0.0));
}

void ColregsAvoidance::setTracks(const std::vector<Contact>& tracks, double t) {
  if (!std::isfinite(t)) {
    counters_.increment("bad_tracks");
    return;
  }
  tracks_.clear();
  std::set<std::uint32_t> ids;
  for (const Contact& c : tracks) {
    if (!c.position.allFinite() || !c.velocity.allFinite() || !c.covariance.allFinite() || !std::isfinite(c.length) ||
        !std::isfinite(c.width)) {
      counters_.increment("bad_tracks");
      continue;
    }
    if (c.id == 0 || !ids.insert(c.id).second) {
      counters_.increment("unknown_track_id");
      continue;
    }
    if (moving(c)) tracks_.push_back(c);
  }
  tracks_t_ = t;
}

bool ColregsAvoidance::isMovingTarget(const SbbObstacle& o, double t, double match_gap) const {
  if (!p_.enabled) return false;
  const double dt = std::clamp(t - tracks_t_, 0.0, 2.0);
  for (const Contact& c : tracks_)
    if ((o.origin - (c.position + dt * c.velocity)).norm() <= 0.5 * std::max(c.length, c.width) + match_gap) return true;
  return false;
}

double ColregsAvoidance::reach(const Contact& c, double hull_reach) const {
  return hull_reach + 0.5 * std::max(c.length, c.width);
}

bool ColregsAvoidance::risk(const Contact& c, const Eigen::Vector2d& p, const Eigen::Vector2d& v,
                            double hull_reach) const {
  const Cpa a = closestApproach(p, v, c.position, c.velocity);
  return a.tcpa > 0.0 && a.tcpa <= p_.tcpa_horizon && a.distance - reach(c, hull_reach) < p_.safe_distance;
}

bool ColregsAvoidance::courseClear(double course, const Eigen::Vector2d& p, double speed, double hull_reach,
                                   const std::vector<SbbObstacle>& statics) const {
  const Eigen::Vector2d end = p + speed * p_.obstacle_lookahead * Eigen::Vector2d(std::cos(course), std::sin(course));
  for (const SbbObstacle& o : statics)
    if (segmentDistance(p, end, o.origin) < 0.5 * std::max(o.length, o.width) + hull_reach) return false;
  return true;
}

ColregsOutput ColregsAvoidance::update(double t, const Eigen::Vector2d& p, const Eigen::Vector2d& v,
                                       double leg_course, double path_course, double path_speed, double hull_reach,
                                       const std::vector<SbbObstacle>& statics, bool follow) {
  ColregsOutput out;
  if (!p_.enabled || !p.allFinite() || !v.allFinite() || !std::isfinite(path_course) || !std::isfinite(leg_course) ||
      !std::isfinite(t)) {
    if (p_.enabled) counters_.increment("bad_state");
    active_.clear();
    steering_ = false;
    return out;
  }
  // the contacts now
  const double dt = std::clamp(t - tracks_t_, 0.0, 2.0);
  std::vector<Contact> now = tracks_;
  for (Contact& c : now) c.position += dt * c.velocity;
  for (auto it = active_.begin(); it != active_.end();) {  // a contact no longer tracked (or still): over
    const bool kept = std::any_of(now.begin(), now.end(), [&](const Contact& c) { return c.id == it->first; });
    it = kept ? std::next(it) : active_.erase(it);
  }
  const double speed = v.norm();
  const double own_course = speed > 0.3 ? std::atan2(v.y(), v.x()) : path_course;
  const double run_speed = path_speed > 0.1 ? path_speed : std::max(speed, 0.1);
  const Eigen::Vector2d u_leg(std::cos(leg_course), std::sin(leg_course));
  const Eigen::Vector2d v_path = run_speed * Eigen::Vector2d(std::cos(path_course), std::sin(path_course));
  const Contact* urgent = nullptr;
  double urgent_tcpa = std::numeric_limits<double>::infinity();
  for (const Contact& c : now) {
    const Cpa a = closestApproach(p, v, c.position, c.velocity);
    const bool at_risk = risk(c, p, v, hull_reach);
    auto it = active_.find(c.id);
    if (it == active_.end()) {
      if (!at_risk || !follow) continue;
      const Encounter e = classify(p, own_course, c.position, std::atan2(c.velocity.y(), c.velocity.x()), p_);
      it = active_.emplace(c.id, Active{e, false}).first;
      counters_.increment("encounters");
    }
    Active& e = it->second;
    // Over: an alteration is held until the contact is past and the path's course clears it (without crossing ahead
    // of one we give way to); a stand-on contact that never needed us to act, as soon as the risk is gone.
    const bool path_clear = !risk(c, p, v_path, hull_reach) &&
                            !(e.type == Encounter::kCrossingGiveWay && crossesAhead(p, v_path, c.position, c.velocity));
    // Past: the range opens; meeting or overtaking, also abeam or astern along the leg (two boats that both turned
    // away from a head-on meeting open the range long before they have passed each other, and met again as they
    // both turned back).
    const bool crossing = e.type == Encounter::kCrossingGiveWay || e.type == Encounter::kCrossingStandOn;
    const bool past = a.tcpa <= 0.0 && (crossing || (c.position - p).dot(u_leg) < 0.0);
    if (e.acting ? (past && path_clear) : !at_risk) {
      active_.erase(it);
      counters_.increment("encounters_cleared");
      continue;
    }
    if (!e.acting && follow) {
      if (givesWay(e.type)) {
        e.acting = true;
        counters_.increment("give_way");
      } else if (at_risk && a.tcpa <= p_.stand_on_tcpa) {
        e.acting = true;  // rule 17(b): the give-way vessel has not acted in time
        counters_.increment("stand_on_acted");
      }
    }
    if (a.tcpa < urgent_tcpa || !urgent) {
      urgent = &c;
      urgent_tcpa = a.tcpa;
    }
  }
  bool acting = false;
  for (const auto& kv : active_) acting = acting || kv.second.acting;
  if (!acting || !follow) {
    steering_ = false;
  } else {
    if (!steering_) {
      steering_ = true;
      base_course_ = path_course;
      offset_ = p_.course_offset;
    }
    // The least alteration from the one held (never less: a course that comes and goes is no clear action) that
    // clears every contact acted for, without crossing ahead of a give-way one, and keeps static obstacles clear.
    const double step = deg2rad(5.0);
    double best = -1.0, best_score = -std::numeric_limits<double>::infinity();
    for (double off = offset_; off <= p_.max_course_offset + 1e-9; off += step) {
      const double course = base_course_ + off;
      const Eigen::Vector2d vc = run_speed * Eigen::Vector2d(std::cos(course), std::sin(course));
      double worst = std::numeric_limits<double>::infinity();
      bool ok = true;
      for (const Contact& c : now) {
        auto it = active_.find(c.id);
        if (it == active_.end() || !it->second.acting) continue;
        const Cpa a = closestApproach(p, vc, c.position, c.velocity);
        if (a.tcpa > 0.0) worst = std::min(worst, a.distance - reach(c, hull_reach));
        if (risk(c, p, vc, hull_reach) ||
            (it->second.type == Encounter::kCrossingGiveWay && crossesAhead(p, vc, c.position, c.velocity)))
          ok = false;
      }
      const bool clear_of_statics = courseClear(course, p, run_speed, hull_reach, statics);
      if (ok && clear_of_statics) {
        best = off;
        break;
      }
      // none clears all: the one that passes the contacts widest, static obstacles kept clear first
      const double score = worst + (clear_of_statics ? 1e6 : 0.0);
      if (score > best_score) {
        best_score = score;
        best = off;
      }
      if (off + step > p_.max_course_offset + 1e-9) counters_.increment("no_safe_course");
    }
    offset_ = best;
    out.steer = true;
    out.course = wrapAngle(base_course_ + offset_);
  }
  if (urgent) {
    const Active& e = active_.at(urgent->id);
    const Cpa a = closestApproach(p, v, urgent->position, urgent->velocity);
    out.encounter = e.type;
    out.contact = urgent->id;
    out.action = e.acting ? EncounterAction::kStarboard : EncounterAction::kStandOn;
    out.cpa = a.distance - reach(*urgent, hull_reach);
    out.tcpa = a.tcpa;
  }
  return out;
}

}  // namespace guidance
}  // namespace offshore_gnc
