#pragma once
// A mission's outcome as a skipper means it, the same in both runners (mission_rosfree; the main job's report
// through the mission_outcome tool): success needs the USV on station at the target for the hold time (or, where
// the scenario expects none, the AUV's search ending without a target) where the true target really is (the USV's
// true position within the stand-off plus the tolerance of it), no contact between the hull and anything, and the
// reported target within the scenario's tolerance of the true one. ROS-free.
#include <limits>
#include <string>

namespace offshore_gnc {
namespace closed_loop {

enum class Outcome {
  kSuccess, kCollision, kMissedTarget, kWrongTarget, kOffStation, kSafetyAbort, kTimeout, kStackDied
};
// success, collision, missed_target, wrong_target, off_station, safety_abort, timeout, stack_died
const char* toString(Outcome o);

struct OutcomeFacts {
  bool expect_target = true;  // the scenario's mission.expect: target_reached (true) or no_target
  bool held = false;          // the USV held at the reported target for the hold time
  bool auv_no_target = false; // the AUV ended its coverage without a detection
  bool target_reported = false;
  double target_error_m = std::numeric_limits<double>::quiet_NaN();  // horizontal, to the nearest true target
  double target_tolerance_m = 2.0;  // the scenario's mission.target_tolerance
  double min_clearance_m = std::numeric_limits<double>::infinity();  // the hull's (sim/contact.h); <= 0: contact
  // where the USV really ended: its true distance from the nearest true target, and how far is still at it (the
  // mission's stand-off plus the target tolerance)
  double final_distance_m = std::numeric_limits<double>::quiet_NaN();
  double station_tolerance_m = 5.0;
  bool stack_died = false;    // a vehicle's stack stopped (ROS runner)
  bool safety_stop = false;   // a supervisor held, stopped or surfaced a vehicle at some time
};

// The first that applies of: stack_died, collision, wrong_target (a target where none is, or beyond the
// tolerance), missed_target (no detection where a target is), success, off_station (the USV held, but not at the
// true target: e.g. a safety hold short of it became its station), safety_abort, timeout.
Outcome classify(const OutcomeFacts& f);

}  // namespace closed_loop
}  // namespace offshore_gnc
