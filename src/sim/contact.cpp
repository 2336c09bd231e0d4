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

double hullClearance(const HullFootprint& hull, const Eigen::Vector2d& ne, double yaw, const World& world, double t,
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
  for (const auto* vs : {&world.vessels, &extra})
    for (const auto& v : *vs) keep(bg::distance(toBg(vesselFootprint(v, t)), h), "a vessel", vesselPose(v, t).centre);
  for (const auto& s : world.shorelines) keep(bg::distance(toBg(s), h), "the shore", ne);
  return best;
}

}  // namespace sim
}  // namespace offshore_gnc
