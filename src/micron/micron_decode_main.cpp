// micron_decode: decodes a Tritech SeaNet serial capture (raw bytes; a file or stdin) into JSON lines, one object
// per packet (type name, every field, mtHeadData with its bins) and one per rejected packet with the reason; a
// final summary object with the counters (garbage bytes included) goes to stderr.
//
//   micron_decode [--forward-offset-deg D] [--inverted] [--sound-speed C] [CAPTURE | -]
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/micron/json.h"

int main(int argc, char** argv) {
  using namespace offshore_gnc;
  using namespace offshore_gnc::micron;
  HeadGeometry geometry;
  double sound_speed = 1500.0;
  const char* path = nullptr;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--forward-offset-deg" && i + 1 < argc) {
      geometry.forward_offset = deg2rad(std::atof(argv[++i]));
    } else if (a == "--inverted") {
      geometry.inverted = true;
    } else if (a == "--sound-speed" && i + 1 < argc) {
      sound_speed = std::atof(argv[++i]);
    } else if (a == "-h" || a == "--help" || path) {
      std::fprintf(stderr, "usage: micron_decode [--forward-offset-deg D] [--inverted] [--sound-speed C] [CAPTURE | -]\n");
      return 2;
    } else {
      path = argv[i];
    }
  }
  std::ifstream file;
  std::istream* in = &std::cin;
  if (path && std::strcmp(path, "-") != 0) {
    file.open(path, std::ios::binary);
    if (!file) {
      std::fprintf(stderr, "micron_decode: cannot open %s: %s\n", path, std::strerror(errno));
      return 1;
    }
    in = &file;
  }
  StreamDecoder dec;
  std::vector<StreamDecoder::Event> events;
  std::vector<char> buf(4096);
  while (*in) {
    in->read(buf.data(), static_cast<std::streamsize>(buf.size()));
    events.clear();
    dec.feed(reinterpret_cast<const std::uint8_t*>(buf.data()), static_cast<std::size_t>(in->gcount()), events);
    for (const auto& e : events)
      std::cout << (e.message ? toJson(*e.message, geometry, sound_speed) : rejectionJson(e.reason, e.raw)) << '\n';
  }
  auto counts = dec.counters().snapshot();
  if (dec.pending()) counts["truncated_bytes"] = dec.pending();  // a packet cut off at the end of the capture
  std::cerr << "{\"summary\":{";
  bool first = true;
  for (const auto& kv : counts) {
    std::cerr << (first ? "" : ",") << "\"" << kv.first << "\":" << kv.second;
    first = false;
  }
  std::cerr << "}}\n";
  return 0;
}
