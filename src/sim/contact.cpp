#include "offshore_gnc/sim/contact.h"

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace offshore_gnc {
namespace sim {

namespace bg = boost::geometry;
using BgPoint = bg::model::d2::point_xy<double>;
using BgPolygon = bg::model::polygon<BgPoint>;

namespace {
BgPolygon toBg(const Polygon& p) {
  BgPolygon out;
  for (const auto& v : p) bg::append(out.outer(), BgPoint(v.x(), v.y()));
  if (!p.empty()) bg::append(out.outer(), BgPoint(p.front().x(), p.front().y()));
  bg::correct(out);  // orientation and closure as Boost.Geometry wants them
  return out;
}
}  // namespace

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

Polygon HullFootprint::placed(const Eigen::Vector2d& ne, double yaw) const {
  const Eigen::Rotation2Dd r(yaw);  // body (x forward, y starboard) -> NED (north, east)
  Polygon p;
  for (std::size_t i = 0; i + 1 < outline.size(); i += 2) p.push_back(ne + r * Eigen::Vector2d(outline[i], outline[i + 1]));
  return p;
}

double hullClearance(const HullFootprint& hull, const Eigen::Vector2d& ne, double yaw, const World& world,
                     const std::vector<Vessel>& extra, std::string* nearest) {
  const BgPolygon h = toBg(hull.placed(ne, yaw));
  double best = std::numeric_limits<double>::infinity();
  const auto keep = [&](double d, const char* what, const Eigen::Vector2d& at) {
    if (!(d < best)) return;
    best = d;
    if (nearest) {
      char b[96];
      std::snprintf(b, sizeof b, "%s at N %.1f E %.1f", what, at.x(), at.y());
      *nearest = b;
    }
  };
  for (const auto& b : world.buoys) {
    const BgPoint c(b.centre.x(), b.centre.y());
    keep(bg::within(c, h) ? -b.radius : bg::distance(c, h) - b.radius, "a buoy", b.centre);
  }
  for (const auto& v : world.vessels) keep(bg::distance(toBg(vesselFootprint(v)), h), "a vessel", v.centre);
  for (const auto& v : extra) keep(bg::distance(toBg(vesselFootprint(v)), h), "a vessel", v.centre);
  for (const auto& s : world.shorelines) keep(bg::distance(toBg(s), h), "the shore", ne);
  return best;
}

}  // namespace sim
}  // namespace offshore_gnc
