#include "offshore_gnc/perception/target_geometry.h"

#include <cmath>
#include <limits>

namespace offshore_gnc {
namespace perception {

TargetGeometry describeTarget(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& sensor) {
  TargetGeometry g;
  g.num_points = points.size();
  if (points.empty()) return g;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin, best = zmin;
  for (const auto& p : points) {
    sum += p;
    zmin = std::min(zmin, p.z());
    zmax = std::max(zmax, p.z());
    const double d2 = (p.head<2>() - sensor.head<2>()).squaredNorm();
    if (d2 < best) {
      best = d2;
      g.nearest = p;
    }
  }
  g.centroid = sum / static_cast<double>(points.size());
  g.height = zmax - zmin;
  g.range = std::sqrt(best);

  // Angular extremes relative to the centroid direction (rotate so the centroid is at angle 0).
  Eigen::Vector2d c = g.centroid.head<2>() - sensor.head<2>();
  if (c.squaredNorm() == 0.0) c = Eigen::Vector2d(1, 0);
  c.normalize();
  double amin = std::numeric_limits<double>::infinity(), amax = -amin;
  const Eigen::Vector3d* first = &points.front();
  const Eigen::Vector3d* last = &points.front();
  for (const auto& p : points) {
    const Eigen::Vector2d r = p.head<2>() - sensor.head<2>();
    const double a = pseudoAngle(c.x() * r.y() - c.y() * r.x(), c.dot(r));
    if (a < amin) { amin = a; first = &p; }
    if (a > amax) { amax = a; last = &p; }
  }
  g.origin = 0.5 * (*first + *last);
  Eigen::Vector2d u = last->head<2>() - first->head<2>();
  if (u.squaredNorm() < 1e-12) u = Eigen::Vector2d(-c.y(), c.x());  // one return: across the line of sight
  u.normalize();
  g.axis = Eigen::Vector3d(u.x(), u.y(), 0.0);
  const Eigen::Vector2d n(-u.y(), u.x());
  double lmin = std::numeric_limits<double>::infinity(), lmax = -lmin, wmin = lmin, wmax = -lmin;
  for (const auto& p : points) {
    const double l = u.dot(p.head<2>()), w = n.dot(p.head<2>());
    lmin = std::min(lmin, l); lmax = std::max(lmax, l);
    wmin = std::min(wmin, w); wmax = std::max(wmax, w);
  }
  g.length = lmax - lmin;
  g.width = wmax - wmin;
  const Eigen::Vector2d o = g.origin.head<2>() - sensor.head<2>();
  g.bearing = std::atan2(o.y(), o.x());
  return g;
}

}  // namespace perception
}  // namespace offshore_gnc
