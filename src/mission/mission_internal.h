#pragma once
// Internal to the mission module, shared by its parts, by what they do:
//   mission.cpp       phase names, holdPath;
//   auv_mission.cpp   the AUV's mission (search, hold, ascent, surface) and its coverage path;
//   usv_mission.cpp   the USV's mission (transit, arrival, manual, peer), its status intake;
//   usv_recovery.cpp  the USV's recovery of the surfaced AUV (the side, the run-in, the close-in, RECOVERED).
#include <limits>

#include "offshore_gnc/mission/mission.h"

namespace offshore_gnc {
namespace mission {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace mission
}  // namespace offshore_gnc
