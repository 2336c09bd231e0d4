#pragma once
// JSON rendering of decoded SeaTrac messages in SI units (metres, degrees, m/s, seconds, dB), one object per
// message, for the usbl_decode tool and logs.
#include <string>

#include "offshore_gnc/usbl/seatrac.h"

namespace offshore_gnc {
namespace usbl {

std::string toJson(const Message& m);
std::string rejectionJson(const std::string& reason, const std::string& line);
std::string jsonEscape(const std::string& s);

}  // namespace usbl
}  // namespace offshore_gnc
