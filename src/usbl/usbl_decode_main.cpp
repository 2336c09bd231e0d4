// usbl_decode: decodes a SeaTrac serial capture (raw bytes or text lines; a file or stdin) into JSON lines, one
// object per message (CID name, every field in SI units) and one per rejected frame with the reason; a final
// summary object with the counters goes to stderr.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <vector>

#include "offshore_gnc/usbl/json.h"
#include "offshore_gnc/usbl/seatrac.h"

int main(int argc, char** argv) {
  using namespace offshore_gnc::usbl;
  if (argc > 2 || (argc == 2 && (!std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "--help")))) {
    std::fprintf(stderr, "usage: usbl_decode [CAPTURE]   (reads stdin without CAPTURE or with '-')\n");
    return 2;
  }
  std::ifstream file;
  std::istream* in = &std::cin;
  if (argc == 2 && std::strcmp(argv[1], "-") != 0) {
    file.open(argv[1], std::ios::binary);
    if (!file) {
      std::fprintf(stderr, "usbl_decode: cannot open %s: %s\n", argv[1], std::strerror(errno));
      return 1;
    }
    in = &file;
  }
  StreamDecoder dec;
  std::vector<StreamDecoder::Event> events;
  std::vector<char> buf(4096);
  auto flush = [&events]() {
    for (const auto& e : events)
      std::cout << (e.message ? toJson(*e.message) : rejectionJson(e.reason, e.line)) << '\n';
    events.clear();
  };
  while (*in) {
    in->read(buf.data(), static_cast<std::streamsize>(buf.size()));
    dec.feed(reinterpret_cast<const std::uint8_t*>(buf.data()), static_cast<std::size_t>(in->gcount()), events);
    flush();
  }
  dec.feed("\n", events);  // a last line without CR LF still counts
  flush();
  std::cerr << "{\"summary\":{";
  bool first = true;
  for (const auto& kv : dec.counters().snapshot()) {
    std::cerr << (first ? "" : ",") << "\"" << kv.first << "\":" << kv.second;
    first = false;
  }
  std::cerr << "}}\n";
  return 0;
}
