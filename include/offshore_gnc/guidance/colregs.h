#pragma once
// COLREGs-aware avoidance of moving vessels (issue 33; rules 8, 13-17), ROS-free: the LiDAR's tracks in, a course
// to steer out while an encounter asks for one. Each confirmed moving track is classified from two bearings, as
// MOOS-IvP's BHV_AvdColregs does: where the contact lies off our bow, and where we lie off its bow. Only a contact
// with a risk of collision (hull-to-hull CPA below safe_distance within tcpa_horizon) starts an encounter; its
// type is then kept until it is over (a crossing that swings into an overtaking as we turn is still the crossing).
// Give-way (head-on, crossing from starboard, overtaking): at once, at least course_offset to starboard of the
// leg's course, larger when that does not clear the contact or crosses ahead of it; held until the contact is past
// and the path's own course is clear of it. Stand-on (crossing from port, being overtaken): course and speed kept
// until the rule-17 trigger (TCPA below stand_on_tcpa with the risk still there), then the same turn to
// starboard, never to port. Static obstacles are the SBB's; the supervisor's all-stop is the last resort.
// NED (x north, y east), metres, seconds, radians.
#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/guidance/sbb.h"

namespace offshore_gnc {
namespace guidance {

// A tracked object as guidance takes it (perception::Track, or the Track message): plain, no perception types.
struct Contact {
  std::uint32_t id = 0;                              // from 1 (0: unknown, refused)
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // at time t of setTracks [m]
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // over ground [m/s]
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();  // of (x, y, vx, vy)
  double length = 0.0, width = 0.0;                  // its extent [m]
  bool confirmed = false;
};

struct ColregsParams {
  bool enabled = true;
  double min_speed = 0.5;          // a track slower than this stands still: the SBB's, not an encounter [m/s]
  double speed_sigmas = 2.0;       // ... or whose speed is within this many of its velocity's standard deviations
  double safe_distance = 10.0;     // hull-to-hull closest approach wanted [m]
  double tcpa_horizon = 120.0;     // a closest approach later than this is no risk yet [s]
  double head_on_sector = deg2rad(10.0);  // each ahead of the other within this: head-on (rule 14) [rad]
  double abaft_beam = deg2rad(22.5);      // more than this abaft the beam: overtaking (rule 13) [rad]
  double course_offset = deg2rad(35.0);   // the least alteration to starboard (rule 16: large) [rad]
  double max_course_offset = deg2rad(90.0);  // the largest tried [rad]
  double stand_on_tcpa = 30.0;     // rule 17: the stand-on vessel acts when the closest approach is this near [s]
  double obstacle_lookahead = 30.0;  // a course must keep static obstacles clear over this much travel [s]
  static const ParamTable<ColregsParams>& table();
  void validate() const;
};

enum class Encounter : std::uint8_t {
  kNone = 0,
  kHeadOn = 1,          // rule 14: give way (both turn to starboard)
  kCrossingGiveWay = 2, // rule 15: the contact on our starboard side
  kCrossingStandOn = 3, // rule 15: on our port side (rule 17)
  kOvertaking = 4,      // rule 13: we overtake it: give way
  kOvertaken = 5,       // rule 13: it overtakes us: stand on (rule 17)
};
const char* toString(Encounter e);
inline bool givesWay(Encounter e) {
  return e == Encounter::kHeadOn || e == Encounter::kCrossingGiveWay || e == Encounter::kOvertaking;
}

enum class EncounterAction : std::uint8_t { kNone = 0, kStandOn = 1, kStarboard = 2 };

// Rules 13-15 from the geometry alone: `own_course` and the contact's course over ground, its position relative
// to ours. No risk test (classify only those with one).
Encounter classify(const Eigen::Vector2d& own_position, double own_course, const Eigen::Vector2d& contact_position,
                   double contact_course, const ColregsParams& p);

struct Cpa {
  double tcpa = 0.0;      // [s] (<= 0: the range opens)
  double distance = 0.0;  // centre to centre at tcpa (at t = 0 when opening) [m]
};
// Closest approach of two constant velocities; no relative motion: now.
Cpa closestApproach(const Eigen::Vector2d& p_own, const Eigen::Vector2d& v_own, const Eigen::Vector2d& p_c,
                    const Eigen::Vector2d& v_c);
// Whether we, at `v_own`, cross the contact's track line ahead of it (the point where we cross it not yet reached
// by the contact). False when we never cross its track.
bool crossesAhead(const Eigen::Vector2d& p_own, const Eigen::Vector2d& v_own, const Eigen::Vector2d& p_c,
                  const Eigen::Vector2d& v_c);

// What guidance does about traffic this step.
struct ColregsOutput {
  bool steer = false;       // follow `course` (over ground) at the path's speed instead of the LOS heading
  double course = 0.0;      // [rad]
  Encounter encounter = Encounter::kNone;  // the most urgent encounter's
  std::uint32_t contact = 0;
  EncounterAction action = EncounterAction::kNone;
  double cpa = 0.0;         // its hull-to-hull closest approach on our present velocity [m]
  double tcpa = 0.0;        // [s]
};

class ColregsAvoidance {
 public:
  explicit ColregsAvoidance(const ColregsParams& p = ColregsParams());
  void setParams(const ColregsParams& p);
  const ColregsParams& params() const { return p_; }
  // The tracks of one frame at time t. Refused and counted: non-finite (bad_tracks), id 0 or repeated
  // (unknown_track_id); tentative or standing still: no encounter (the SBB's, when boxed).
  void setTracks(const std::vector<Contact>& tracks, double t);
  // Whether `o` at time t is a moving track's target (not to be boxed as if it stood still).
  bool isMovingTarget(const SbbObstacle& o, double t, double match_gap) const;

  // One step: our position and velocity over ground, the active leg's direction, the path's course (LOS's, what is
  // resumed) and speed, our
  // hull's reach and the static obstacles (for the course's run). No path to follow: pass follow = false (the
  // encounters are kept, nothing steered).
  ColregsOutput update(double t, const Eigen::Vector2d& position, const Eigen::Vector2d& velocity,
                       double leg_course, double path_course, double path_speed, double hull_reach,
                       const std::vector<SbbObstacle>& statics, bool follow);
  const Counters& counters() const { return counters_; }  // bad_tracks, unknown_track_id, give_way, stand_on_acted...

 private:
  struct Active {
    Encounter type = Encounter::kNone;
    bool acting = false;
  };
  bool moving(const Contact& c) const;
  double reach(const Contact& c, double hull_reach) const;
  // The hull-to-hull closest approach is below safe_distance within the horizon.
  bool risk(const Contact& c, const Eigen::Vector2d& p, const Eigen::Vector2d& v, double hull_reach) const;
  bool courseClear(double course, const Eigen::Vector2d& p, double speed, double hull_reach,
                   const std::vector<SbbObstacle>& statics) const;

  ColregsParams p_;
  std::vector<Contact> tracks_;  // moving, confirmed, at tracks_t_
  double tracks_t_ = 0.0;
  std::map<std::uint32_t, Active> active_;
  bool steering_ = false;
  double base_course_ = 0.0, offset_ = 0.0;  // the course resumed from, the alteration held
  Counters counters_;
};

}  // namespace guidance
}  // namespace offshore_gnc
