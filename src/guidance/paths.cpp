#include "offshore_gnc/guidance/paths.h"

#include <cmath>

namespace offshore_gnc {
namespace guidance {

std::vector<Eigen::Vector3d> straightLine(const Eigen::Vector3d& start, const Eigen::Vector3d& goal,
                                          double spacing) {
  std::vector<Eigen::Vector3d> out;
  if (!start.allFinite() || !goal.allFinite() || !std::isfinite(spacing) || spacing <= 0.0) return out;
  const double len = (goal - start).norm();
  if (len < 1e-3) return out;
  const int n = static_cast<int>(std::ceil(len / spacing - 1e-9));
  for (int i = 0; i < n; ++i) out.push_back(start + (goal - start) * (i * spacing / len));
  out.push_back(goal);
  return out;
}

std::vector<Eigen::Vector3d> lawnmower(const Eigen::Vector2d& corner, double heading, double length, double width,
                                       double spacing, double depth) {
  std::vector<Eigen::Vector3d> out;
  if (!(length > 0.0) || !(width >= 0.0) || !(spacing > 0.0) || !corner.allFinite() || !std::isfinite(heading) ||
      !std::isfinite(depth))
    return out;
  const Eigen::Vector2d along(std::cos(heading), std::sin(heading));
  const Eigen::Vector2d across(-std::sin(heading), std::cos(heading));  // starboard of `heading` in NED
  const int tracks = static_cast<int>(std::floor(width / spacing + 1e-9)) + 1;
  for (int i = 0; i < tracks; ++i) {
    const Eigen::Vector2d base = corner + across * (i * spacing);
    const Eigen::Vector2d a = (i % 2 == 0) ? base : base + along * length;
    const Eigen::Vector2d b = (i % 2 == 0) ? base + along * length : base;
    out.emplace_back(a.x(), a.y(), depth);
    out.emplace_back(b.x(), b.y(), depth);
  }
  return out;
}

}  // namespace guidance
}  // namespace offshore_gnc
