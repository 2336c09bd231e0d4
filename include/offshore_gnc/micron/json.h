#pragma once
// JSON rendering of decoded SeaNet packets (one object per packet, angles in degrees, ranges in metres), for the
// micron_decode tool and logs.
#include <cstdint>
#include <string>
#include <vector>

#include "offshore_gnc/micron/seanet.h"
#include "offshore_gnc/micron/session.h"

namespace offshore_gnc {
namespace micron {

// `geometry` and `sound_speed` give mtHeadData its bearing (clockwise from the vehicle's forward axis) and
// bin size; the raw head angle is printed too.
std::string toJson(const Message& m, const HeadGeometry& geometry, double sound_speed);
std::string rejectionJson(const std::string& reason, const std::vector<std::uint8_t>& raw);

}  // namespace micron
}  // namespace offshore_gnc
