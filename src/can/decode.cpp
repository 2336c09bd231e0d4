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
  // The fields a status and a per-jet set-point share.
  Json& jet(std::uint8_t jet, double rpm, double nozzle, double bucket) {
    return num("jet", jet).num("rpm", rpm).num("nozzle", nozzle).num("bucket", bucket);
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
  const jet::Decoded d = jet::decode(f, addresses);
  using K = jet::Decoded::Kind;
  switch (d.kind) {
    case K::kCommand:
    case K::kManual:
      return Json(line.stamp, line.iface, id, d.kind == K::kManual ? "waterjet_manual" : "waterjet_command")
          .num("surge", d.command.surge).num("sway", d.command.sway).num("yaw", d.command.yaw)
          .num("source", d.command.source).num("counter", d.command.counter).done();
    case K::kStatus: {
      const jet::Status& st = d.status;
      return Json(line.stamp, line.iface, id, "waterjet_status")
          .jet(st.jet, st.rpm, st.nozzle, st.bucket).num("faults", st.faults).num("counter", st.counter).done();
    }
    case K::kSetpoint: {
      const jet::Setpoint& sp = d.setpoint;
      return Json(line.stamp, line.iface, id, "waterjet_setpoint")
          .jet(sp.jet, sp.rpm, sp.nozzle, sp.bucket).num("source", sp.source).num("counter", sp.counter).done();
    }
    case K::kNone: break;
  }
  return fail(jet::toString(d.error));
}

}  // namespace can
}  // namespace offshore_gnc
