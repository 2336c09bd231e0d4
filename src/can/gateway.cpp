#include "offshore_gnc/can/gateway.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace can {

const ParamTable<GatewayConfig>& GatewayConfig::table() {
  using C = GatewayConfig;
  static const ParamTable<C> t =
      ParamTable<C>()
          .number("command_rate", &C::command_rate, 1.0, 200.0, "Hz", "command frames per second")
          .number("watchdog_timeout", &C::watchdog_timeout, 0.01, 10.0, "s",
                  "no autonomy command for this long: the neutral command (source watchdog)")
          .number("manual_hold", &C::manual_hold, 0.01, 10.0, "s", "a manual frame from the bridge silences autonomy this long")
          .number("jet_timeout", &C::jet_timeout, 0.01, 10.0, "s",
                  "no valid status frame from a jet for this long: it is not answering (both jets neutral)")
          .choice("command_frames", &C::command_frames, {"jets", "joystick"},
                  "jets: per-jet set-points allocated here; joystick: the 3-axis frame, for units that allocate it")
          .nest("address/", &C::addresses, jet::Addresses::table());
  return t;
}

const ParamTable<GatewayNodeParams>& GatewayNodeParams::table() {
  using P = GatewayNodeParams;
  static const ParamTable<P> t =
      ParamTable<P>()
          .string("interface", &P::bus, &SocketCanOptions::iface, "the SocketCAN interface of the jets' bus")
          .flag("fd", &P::bus, &SocketCanOptions::fd, "CAN FD when the interface's MTU allows it")
          .flag("auto_restart", &P::bus, &SocketCanOptions::auto_restart, "restart the controller after bus-off")
          .number("restart_delay", &P::bus, &SocketCanOptions::restart_delay, 0.0, 10.0, "s",
                  "between bus-off and the restart request")
          .string("model_params", &P::model_params, "the jets' model (config/models/; empty: the built-in one)")
          .string("gps_frame", &P::gps_frame, "frame of the GPS-compass fix")
          .string("world_frame", &P::world_frame, "frame of the heading and the velocity over ground (ENU)");
  return t;
}

void GatewayConfig::validate() const {
  table().validate(*this);
  requireRange("watchdog_timeout", watchdog_timeout, period(), 10.0);
  requireRange("manual_hold", manual_hold, period(), 10.0);
  requireRange("jet_timeout", jet_timeout, period(), 10.0);
  if (addresses.jet_base == addresses.gateway || addresses.jet_base + 1 == addresses.gateway ||
      addresses.bridge == addresses.gateway)
    throw ConfigError("parameter 'addresses': gateway, bridge and jet source addresses must differ");
}

const char* toString(Mode m) {
  switch (m) {
    case Mode::kAutonomy: return "autonomy";
    case Mode::kManual: return "manual";
    case Mode::kWatchdog: return "watchdog";
    case Mode::kJetSilent: return "jet_silent";
  }
  return "?";
}

const char* jetName(int jet) { return jet == 0 ? "port" : "starboard"; }

GatewayPolicy::GatewayPolicy(GatewayConfig config, const models::UsvParams& jets, Counters& counters)
    : cfg_(std::move(config)),
      counters_(counters),
      allocation_(jets),
      per_jet_(cfg_.command_frames == "jets"),
      autonomy_jets_(JetAllocation::neutral(kWatchdog)) {
  cfg_.validate();
}

bool GatewayPolicy::onAutonomy(double surge, double sway, double yaw, double now) {
  for (double v : {surge, sway, yaw})
    if (!std::isfinite(v) || std::abs(v) > 1.0) {
      counters_.increment("autonomy_out_of_range");
      return false;
    }
  if (now - manual_at_ <= cfg_.manual_hold) counters_.increment("autonomy_suppressed");
  autonomy_.surge = surge;
  autonomy_.sway = sway;
  autonomy_.yaw = yaw;
  autonomy_.source = kAutonomy;
  if (per_jet_) {
    autonomy_jets_ = allocation_.allocate(surge, sway, yaw, kAutonomy);
    if (allocation_.lastScale() < 1.0) counters_.increment("autonomy_saturated");  // direction kept, scaled down
  }
  autonomy_at_ = now;
  return true;
}

void GatewayPolicy::onManual(const jet::Command& c, double now) {
  manual_ = c;
  manual_at_ = now;
}

void GatewayPolicy::onStatus(const jet::Status& s, double now) { heard_at_[s.jet & 1] = now; }

bool GatewayPolicy::answering(int jet, double now) const {
  return first_tick_ || silentFor(jet, now) <= cfg_.jet_timeout;
}

double GatewayPolicy::silentFor(int jet, double now) const { return now - heard_at_[jet & 1]; }

Mode GatewayPolicy::mode(double now) const {
  if (now - manual_at_ <= cfg_.manual_hold) return Mode::kManual;
  if (now - autonomy_at_ > cfg_.watchdog_timeout) return Mode::kWatchdog;
  if (!answering(0, now) || !answering(1, now)) return Mode::kJetSilent;
  return Mode::kAutonomy;
}

std::vector<CanFrame> GatewayPolicy::tick(double now) {
  if (first_tick_)  // the silence clock of a jet not heard yet starts now
    for (double& h : heard_at_) h = std::max(h, now);
  const Mode m = mode(now);
  if (m != last_mode_ || first_tick_) {
    if (m == Mode::kManual) counters_.increment("manual_overrides");
    if (m == Mode::kWatchdog && !first_tick_) counters_.increment("watchdog_trips");
    last_mode_ = m;
  }
  first_tick_ = false;
  for (int i = 0; i < 2; ++i) {
    const bool a = answering(i, now);
    if (!a && answering_[i]) counters_.increment(std::string(jetName(i)) + "_jet_timeouts");
    answering_[i] = a;
  }
  if (m == Mode::kManual) return {};  // the bridge drives the jets; we stay off the bus
  const bool drive = m == Mode::kAutonomy;  // otherwise neutral: no thrust, nozzles centred
  const std::uint8_t counter = counter_;
  counter_ = static_cast<std::uint8_t>((counter_ + 1) & 0x0F);
  std::vector<CanFrame> out;
  if (per_jet_) {
    for (jet::Setpoint s : drive ? autonomy_jets_ : JetAllocation::neutral(kWatchdog)) {
      s.counter = counter;
      out.push_back(jet::encodeSetpoint(s, cfg_.addresses));
    }
  } else {
    jet::Command c;
    c.source = kWatchdog;
    if (drive) c = autonomy_;
    c.counter = counter;
    out.push_back(jet::encodeCommand(c, false, cfg_.addresses));
  }
  return out;
}

double CanGateway::monotonic() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

CanGateway::CanGateway(SocketCanOptions bus, GatewayConfig config, const models::UsvParams& jets, Counters& counters)
    : CanGateway(std::make_unique<SocketCan>(std::move(bus), counters), std::move(config), jets, counters,
                 &CanGateway::monotonic) {}

CanGateway::CanGateway(std::unique_ptr<BusInterface> bus, GatewayConfig config, const models::UsvParams& jets,
                       Counters& counters, Clock clock)
    : counters_(counters), bus_(std::move(bus)), now_(std::move(clock)), policy_(std::move(config), jets, counters) {
  bus_->open();  // failure is not fatal: poll() retries, diagnostics show the state
}

bool CanGateway::onAutonomy(double surge, double sway, double yaw) {
  std::lock_guard<std::mutex> lock(mutex_);
  return policy_.onAutonomy(surge, sway, yaw, now_());
}

Mode CanGateway::mode() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return policy_.mode(now_());
}

BusState CanGateway::state() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return bus_->state();
}

bool CanGateway::jetAnswering(int jet) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return policy_.answering(jet, now_());
}

double CanGateway::jetSilentFor(int jet) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return policy_.silentFor(jet, now_());
}

void CanGateway::spinOnce(double max_wait_s, const GatewayOutputs& out) {
  double t = now_();
  const double wait = std::max(0.0, std::min(max_wait_s, next_tick_ - t));
  bus_->wait(wait);  // only this thread touches the socket fd
  std::lock_guard<std::mutex> lock(mutex_);
  t = now_();
  bus_->poll(t);
  for (const CanFrame& f : bus_->receive(t)) handle(f, t, out);
  if (t >= next_tick_) {
    // Fixed rate without drift; after a stall, restart the schedule instead of bursting.
    const double period = policy_.config().period();
    next_tick_ = (next_tick_ > 0.0 && t - next_tick_ < period) ? next_tick_ + period : t + period;
    for (const CanFrame& f : policy_.tick(t)) {
      // A command that cannot leave now is stale by the next period: never queue it for a burst later.
      if (bus_->state() == BusState::kBusOff || bus_->state() == BusState::kDown) counters_.increment("commands_not_sent");
      else bus_->send(f);
    }
    if (reported_answering_ != policy_.answeringAtTick()) {
      reported_answering_ = policy_.answeringAtTick();
      if (out.answering) out.answering(*reported_answering_);
    }
    if (reported_state_ != bus_->state()) {
      reported_state_ = bus_->state();
      if (out.bus_state) out.bus_state(*reported_state_);
    }
  }
  bus_->flush();
}

void CanGateway::handle(const CanFrame& f, double t, const GatewayOutputs& out) {
  if (auto p = n2k::decodePositionRapid(f)) {
    if (p->lat_deg && p->lon_deg) {
      if (out.position) out.position(*p, n2k::decodeId(f.id).source);
    } else {
      counters_.increment("gps_not_available");
    }
    return;
  }
  if (auto h = n2k::decodeVesselHeading(f)) {
    if (h->heading_rad) {
      if (out.heading) out.heading(*h, n2k::decodeId(f.id).source);
    } else {
      counters_.increment("heading_not_available");
    }
    return;
  }
  if (auto c = n2k::decodeCogSogRapid(f)) {
    if (out.cog_sog) out.cog_sog(*c, n2k::decodeId(f.id).source);
    return;
  }
  if (f.extended) {
    const std::uint32_t pgn = n2k::decodeId(f.id).pgn;
    if ((pgn == n2k::kPgnPositionRapid || pgn == n2k::kPgnVesselHeading || pgn == n2k::kPgnCogSogRapid)) {
      counters_.increment("wrong_dlc");
      return;
    }
  }
  const jet::Decoded d = jet::decode(f, policy_.config().addresses);
  // The counter must follow the sender's previous one; a unit repeating one frame (counter stuck) never passes,
  // so it does not count as answering.
  auto inSequence = [&](std::uint8_t counter) {
    const bool ok = counters_check_.accept(f.id, counter);
    if (!ok) counters_.increment("counter_jumps");
    return ok;
  };
  using K = jet::Decoded::Kind;
  switch (d.kind) {
    case K::kCommand:
    case K::kSetpoint:  // another gateway on the bus, or ours seen from another socket: not ours to obey
      counters_.increment("foreign_commands");
      return;
    case K::kManual:
      if (!inSequence(d.command.counter)) return;
      policy_.onManual(d.command, t);
      if (out.manual) out.manual(d.command);
      return;
    case K::kStatus:
      if (!inSequence(d.status.counter)) return;
      policy_.onStatus(d.status, t);
      if (out.status) out.status(d.status);
      return;
    case K::kNone: break;
  }
  counters_.increment(jet::toString(d.error));
}

}  // namespace can
}  // namespace offshore_gnc
