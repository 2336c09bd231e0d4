#include "offshore_gnc/can/gateway.h"

#include <chrono>
#include <cmath>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace can {

void GatewayConfig::validate() const {
  requireRange("period", period, 0.005, 1.0);
  requireRange("watchdog_timeout", watchdog_timeout, period, 10.0);
  requireRange("manual_hold", manual_hold, period, 10.0);
  if (addresses.jet_base == addresses.gateway || addresses.jet_base + 1 == addresses.gateway ||
      addresses.bridge == addresses.gateway)
    throw ConfigError("parameter 'addresses': gateway, bridge and jet source addresses must differ");
}

const char* toString(Mode m) {
  switch (m) {
    case Mode::kAutonomy: return "autonomy";
    case Mode::kManual: return "manual";
    case Mode::kWatchdog: return "watchdog";
  }
  return "?";
}

GatewayPolicy::GatewayPolicy(GatewayConfig config, Counters& counters) : cfg_(config), counters_(counters) {
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
  autonomy_at_ = now;
  return true;
}

void GatewayPolicy::onManual(const jet::Command& c, double now) {
  manual_ = c;
  manual_at_ = now;
}

Mode GatewayPolicy::mode(double now) const {
  if (now - manual_at_ <= cfg_.manual_hold) return Mode::kManual;
  if (now - autonomy_at_ <= cfg_.watchdog_timeout) return Mode::kAutonomy;
  return Mode::kWatchdog;
}

std::optional<CanFrame> GatewayPolicy::tick(double now) {
  const Mode m = mode(now);
  if (m != last_mode_ || first_tick_) {
    if (m == Mode::kManual) counters_.increment("manual_overrides");
    if (m == Mode::kWatchdog && !first_tick_) counters_.increment("watchdog_trips");
    last_mode_ = m;
    first_tick_ = false;
  }
  if (m == Mode::kManual) return std::nullopt;  // the bridge drives the jets; we stay off the bus
  jet::Command c;  // neutral: no thrust, nozzle centred
  c.source = kWatchdog;
  if (m == Mode::kAutonomy) c = autonomy_;
  c.counter = counter_;
  counter_ = static_cast<std::uint8_t>((counter_ + 1) & 0x0F);
  return jet::encodeCommand(c, false, cfg_.addresses);
}

double CanGateway::monotonic() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

CanGateway::CanGateway(SocketCanOptions bus, GatewayConfig config, Counters& counters)
    : CanGateway(std::make_unique<SocketCan>(std::move(bus), counters), config, counters, &CanGateway::monotonic) {}

CanGateway::CanGateway(std::unique_ptr<BusInterface> bus, GatewayConfig config, Counters& counters, Clock clock)
    : counters_(counters), bus_(std::move(bus)), now_(std::move(clock)), policy_(config, counters) {
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
    next_tick_ = (next_tick_ > 0.0 && t - next_tick_ < policy_.config().period) ? next_tick_ + policy_.config().period
                                                                                 : t + policy_.config().period;
    if (auto f = policy_.tick(t)) {
      // A command that cannot leave now is stale by the next period: never queue it for a burst later.
      if (bus_->state() == BusState::kBusOff || bus_->state() == BusState::kDown) counters_.increment("commands_not_sent");
      else bus_->send(*f);
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
  jet::Command cmd;
  bool manual = false;
  jet::Error e = jet::decodeCommand(f, cmd, &manual);
  if (e == jet::Error::kNone) {
    if (!manual) {  // another gateway on the bus, or our own echo: not ours to obey
      counters_.increment("foreign_commands");
      return;
    }
    if (!counters_check_.accept(f.id, cmd.counter)) {
      counters_.increment("counter_jumps");
      return;
    }
    policy_.onManual(cmd, t);
    if (out.manual) out.manual(cmd);
    return;
  }
  if (e == jet::Error::kNotOurs) {
    jet::Status st;
    e = jet::decodeStatus(f, st, policy_.config().addresses);
    if (e == jet::Error::kNone) {
      if (!counters_check_.accept(f.id, st.counter)) {
        counters_.increment("counter_jumps");
        return;
      }
      if (out.status) out.status(st);
      return;
    }
  }
  counters_.increment(jet::toString(e));
}

}  // namespace can
}  // namespace offshore_gnc
