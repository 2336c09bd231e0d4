#include "offshore_gnc/ros/site.h"

#include <ros/node_handle.h>

#include "offshore_gnc/ros/params.h"

namespace offshore_gnc {
namespace ros_util {

geo::LatLonAlt readOrigin() {
  const ros::NodeHandle site("/site");
  XmlRpc::XmlRpcValue v;
  if (!site.getParam("origin", v))
    throw ConfigError("no site origin: parameter '/site/origin' is not set (launch with origin:=LAT,LON[,ALT] or "
                      "site:=FILE holding origin: {latitude, longitude, altitude}; in simulation the scenario sets it)");
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString) return geo::parseLatLonAlt(static_cast<std::string>(v));
  for (const char* k : {"latitude", "longitude"})
    if (!site.hasParam(std::string("origin/") + k))
      throw ConfigError(std::string("site origin: parameter '/site/origin/") + k + "' is missing");
  geo::LatLonAlt o;
  readParams(ParamReader(site), geo::LatLonAlt::table(), o, "origin/");
  geo::checkLatLonAlt(o, "/site/origin");
  return o;
}

}  // namespace ros_util
}  // namespace offshore_gnc
