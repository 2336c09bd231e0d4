#pragma once
// Decodes any frame the stack knows (NMEA 2000 GPS-compass PGNs; our waterjet protocol: 3-axis commands,
// per-jet set-points, status) into one JSON object with SI units, for can_decode and the fuzz targets. Unknown
// ids and broken frames give nullopt with the reason in `error` (unknown_id, wrong_dlc, bad_checksum,
// out_of_range).
#include <optional>
#include <string>

#include "offshore_gnc/can/frame.h"
#include "offshore_gnc/can/waterjet_protocol.h"

namespace offshore_gnc {
namespace can {

std::optional<std::string> decodeToJson(const CandumpLine& line, const jet::Addresses& addresses = {},
                                        std::string* error = nullptr);

}  // namespace can
}  // namespace offshore_gnc
