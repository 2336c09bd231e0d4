#pragma once
// The operation's site: the local origin every node of both vehicles shares. It belongs to the operation, not to a
// vehicle: launch/common.launch sets /site/origin once per master, from `origin:=LAT,LON[,ALT]`, or else from a
// site file (`site:=FILE`, in simulation the scenario), whose key `origin: {latitude, longitude, altitude}` it
// loads under /site. The relays compare the two vehicles' origins at link-up (docs/relay.md).
#include "offshore_gnc/geo/geo.h"

namespace offshore_gnc {
namespace ros_util {

// /site/origin: a map {latitude, longitude, altitude} or the text "LAT,LON[,ALT]". Throws ConfigError saying how
// to set it when it is missing, and naming the key when a value is not a finite number in range.
geo::LatLonAlt readOrigin();

}  // namespace ros_util
}  // namespace offshore_gnc
