#pragma once
// Mission path builders (paper 3.2.3, thesis 4.3): the building blocks the mission logic calls. ROS-free, NED.
#include <Eigen/Core>

#include <vector>

namespace offshore_gnc {
namespace guidance {

// Straight line from `start` to `goal` with a waypoint every `spacing` metres (the last leg may be shorter).
// Both ends included. A goal at the start (closer than 1e-3 m) or non-finite input gives an empty path, which
// guidance reports as "no path" (hold).
std::vector<Eigen::Vector3d> straightLine(const Eigen::Vector3d& start, const Eigen::Vector3d& goal,
                                          double spacing = 10.0);

// Lawnmower coverage of the rectangle with corner `corner`, extent `length` along `heading` (NED yaw) and
// `width` to starboard of it, at constant `depth`; tracks `spacing` apart. Empty on non-positive sizes.
std::vector<Eigen::Vector3d> lawnmower(const Eigen::Vector2d& corner, double heading, double length, double width,
                                       double spacing, double depth);

}  // namespace guidance
}  // namespace offshore_gnc
