#pragma once
// The closed-loop scenarios shared by the gtests and `./scripts/bench tracking` (thesis Fig. 4.11, 4.14, 4.19),
// each with a 0.2 m/s current across the main path direction.
#include "offshore_gnc/closed_loop/closed_loop.h"

namespace offshore_gnc {
namespace closed_loop {
namespace scenarios {

ClosedLoopConfig usvStraight(bool adaptive_crab);  // 5 waypoints on a straight line (Fig. 4.11)
ClosedLoopConfig usvBuoy(bool adaptive_crab);      // straight route with a static buoy on it (Fig. 4.14)
ClosedLoopConfig auvCoverage(bool adaptive_crab);  // Girona500 lawnmower at constant depth (Fig. 4.19)
// The route of the simulator rostest (test/rostest/closed_loop): config/scenarios/pyhajarvi.yaml's buoy 25 m ahead of
// a boat at rest, waypoints every 40 m, config/guidance/usv.yaml's settings.
ClosedLoopConfig usvNearBuoy(bool adaptive_crab);
// Station keeping from rest: the path ends at once, the current sets the boat off (the mission's USV waiting).
ClosedLoopConfig usvHoldFromRest();
// The default mission's transit: from rest, 57 m north-west with waypoints every 10 m, the whole path inside the
// slowdown before the stand-off point, the current across it.
ClosedLoopConfig usvShortTransit();

}  // namespace scenarios
}  // namespace closed_loop
}  // namespace offshore_gnc
