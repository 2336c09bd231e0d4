#pragma once
// The radio link between the two vehicles' masters in simulation: what the relays' messages meet on the way. One
// set of parameters (RadioParams, config/relay/radio.yaml) for both runners: the main job's
// python/offshore_gnc/radio.py carries the relays' TCP stream and UDP datagrams through it (`radio_params` prints
// the parameters for it), the ROS-free mission's closed_loop::RadioLink its messages (RadioChannel below, the same
// model). In the thesis the Girona500 reached the other computers by WiFi through a gateway buoy (4.3.1) and the
// aColor by a tether; 5.1.1 names WiFi as the co-operative system's flexible choice, without figures. The defaults
// are a 2.4 GHz WiFi link over water at a few hundred metres, estimates: docs/relay.md, "The simulated radio".
#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <string>

#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace sim {

struct RadioParams {
  double latency = 0.01;      // one way, the channel's own [s]
  double jitter = 0.005;      // an exponential extra delay, mean [s]
  double loss = 0.02;         // packets lost, mean fraction [-]
  double loss_burst = 3.0;    // packets in a run of losses, mean (Gilbert-Elliott: fades come in bursts)
  double bandwidth = 2e6;     // [bit/s] each direction
  double retransmit = 0.2;    // a lost TCP segment arrives this much later (the sender's retransmission timeout) [s]
  double queue = 0.5;         // a datagram that would wait longer than this for the channel is dropped [s]
  static const ParamTable<RadioParams>& table();
};
// From a YAML file of the table's keys ("": the defaults); ConfigError naming the file and key.
RadioParams loadRadioParams(const std::string& file);

// Header bytes a packet carries on the channel besides its payload: IP + TCP (with timestamps), IP + UDP.
constexpr std::size_t kTcpOverhead = 52, kUdpOverhead = 28;

// One direction of the radio, in simulated seconds (python/offshore_gnc/radio.py's Channel is the same model in
// wall seconds): packets queue for the channel at `bandwidth`, arrive latency + an exponential jitter after their
// last bit but never before the packet ahead of them (the link delivers in order), and are lost in runs
// (Gilbert-Elliott: the bad state is entered with the probability that makes the mean loss `loss` and left after
// `loss_burst` packets on average). A lost reliable packet (TCP) comes `retransmit` later and holds back the
// reliable ones after it; a lost datagram is gone, and so is one that would wait longer than `queue` for the
// channel.
class RadioChannel {
 public:
  RadioChannel(const RadioParams& p, std::uint64_t seed);
  // When a packet of `payload` bytes handed over at `now` arrives, or nothing when it is lost (datagrams only).
  std::optional<double> schedule(double now, std::size_t payload, bool reliable);

  struct Stats {
    std::size_t packets = 0, lost = 0, retransmitted = 0, dropped_queue = 0;
  };
  const Stats& stats() const { return stats_; }
  const RadioParams& params() const { return p_; }

 private:
  bool lost();

  RadioParams p_;
  double p_bad_, p_good_;
  bool bad_ = false;
  double busy_until_ = 0.0, last_ = 0.0, last_reliable_ = 0.0;
  std::mt19937_64 rng_;
  Stats stats_;
};

}  // namespace sim
}  // namespace offshore_gnc
