// radio_params [FILE]: the simulated radio's parameters (sim::RadioParams, FILE's keys over the defaults, checked
// by its table) as one line of JSON, for the main job's radio (python/offshore_gnc/radio.py). Exits 2 with the
// error on a bad file.
#include <cstdio>
#include <string>

#include "offshore_gnc/sim/radio.h"

using namespace offshore_gnc;

int main(int argc, char** argv) {
  if (argc > 2) {
    std::fprintf(stderr, "usage: radio_params [FILE.yaml]\n");
    return 2;
  }
  try {
    const sim::RadioParams p = sim::loadRadioParams(argc == 2 ? argv[1] : "");
    std::string out;
    for (const auto& s : sim::RadioParams::table().specs())
      out += (out.empty() ? "{\"" : ", \"") + s.name + "\": " + ParamTable<sim::RadioParams>::text(s, p);
    std::printf("%s}\n", out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
