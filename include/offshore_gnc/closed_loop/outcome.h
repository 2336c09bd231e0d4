#pragma once
// A mission's outcome as a skipper means it, the same in both runners (mission_rosfree; the main job's report
// through the mission_outcome tool): success needs the USV on station at the target for the hold time (or, where
// the scenario expects none, the AUV's search ending without a target), no contact between the hull and anything,
// and the reported target within the scenario's tolerance of the true one. ROS-free.
#include <limits>
#include <string>

namespace offshore_gnc {
namespace closed_loop {

enum class Outcome { kSuccess, kCollision, kMissedTarget, kWrongTarget, kSafetyAbort, kTimeout, kStackDied };
const char* toString(Outcome o);  // success, collision, missed_target, wrong_target, safety_abort, timeout, stack_died

struct OutcomeFacts {
  bool expect_target = true;  // the scenario's mission.expect: target_reached (true) or no_target
  bool held = false;          // the USV held at the reported target for the hold time
  bool auv_no_target = false; // the AUV ended its coverage without a detection
  bool target_reported = false;
  double target_error_m = std::numeric_limits<double>::quiet_NaN();  // horizontal, to the nearest true target
  double target_tolerance_m = 2.0;  // the scenario's mission.target_tolerance
  double min_clearance_m = std::numeric_limits<double>::infinity();  // the hull's (sim/contact.h); <= 0: contact
  bool stack_died = false;    // a vehicle's stack stopped (ROS runner)
  bool safety_stop = false;   // a supervisor held, stopped or surfaced a vehicle at some time
};

// The first that applies of: stack_died, collision, wrong_target (a target where none is, or beyond the
// tolerance), missed_target (no detection where a target is), success, safety_abort, timeout.
Outcome classify(const OutcomeFacts& f);

}  // namespace closed_loop
}  // namespace offshore_gnc
