#pragma once
// Contact between the USV's hull and what is in the water, for judging a mission as a skipper would: the hull's
// footprint (its outline in the body frame, turning with the boat) against each obstacle's true shape (buoys as
// discs, vessels as their boxes, the shorelines as polygons), not a reference point against circles. ROS-free.
#include <Eigen/Core>

#include <string>
#include <vector>

#include "offshore_gnc/models/hull.h"
#include "offshore_gnc/sim/world.h"

namespace offshore_gnc {
namespace sim {

// The hull's footprint is the vehicle's (models::HullFootprint: guidance keeps it clear too).
using models::HullFootprint;

// Signed clearance [m] between the placed hull and the nearest obstacle of `world` (and `extra` vessels, e.g. a
// fault's), its vessels where they are at time t [s]: > 0 the gap, <= 0 contact (0 when the shapes touch or
// overlap; a buoy's centre inside the hull gives minus its radius). +inf when the world is empty. `nearest`, when
// given, names the nearest obstacle and where it is.
double hullClearance(const HullFootprint& hull, const Eigen::Vector2d& ne, double yaw, const World& world, double t,
                     const std::vector<Vessel>& extra = {}, std::string* nearest = nullptr);

}  // namespace sim
}  // namespace offshore_gnc
