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
    case Outcome::kSafetyAbort: return "safety_abort";
    case Outcome::kTimeout: return "timeout";
    case Outcome::kStackDied: return "stack_died";
  }
  return "unknown";
}

Outcome classify(const OutcomeFacts& f) {
  if (f.stack_died) return Outcome::kStackDied;
  if (f.min_clearance_m <= 0.0) return Outcome::kCollision;
  // a report where nothing lies, or farther than the tolerance: the USV was sent to the wrong place
  if (f.target_reported && (!f.expect_target || !(f.target_error_m <= f.target_tolerance_m))) return Outcome::kWrongTarget;
  if (f.expect_target && f.auv_no_target) return Outcome::kMissedTarget;
  if (f.expect_target && f.held)
    return f.final_distance_m <= f.station_tolerance_m ? Outcome::kSuccess : Outcome::kOffStation;
  if (!f.expect_target && f.auv_no_target) return Outcome::kSuccess;
  return f.safety_stop ? Outcome::kSafetyAbort : Outcome::kTimeout;
}

}  // namespace closed_loop
}  // namespace offshore_gnc
