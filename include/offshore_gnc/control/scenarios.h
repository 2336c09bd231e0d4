#pragma once
// The closed-loop scenarios shared by the gtests and `./scripts/bench tracking` (thesis Fig. 4.11, 4.14, 4.19),
// each with a 0.2 m/s current across the main path direction.
#include "offshore_gnc/control/closed_loop.h"

namespace offshore_gnc {
namespace control {
namespace scenarios {

ClosedLoopConfig usvStraight(bool adaptive_crab);  // 5 waypoints on a straight line (Fig. 4.11)
ClosedLoopConfig usvBuoy(bool adaptive_crab);      // straight route with a static buoy on it (Fig. 4.14)
ClosedLoopConfig auvCoverage(bool adaptive_crab);  // Girona500 lawnmower at constant depth (Fig. 4.19)

}  // namespace scenarios
}  // namespace control
}  // namespace offshore_gnc
