// Micron head emulator (include/offshore_gnc/micron_sim/emulator.h).
#include "offshore_gnc/micron_sim/emulator.h"

#include <cmath>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace micron_sim {

using namespace micron;  // the SeaNet protocol's names

namespace {
constexpr double kAdIntervalS = 640e-9;
constexpr double kConfigAckTime = 0.3;  // [s] HeadInf shows SentCfg + NoParams this long, then only SentCfg
}  // namespace

const ParamTable<EmulatorConfig>& EmulatorConfig::table() {
  using E = EmulatorConfig;
  static const ParamTable<E> t =
      ParamTable<E>()
          .string("port", &E::port, "the pseudo-terminal's path (a symlink), the driver's `port`")
          .string("scenario", &E::scenario, "the scenario file whose world the head sees: required")
          .nest("", &E::geometry, HeadGeometry::table())
          .number("sound_speed", &E::sound_speed, 1300, 1700, "m/s", "of the emulated water")
          .number("recentre_time", &E::recentre_time, 0, 60, "s",
                  "after power-up or mtReBoot before the head is centred")
          .number("ping_period", &E::ping_period, 0.001, 5, "s",
                  "from mtSendData to mtHeadData (travel and motor step)")
          .numberAt("noise_level", [](E& e) -> double& { return e.model.noise_level; }, 0, 255, "",
                    "mean speckle intensity of the simulator's sonar model")
          .list("mount", 3, -10, 10, "m", "head in the AUV's body frame (FRD), as the driver's `mount`",
                [](const E& e) { return std::vector<double>{e.model.mount.x(), e.model.mount.y(), e.model.mount.z()}; },
                [](E& e, const std::vector<double>& v) { e.model.mount = {v[0], v[1], v[2]}; })
          .integer("seed", &E::seed, 0, 1 << 30, "the speckle's random seed");
  return t;
}

HeadEmulator::HeadEmulator(const EmulatorConfig& cfg, const sim::World& world) : cfg_(cfg), world_(world) {
  EmulatorConfig::table().validate(cfg);
  requireRange("alive_period", cfg.alive_period, 0.05, 10);  // the head's own, no parameter
}

std::uint8_t HeadEmulator::headInf(double now) const {
  if (now < powered_at_ + cfg_.recentre_time) return kInCentre | kMotoring | kMotorOn | kNoParams;
  if (!model_) return kCentred | kMotorOn | kNoParams;
  if (now < configured_at_ + kConfigAckTime) return kSentCfg | kNoParams | kCentred | kMotorOn;
  return kSentCfg | kCentred | kMotorOn | kInScan;
}

std::string HeadEmulator::receive(const std::uint8_t* data, std::size_t n, double now) {
  events_.clear();
  decoder_.feed(data, n, events_);
  std::string out;
  for (const auto& e : events_)
    if (e.message) out += handle(*e.message, now);
  return out;
}

std::string HeadEmulator::handle(const Message& m, double now) {
  if (auto c = std::get_if<Command>(&m.body)) {
    if (c->type == mtReBoot) {
      counters_.increment("reboots");
      powered_at_ = now;
      next_alive_ = now + cfg_.alive_period;
      model_.reset();
      ping_pending_ = false;
      return {};
    }
    if (c->type == mtSendVersion) {
      counters_.increment("version_requests");
      VersionData v;
      v.software_version = 0x13;
      v.info_bits = 0x02;
      v.uid = 0x2A17;
      v.program_length = 0x0001F400;
      v.checksum = 0xBEEF;
      return encode(fromSonar(v));
    }
    counters_.increment("unsupported");
    return {};
  }
  if (auto hc = std::get_if<HeadCommand>(&m.body)) {
    sim::SonarConfig sc = cfg_.model;
    sc.step = hc->step_angle * (2.0 * kPi / kAngleUnitsPerTurn);
    const int span = ((hc->right_limit - hc->left_limit) % kAngleUnitsPerTurn + kAngleUnitsPerTurn) % kAngleUnitsPerTurn;
    // sim::Sonar scans sectors only: continuous rotation is emulated as a full-circle sector scan.
    if (hc->hd_ctrl & kCont) counters_.increment("continuous_as_sector");
    sc.sector = (hc->hd_ctrl & kCont) ? 2.0 * kPi : span * (2.0 * kPi / kAngleUnitsPerTurn);
    sc.bins = hc->nbins;
    sc.range = hc->ad_interval * kAdIntervalS * cfg_.sound_speed / 2.0 * hc->nbins;
    const int centre = (hc->left_limit + span / 2) % kAngleUnitsPerTurn;
    const int forward = cfg_.geometry.unitsOf(0.0);
    if (!(hc->hd_ctrl & kCont) && std::abs(centre - forward) > 1) counters_.increment("sector_not_centred");
    try {
      model_ = std::make_unique<sim::Sonar>(sc, world_, static_cast<std::uint64_t>(cfg_.seed));
    } catch (const ConfigError&) {
      counters_.increment("bad_head_commands");  // the head keeps NoParams
      model_.reset();
      return {};
    }
    command_ = *hc;
    configured_at_ = now;
    ping_pending_ = false;
    counters_.increment("head_commands");
    return {};
  }
  if (std::get_if<SendData>(&m.body)) {
    counters_.increment("requests");
    if (!model_ || now < powered_at_ + cfg_.recentre_time) {
      counters_.increment("requests_without_params");
      return {};
    }
    if (!ping_pending_) {
      ping_pending_ = true;
      ping_due_ = now + cfg_.ping_period;
    }
    return {};
  }
  counters_.increment("unsupported");
  return {};
}

std::string HeadEmulator::poll(double now) {
  std::string out;
  if (!started_) {
    started_ = true;
    powered_at_ = now;
    next_alive_ = now;
  }
  if (now >= next_alive_) {
    next_alive_ = now + cfg_.alive_period;
    Alive a;
    a.head_time_ms = static_cast<std::uint32_t>(std::fmod(now, 86400.0) * 1000.0);
    a.motor_position = model_ ? static_cast<std::uint16_t>(cfg_.geometry.unitsOf(beam_.bearing)) : 3200;
    a.head_inf = headInf(now);
    out += encode(fromSonar(a));
  }
  if (ping_pending_ && now >= ping_due_ && model_) {
    ping_pending_ = false;
    if (!have_vehicle_) {
      counters_.increment("no_vehicle_state");  // nothing to draw the beam from: the request goes unanswered
      return out;
    }
    VehicleState s = vehicle_;
    s.t = now;
    model_->ping(s, beam_);
    HeadData h;
    h.device_type = command_.head_type;
    h.head_status = kDataRange8;
    h.sweep_code = kScanning;
    h.hd_ctrl = command_.hd_ctrl;
    h.range_scale = command_.range_scale;
    h.gain = command_.igain_ch1;
    h.ad_span = command_.ad_span;
    h.ad_low = command_.ad_low;
    h.ad_interval = command_.ad_interval;
    h.left_limit = command_.left_limit;
    h.right_limit = command_.right_limit;
    h.step_angle = command_.step_angle;
    h.bearing = static_cast<std::uint16_t>(cfg_.geometry.unitsOf(beam_.bearing));
    if (command_.hd_ctrl & kAdc8On) {
      h.data = beam_.intensities;
    } else {  // 4-bit packed, high nibble first
      for (std::size_t i = 0; i + 1 < beam_.intensities.size(); i += 2)
        h.data.push_back(static_cast<std::uint8_t>((beam_.intensities[i] & 0xF0) | (beam_.intensities[i + 1] >> 4)));
    }
    counters_.increment("beams");
    out += encode(fromSonar(h));
  }
  return out;
}

}  // namespace micron_sim
}  // namespace offshore_gnc
