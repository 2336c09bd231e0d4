#include "offshore_gnc/sim/radio.h"

#include <algorithm>

#include "offshore_gnc/common/param_yaml.h"

namespace offshore_gnc {
namespace sim {

const ParamTable<RadioParams>& RadioParams::table() {
  using P = RadioParams;
  static const ParamTable<P> t = ParamTable<P>()
      .number("latency", &P::latency, 0, 10, "s", "one-way delay of the radio channel")
      .number("jitter", &P::jitter, 0, 10, "s", "extra delay per packet, exponential, mean")
      .number("loss", &P::loss, 0, 0.9, "", "packets lost, mean fraction")
      .number("loss_burst", &P::loss_burst, 1, 1000, "", "packets in a run of losses, mean (Gilbert-Elliott)")
      .number("bandwidth", &P::bandwidth, 1e3, 1e10, "bit/s", "the channel's rate, each direction")
      .number("retransmit", &P::retransmit, 0, 60, "s", "a lost TCP segment arrives this much later (retransmission)")
      .number("queue", &P::queue, 0, 60, "s", "a datagram waiting longer for the channel is dropped");
  return t;
}

RadioParams loadRadioParams(const std::string& file) {
  RadioParams p;
  if (file.empty()) return p;
  readParamsYaml(loadYamlFile(file), RadioParams::table(), p, file);
  return p;
}

RadioChannel::RadioChannel(const RadioParams& p, std::uint64_t seed)
    : p_(p),
      p_bad_(p.loss > 0.0 ? p.loss / (p.loss_burst * (1.0 - p.loss)) : 0.0),
      p_good_(1.0 / p.loss_burst),
      rng_(seed) {
  RadioParams::table().validate(p);
}

bool RadioChannel::lost() {
  const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  bad_ = bad_ ? u >= p_good_ : u < p_bad_;
  return bad_;
}

std::optional<double> RadioChannel::schedule(double now, std::size_t payload, bool reliable) {
  ++stats_.packets;
  const double bits = 8.0 * static_cast<double>(payload + (reliable ? kTcpOverhead : kUdpOverhead));
  const double start = std::max(now, busy_until_);
  if (!reliable && start - now > p_.queue) {
    ++stats_.dropped_queue;  // the channel is full: what comes now is lost
    return std::nullopt;
  }
  busy_until_ = start + bits / p_.bandwidth;
  const double jitter = p_.jitter > 0.0 ? std::exponential_distribution<double>(1.0 / p_.jitter)(rng_) : 0.0;
  // The link delivers in order (WiFi's link layer: its retries hold back what follows), so the jitter delays
  // but never reorders; only TCP's own retransmission, above it, comes later still.
  double due = std::max(busy_until_ + p_.latency + jitter, last_);
  last_ = due;
  if (lost()) {
    if (!reliable) {
      ++stats_.lost;
      return std::nullopt;
    }
    ++stats_.retransmitted;
    due += p_.retransmit;
  }
  if (reliable) {  // in order: a segment never overtakes the one before it
    due = std::max(due, last_reliable_);
    last_reliable_ = due;
  }
  return due;
}

}  // namespace sim
}  // namespace offshore_gnc
