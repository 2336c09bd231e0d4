#include "offshore_gnc/models/hull.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

namespace offshore_gnc {
namespace models {

const ParamTable<HullFootprint>& HullFootprint::table() {
  using H = HullFootprint;
  static const ParamTable<H> t = ParamTable<H>().numbers(
      "vehicle/outline", &H::outline, 0, -100.0, 100.0, "m",
      "the hull's waterline outline, body x forward, y starboard, about the reference point: x0, y0, x1, y1, ...");
  return t;
}

void HullFootprint::validate() const {
  if (outline.size() < 6 || outline.size() % 2 != 0)
    throw ConfigError("parameter 'vehicle/outline' needs at least 3 corners as x, y pairs, has " +
                      std::to_string(outline.size()) + " values");
  table().validate(*this);
}

std::vector<Eigen::Vector2d> HullFootprint::placed(const Eigen::Vector2d& ne, double yaw) const {
  const Eigen::Rotation2Dd r(yaw);  // body (x forward, y starboard) -> NED (north, east)
  std::vector<Eigen::Vector2d> p;
  for (std::size_t i = 0; i + 1 < outline.size(); i += 2) p.push_back(ne + r * Eigen::Vector2d(outline[i], outline[i + 1]));
  return p;
}

double HullFootprint::ahead() const {
  double x = 0.0;
  for (std::size_t i = 0; i + 1 < outline.size(); i += 2) x = std::max(x, outline[i]);
  return x;
}

double HullFootprint::astern() const {
  double x = 0.0;
  for (std::size_t i = 0; i + 1 < outline.size(); i += 2) x = std::max(x, -outline[i]);
  return x;
}

double HullFootprint::abeam() const {
  double y = 0.0;
  for (std::size_t i = 0; i + 1 < outline.size(); i += 2) y = std::max(y, std::abs(outline[i + 1]));
  return y;
}

}  // namespace models
}  // namespace offshore_gnc
