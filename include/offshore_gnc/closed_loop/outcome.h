#pragma once
// A mission's outcome as a skipper means it, the same in both runners (mission_rosfree; the main job's report
// through the mission_outcome tool): success needs the USV on station at the target (or, where the scenario
// expects none, the AUV's search ending without a target) where the true target really is (the USV's true position
// within the stand-off plus the tolerance of it), then the AUV recovered (the USV holding beside it at the surface,
// both stationary: docs/mission.md), no contact between the hull and anything (the AUV included), and the reported
// target within the scenario's tolerance of the true one. ROS-free.
#include <Eigen/Core>

#include <limits>
#include <string>

#include "offshore_gnc/sim/contact.h"

namespace offshore_gnc {
namespace closed_loop {

enum class Outcome {
  kSuccess, kCollision, kMissedTarget, kWrongTarget, kOffStation, kAuvAdrift, kSafetyAbort, kTimeout, kStackDied
};
// success, collision, missed_target, wrong_target, off_station, auv_adrift, safety_abort, timeout, stack_died
const char* toString(Outcome o);

struct OutcomeFacts {
  bool expect_target = true;  // the scenario's mission.expect: target_reached (true) or no_target
  bool held = false;          // the USV came on station at the reported target
  bool recovered = false;     // the USV reported RECOVERED: it holds beside the surfaced AUV, both stationary
  bool auv_no_target = false; // the AUV ended its coverage without a detection
  bool target_reported = false;
  double target_error_m = std::numeric_limits<double>::quiet_NaN();  // horizontal, to the nearest true target
  double target_tolerance_m = 2.0;  // the scenario's mission.target_tolerance
  double min_clearance_m = std::numeric_limits<double>::infinity();  // the hull's (sim/contact.h); <= 0: contact
  double auv_clearance_m = std::numeric_limits<double>::infinity();  // the hull's to the AUV near the surface
  // where the USV really held at the target (at the end of its hold there, before it left for the recovery): its
  // true distance from the nearest true target, and how far is still at it (the stand-off plus the target tolerance)
  double final_distance_m = std::numeric_limits<double>::quiet_NaN();
  double station_tolerance_m = 5.0;
  bool stack_died = false;    // a vehicle's stack stopped
  bool safety_stop = false;   // a supervisor held, stopped or surfaced a vehicle at some time
};

// The first that applies of: stack_died, collision (with an obstacle or the AUV), wrong_target (a target where
// none is, or beyond the tolerance), missed_target (no detection where a target is), off_station (the USV held,
// but not at the true target: e.g. a safety hold short of it became its station), success (recovered too),
// auv_adrift (the search is over but the run ended with the AUV not recovered), safety_abort, timeout.
Outcome classify(const OutcomeFacts& f);

// The USV hull's clearance to the AUV (sim/contact.h's hull against the AUV as a disc of its length) [m].
double auvClearance(const sim::HullFootprint& hull, const Eigen::Vector2d& usv_ne, double usv_yaw,
                    const Eigen::Vector2d& auv_ne, double auv_length);
// The AUV can touch the USV's hull only this close to the surface (its top within the hull's draft, with margin).
inline constexpr double kAuvContactDepth = 1.0;  // [m]

}  // namespace closed_loop
}  // namespace offshore_gnc
