#include "offshore_gnc/closed_loop/outcome.h"

#include <cmath>

namespace offshore_gnc {
namespace closed_loop {

const char* toString(Outcome o) {
  switch (o) {
    case Outcome::kSuccess: return "success";
    case Outcome::kCollision: return "collision";
    case Outcome::kMissedTarget: return "missed_target";
    case Outcome::kWrongTarget: return "wrong_target";
    case Outcome::kOffStation: return "off_station";
    case Outcome::kAuvAdrift: return "auv_adrift";
    case Outcome::kSafetyAbort: return "safety_abort";
    case Outcome::kTimeout: return "timeout";
    case Outcome::kStackDied: return "stack_died";
  }
  return "unknown";
}

Outcome classify(const OutcomeFacts& f) {
  if (f.stack_died) return Outcome::kStackDied;
  if (f.min_clearance_m <= 0.0 || f.auv_clearance_m <= 0.0) return Outcome::kCollision;
  // a report where nothing lies, or farther than the tolerance: the USV was sent to the wrong place
  if (f.target_reported && (!f.expect_target || !(f.target_error_m <= f.target_tolerance_m))) return Outcome::kWrongTarget;
  if (f.expect_target && f.auv_no_target) return Outcome::kMissedTarget;
  // the USV held, but where the true target is not (a safety hold short of it became its station)
  if (f.expect_target && f.held && !(f.final_distance_m <= f.station_tolerance_m)) return Outcome::kOffStation;
  if (f.recovered && (f.expect_target ? f.held : f.auv_no_target)) return Outcome::kSuccess;
  // the search is over (the AUV then comes up) but nobody picked the AUV up: a vehicle left in the water
  if ((f.target_reported || f.auv_no_target) && !f.recovered) return Outcome::kAuvAdrift;
  return f.safety_stop ? Outcome::kSafetyAbort : Outcome::kTimeout;
}

double auvClearance(const sim::HullFootprint& hull, const Eigen::Vector2d& usv_ne, double usv_yaw,
                    const Eigen::Vector2d& auv_ne, double auv_length) {
  sim::World w;
  sim::Buoy b;
  b.centre = auv_ne;
  b.radius = 0.5 * auv_length;
  w.buoys.push_back(b);
  return sim::hullClearance(hull, usv_ne, usv_yaw, w, 0.0);  // a world of the AUV alone: nothing moves in it
}

}  // namespace closed_loop
}  // namespace offshore_gnc
