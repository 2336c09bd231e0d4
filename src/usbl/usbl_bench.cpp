// Decoder throughput on a simulator-shaped stream (pings, acknowledgements, PING_RESP, timeouts). Writes the
// stream to argv[1] so that bench/usbl.sh can time a Python decoder on the same bytes; prints one JSON line.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "offshore_gnc/usbl/beacon_sim.h"
#include "offshore_gnc/usbl/seatrac.h"

int main(int argc, char** argv) {
  using namespace offshore_gnc::usbl;
  BeaconSimConfig cfg;
  cfg.dropout_probability = 0.1;
  BeaconSimulator sim(cfg);
  Pose usv;
  std::string stream;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d auv(40.0 + 0.01 * i, 30.0, 15.0);
    sim.setCurrentRange(transceiverRange(cfg.mount, usv, auv));
    const Message ping{true, PingSend{2, MSG_REQU}};
    stream += encodeFrame(ping);
    stream += sim.handle(ping, i * 2.0);
    stream += sim.poll(i * 2.0 + 1.5, usv, auv);
  }
  if (argc > 1) std::ofstream(argv[1], std::ios::binary) << stream;
  const int reps = 20;
  std::size_t frames = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < reps; ++r) {
    StreamDecoder dec;
    std::vector<StreamDecoder::Event> ev;
    ev.reserve(70000);
    dec.feed(stream, ev);
    for (const auto& e : ev) frames += e.message ? 1 : 0;
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("{\"cpp_frames_per_s\": %.0f, \"cpp_mb_per_s\": %.1f, \"frames\": %zu, \"bytes\": %zu}\n", frames / s,
              stream.size() * reps / s / 1e6, frames / reps, stream.size());
  return 0;
}
