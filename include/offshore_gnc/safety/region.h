#pragma once
// The operating region (after MOOS-IvP's OpRegion): a simple polygon in local NED (x north, y east) the vehicle
// must stay in; convex or concave, vertices in either winding. Also the check that two vehicles' local origins
// agree (their NED frames only line up when they do). ROS-free.
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace offshore_gnc {
namespace safety {

class Region {
 public:
  // Throws ConfigError unless there are >= 3 finite vertices enclosing a non-zero area.
  explicit Region(std::vector<Eigen::Vector2d> vertices);
  // From a flat list x0, y0, x1, y1, ... (the `region` parameter).
  static Region fromList(const std::vector<double>& xy);

  // Inside (even-odd crossing rule, correct for concave polygons); a point on an edge counts as inside.
  bool contains(double x, double y) const;
  // Distance to the nearest edge [m] (inside or outside).
  double distanceToEdge(double x, double y) const;
  // Index of the first point outside, or of the first point whose leg from the previous point crosses the
  // boundary (a concave region can be left between two inside points); nothing when the whole path is inside.
  std::optional<std::size_t> checkPath(const std::vector<Eigen::Vector2d>& path) const;
  std::optional<std::size_t> checkPath(const std::vector<Eigen::Vector3d>& path) const;  // z ignored
  // Empty when the target may be used, else one sentence saying why it is refused, e.g. "target 2520.3 km from
  // the origin is outside the operating region (nearest edge 2519.8 km)".
  std::string checkTarget(double x, double y) const;

  const std::vector<Eigen::Vector2d>& vertices() const { return v_; }

 private:
  std::vector<Eigen::Vector2d> v_;
};

// "12.3 m" below 1 km, "2520.3 km" above: distances as messages print them.
std::string formatDistance(double metres);


}  // namespace safety
}  // namespace offshore_gnc
