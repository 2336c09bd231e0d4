#include "offshore_gnc/can/decode.h"

#include <cstdio>
#include <sstream>

#include "offshore_gnc/can/nmea2000.h"

namespace offshore_gnc {
namespace can {
namespace {

class Json {
 public:
  Json(double stamp, const std::string& iface, const n2k::IsoId& id, const char* name) {
    os_.precision(10);
    os_ << "{\"t\":" << stamp << ",\"iface\":\"";
    for (char c : iface)  // interface names come from the log: escape what JSON needs
      if (c == '"' || c == '\\') os_ << '\\' << c;
      else if (static_cast<unsigned char>(c) < 0x20) os_ << "?";
      else os_ << c;
    os_ << "\",\"pgn\":" << id.pgn << ",\"priority\":" << int(id.priority) << ",\"source\":" << int(id.source)
        << ",\"name\":\"" << name << "\"";
  }
  Json& num(const char* key, const std::optional<double>& v) {
    os_ << ",\"" << key << "\":";
    if (v) os_ << *v;
    else os_ << "null";
    return *this;
  }
  std::string done() { return os_.str() + "}"; }

 private:
  std::ostringstream os_;
};

}  // namespace

std::optional<std::string> decodeToJson(const CandumpLine& line, const jet::Addresses& addresses, std::string* error) {
  const CanFrame& f = line.frame;
  auto fail = [&](const char* why) -> std::optional<std::string> {
    if (error) *error = why;
    return std::nullopt;
  };
  if (f.error) return fail("error_frame");
  if (!f.extended) return fail("unknown_id");
  const n2k::IsoId id = n2k::decodeId(f.id);
  const bool n2k_pgn = id.pgn == n2k::kPgnPositionRapid || id.pgn == n2k::kPgnVesselHeading ||
                       id.pgn == n2k::kPgnCogSogRapid;
  if (n2k_pgn && f.len != 8) return fail("wrong_dlc");
  if (auto p = n2k::decodePositionRapid(f))
    return Json(line.stamp, line.iface, id, "position_rapid").num("latitude_deg", p->lat_deg).num("longitude_deg", p->lon_deg).done();
  if (auto h = n2k::decodeVesselHeading(f))
    return Json(line.stamp, line.iface, id, "vessel_heading")
        .num("sid", h->sid).num("heading_rad", h->heading_rad).num("deviation_rad", h->deviation_rad)
        .num("variation_rad", h->variation_rad).num("reference", h->reference).done();
  if (auto c = n2k::decodeCogSogRapid(f))
    return Json(line.stamp, line.iface, id, "cog_sog_rapid")
        .num("sid", c->sid).num("reference", c->reference).num("cog_rad", c->cog_rad).num("sog_mps", c->sog_mps).done();
  jet::Command cmd;
  bool manual = false;
  jet::Error e = jet::decodeCommand(f, cmd, &manual);
  if (e == jet::Error::kNone)
    return Json(line.stamp, line.iface, id, manual ? "waterjet_manual" : "waterjet_command")
        .num("surge", cmd.surge).num("sway", cmd.sway).num("yaw", cmd.yaw).num("source", cmd.source)
        .num("counter", cmd.counter).done();
  if (e != jet::Error::kNotOurs) return fail(jet::toString(e));
  jet::Status st;
  e = jet::decodeStatus(f, st, addresses);
  if (e == jet::Error::kNone)
    return Json(line.stamp, line.iface, id, "waterjet_status")
        .num("jet", st.jet).num("rpm", st.rpm).num("nozzle", st.nozzle).num("bucket", st.bucket)
        .num("faults", st.faults).num("counter", st.counter).done();
  if (e != jet::Error::kNotOurs) return fail(jet::toString(e));
  jet::Setpoint sp;
  e = jet::decodeSetpoint(f, sp, addresses);
  if (e == jet::Error::kNone)
    return Json(line.stamp, line.iface, id, "waterjet_setpoint")
        .num("jet", sp.jet).num("rpm", sp.rpm).num("nozzle", sp.nozzle).num("bucket", sp.bucket)
        .num("source", sp.source).num("counter", sp.counter).done();
  return fail(jet::toString(e));
}

}  // namespace can
}  // namespace offshore_gnc
