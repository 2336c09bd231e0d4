// Operating region: point in polygon, distance to its edges, path and target checks; origins consistency.
#include "offshore_gnc/safety/region.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/geometry.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace safety {
namespace {

double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Crossing strictly inside both segments: a leg touching a vertex or running along an edge is not counted.
bool properlyCross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                   const Eigen::Vector2d& b) {
  return orient(p, q, a) * orient(p, q, b) < 0.0 && orient(a, b, p) * orient(a, b, q) < 0.0;
}

}  // namespace

Region::Region(std::vector<Eigen::Vector2d> vertices) : v_(std::move(vertices)) {
  if (v_.size() < 3) throw ConfigError("operating region needs at least 3 vertices, has " + std::to_string(v_.size()));
  double area2 = 0.0;
  for (std::size_t i = 0; i < v_.size(); ++i) {
    if (!v_[i].allFinite()) throw ConfigError("operating region vertex " + std::to_string(i) + " is not finite");
    const auto& a = v_[i];
    const auto& b = v_[(i + 1) % v_.size()];
    area2 += a.x() * b.y() - b.x() * a.y();
  }
  if (std::abs(area2) < 1e-6) throw ConfigError("operating region encloses no area (collinear vertices)");
}

Region Region::fromList(const std::vector<double>& xy) {
  if (xy.size() % 2) throw ConfigError("parameter 'region' needs x, y pairs, has " + std::to_string(xy.size()) + " values");
  std::vector<Eigen::Vector2d> v;
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) v.emplace_back(xy[i], xy[i + 1]);
  return Region(std::move(v));
}

bool Region::contains(double x, double y) const {
  if (!std::isfinite(x) || !std::isfinite(y)) return false;
  bool in = false;
  for (std::size_t i = 0, j = v_.size() - 1; i < v_.size(); j = i++) {
    const auto& a = v_[i];
    const auto& b = v_[j];
    // edges straddling the horizontal line through the point, crossed to its right (even-odd rule)
    if ((a.y() > y) != (b.y() > y) && x < a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) in = !in;
  }
  return in || distanceToEdge(x, y) < 1e-9;
}

double Region::distanceToEdge(double x, double y) const {
  const Eigen::Vector2d p(x, y);
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v_.size(); ++i) d = std::min(d, segmentDistance(v_[i], v_[(i + 1) % v_.size()], p));
  return d;
}

std::optional<std::size_t> Region::checkPath(const std::vector<Eigen::Vector2d>& path) const {
  for (std::size_t k = 0; k < path.size(); ++k) {
    if (!contains(path[k].x(), path[k].y())) return k;
    if (k == 0) continue;
    for (std::size_t i = 0; i < v_.size(); ++i)
      if (properlyCross(path[k - 1], path[k], v_[i], v_[(i + 1) % v_.size()])) return k;
  }
  return std::nullopt;
}

std::optional<std::size_t> Region::checkPath(const std::vector<Eigen::Vector3d>& path) const {
  std::vector<Eigen::Vector2d> p;
  p.reserve(path.size());
  for (const auto& q : path) p.push_back(q.head<2>());
  return checkPath(p);
}

std::string Region::checkTarget(double x, double y) const {
  char b[160];
  if (!std::isfinite(x) || !std::isfinite(y)) {
    std::snprintf(b, sizeof b, "target (%g, %g) is not a finite position", x, y);
    return b;
  }
  if (contains(x, y)) return "";
  std::snprintf(b, sizeof b, "target %s from the origin is outside the operating region (nearest edge %s)",
                formatDistance(std::hypot(x, y)).c_str(), formatDistance(distanceToEdge(x, y)).c_str());
  return b;
}

std::string formatDistance(double m) {
  char b[48];
  if (std::abs(m) < 1000.0)
    std::snprintf(b, sizeof b, "%.1f m", m);
  else
    std::snprintf(b, sizeof b, "%.1f km", m / 1000.0);
  return b;
}

}  // namespace safety
}  // namespace offshore_gnc
