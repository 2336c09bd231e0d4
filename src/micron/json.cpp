// JSON lines for decoded SeaNet packets (include/offshore_gnc/micron/json.h).
#include "offshore_gnc/micron/json.h"

#include <cstdio>
#include <sstream>

#include "offshore_gnc/common/angles.h"

namespace offshore_gnc {
namespace micron {

namespace {
std::string hex(const std::uint8_t* p, std::size_t n) {
  std::string s;
  char b[3];
  for (std::size_t i = 0; i < n; ++i) {
    std::snprintf(b, sizeof b, "%02X", p[i]);
    s += b;
  }
  return s;
}
double unitsDeg(int u) { return rad2deg(unitsToRad(u)); }
}  // namespace

std::string toJson(const Message& m, const HeadGeometry& g, double sound_speed) {
  std::ostringstream o;
  o.precision(10);
  o << std::boolalpha;
  o << "{\"type\":\"" << typeName(m.type()) << "\",\"type_id\":" << int(m.type()) << ",\"tx\":" << int(m.tx)
    << ",\"rx\":" << int(m.rx);
  if (auto a = std::get_if<Alive>(&m.body)) {
    o << ",\"head_time_ms\":" << a->head_time_ms << ",\"motor_position_deg\":" << unitsDeg(a->motor_position)
      << ",\"head_inf\":" << int(a->head_inf) << ",\"in_centre\":" << bool(a->head_inf & kInCentre)
      << ",\"centred\":" << bool(a->head_inf & kCentred) << ",\"motoring\":" << bool(a->head_inf & kMotoring)
      << ",\"motor_on\":" << bool(a->head_inf & kMotorOn) << ",\"dir\":" << bool(a->head_inf & kDir)
      << ",\"in_scan\":" << bool(a->head_inf & kInScan) << ",\"no_params\":" << bool(a->head_inf & kNoParams)
      << ",\"sent_cfg\":" << bool(a->head_inf & kSentCfg);
  } else if (auto v = std::get_if<VersionData>(&m.body)) {
    o << ",\"software_version\":" << int(v->software_version) << ",\"info_bits\":" << int(v->info_bits)
      << ",\"uid\":" << v->uid << ",\"program_length\":" << v->program_length << ",\"checksum\":" << v->checksum;
  } else if (auto c = std::get_if<HeadCommand>(&m.body)) {
    o << ",\"v3b\":" << int(c->v3b) << ",\"hd_ctrl\":" << c->hd_ctrl << ",\"adc8on\":" << bool(c->hd_ctrl & kAdc8On)
      << ",\"continuous\":" << bool(c->hd_ctrl & kCont) << ",\"scan_right\":" << bool(c->hd_ctrl & kScanRight)
      << ",\"head_type\":" << int(c->head_type) << ",\"range_scale_m\":" << (c->range_scale & 0x3FFF) / 10.0
      << ",\"left_limit_deg\":" << unitsDeg(c->left_limit) << ",\"right_limit_deg\":" << unitsDeg(c->right_limit)
      << ",\"ad_span\":" << int(c->ad_span) << ",\"ad_low\":" << int(c->ad_low) << ",\"gain\":" << c->igain_ch1 / 210.0
      << ",\"step_deg\":" << unitsDeg(c->step_angle) << ",\"ad_interval\":" << c->ad_interval
      << ",\"bins\":" << c->nbins << ",\"bin_size_m\":" << c->ad_interval * 640e-9 * sound_speed / 2.0
      << ",\"mo_time\":" << int(c->mo_time);
  } else if (auto s = std::get_if<SendData>(&m.body)) {
    o << ",\"time_ms\":" << s->time_ms;
  } else if (auto h = std::get_if<HeadData>(&m.body)) {
    const auto bins = h->bins();
    o << ",\"device_type\":" << int(h->device_type) << ",\"head_status\":" << int(h->head_status)
      << ",\"power_loss\":" << bool(h->head_status & kHdPwrLoss) << ",\"motor_error\":" << bool(h->head_status & kMotErr)
      << ",\"sweep_code\":" << int(h->sweep_code) << ",\"hd_ctrl\":" << h->hd_ctrl
      << ",\"range_scale_m\":" << h->rangeScaleM() << ",\"range_units\":" << h->rangeUnits()
      << ",\"gain\":" << h->gain / 210.0 << ",\"ad_interval\":" << h->ad_interval
      << ",\"bin_size_m\":" << h->ad_interval * 640e-9 * sound_speed / 2.0
      << ",\"left_limit_deg\":" << unitsDeg(h->left_limit) << ",\"right_limit_deg\":" << unitsDeg(h->right_limit)
      << ",\"step_deg\":" << unitsDeg(h->step_angle) << ",\"head_angle_deg\":" << unitsDeg(h->bearing)
      << ",\"bearing_deg\":" << rad2deg(g.bearingOf(h->bearing)) << ",\"bins\":[";
    for (std::size_t i = 0; i < bins.size(); ++i) o << (i ? "," : "") << int(bins[i]);
    o << "]";
  } else if (auto o2 = std::get_if<Other>(&m.body)) {
    o << ",\"body_hex\":\"" << hex(o2->body.data(), o2->body.size()) << "\"";
  }
  o << "}";
  return o.str();
}

std::string rejectionJson(const std::string& reason, const std::vector<std::uint8_t>& raw) {
  return "{\"rejected\":\"" + reason + "\",\"bytes\":" + std::to_string(raw.size()) + ",\"head_hex\":\"" +
         hex(raw.data(), std::min<std::size_t>(raw.size(), 16)) + "\"}";
}

}  // namespace micron
}  // namespace offshore_gnc
