#include "offshore_gnc/usbl/json.h"

#include <cstdio>
#include <sstream>

namespace offshore_gnc {
namespace usbl {

namespace {
std::string hexBytes(const std::vector<std::uint8_t>& v) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string s;
  for (auto b : v) {
    s += kHex[b >> 4];
    s += kHex[b & 15];
  }
  return s;
}

void fixFields(std::ostringstream& os, const AcoFix& f) {
  os << ",\"dest_id\":" << int(f.dest_id) << ",\"src_id\":" << int(f.src_id) << ",\"flags\":" << int(f.flags)
     << ",\"range_valid\":" << (f.has(AcoFix::RANGE) ? "true" : "false")
     << ",\"usbl_valid\":" << (f.has(AcoFix::USBL) ? "true" : "false")
     << ",\"position_valid\":" << (f.has(AcoFix::POSITION) ? "true" : "false")
     << ",\"position_enhanced\":" << (f.has(AcoFix::ENHANCED) ? "true" : "false")
     << ",\"position_filter_error\":" << (f.has(AcoFix::FILTER_ERROR) ? "true" : "false")
     << ",\"msg_type\":" << int(f.msg_type) << ",\"yaw_deg\":" << f.yaw * 0.1 << ",\"pitch_deg\":" << f.pitch * 0.1
     << ",\"roll_deg\":" << f.roll * 0.1 << ",\"depth_local_m\":" << f.depth_local * 0.1
     << ",\"sound_speed_mps\":" << f.vos * 0.1 << ",\"rssi_db\":" << f.rssi * 0.1;
  if (f.has(AcoFix::RANGE))
    os << ",\"range_count\":" << f.range_count << ",\"range_time_s\":" << f.rangeTimeS()
       << ",\"range_m\":" << f.rangeM();
  if (f.has(AcoFix::USBL)) {
    os << ",\"usbl_rssi_db\":[";
    for (std::size_t i = 0; i < f.usbl_rssi.size(); ++i) os << (i ? "," : "") << f.usbl_rssi[i] * 0.1;
    os << "],\"azimuth_deg\":" << f.azimuth * 0.1 << ",\"elevation_deg\":" << f.elevation * 0.1
       << ",\"fit_error\":" << f.fitError();
  }
  if (f.has(AcoFix::POSITION))
    os << ",\"east_m\":" << f.east * 0.1 << ",\"north_m\":" << f.north * 0.1 << ",\"depth_m\":" << f.depth * 0.1;
}
}  // namespace

std::string jsonEscape(const std::string& s) {
  std::string o;
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      o += '\\';
      o += static_cast<char>(c);
    } else if (c < 0x20 || c >= 0x7F) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      o += buf;
    } else {
      o += static_cast<char>(c);
    }
  }
  return o;
}

std::string toJson(const Message& m) {
  std::ostringstream os;
  os.precision(10);
  const auto payload = encodePayload(m);
  os << "{\"cid\":\"" << cidName(payload[0]) << "\",\"direction\":\"" << (m.command ? "command" : "reply") << "\"";
  std::visit(
      [&os](const auto& b) {
        using T = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<T, PingSend>) {
          os << ",\"dest_id\":" << int(b.dest_id) << ",\"msg_type\":" << int(b.msg_type);
        } else if constexpr (std::is_same_v<T, StatusReply>) {
          os << ",\"status\":" << int(b.status) << ",\"status_name\":\""
             << (b.status == kStatusOk ? "OK" : b.status == kStatusXcvrRespTimeout ? "XCVR_RESP_TIMEOUT" : "OTHER")
             << "\",\"beacon_id\":" << int(b.beacon_id);
        } else if constexpr (std::is_same_v<T, FixMessage>) {
          fixFields(os, b.fix);
        } else if constexpr (std::is_same_v<T, DatSend>) {
          os << ",\"dest_id\":" << int(b.dest_id) << ",\"msg_type\":" << int(b.msg_type) << ",\"data_hex\":\""
             << hexBytes(b.data) << "\"";
        } else if constexpr (std::is_same_v<T, DatReceive>) {
          fixFields(os, b.fix);
          os << ",\"ack\":" << (b.ack ? "true" : "false") << ",\"data_hex\":\"" << hexBytes(b.data) << "\"";
        } else {
          os << ",\"payload_hex\":\"" << hexBytes(b.payload) << "\",\"decoded\":false";
        }
      },
      m.body);
  os << "}";
  return os.str();
}

std::string rejectionJson(const std::string& reason, const std::string& line) {
  return "{\"rejected\":\"" + jsonEscape(reason) + "\",\"line\":\"" + jsonEscape(line) + "\"}";
}

}  // namespace usbl
}  // namespace offshore_gnc
