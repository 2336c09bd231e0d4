// can_decode: candump log lines (stdin or files) -> one JSON object per decoded message, SI units.
//   can_decode [--all] [file...]    --all also prints {"error":...} lines for frames it cannot decode
// Exit status 0; a summary of what was skipped goes to stderr, since boat logs always hold foreign traffic.
#include <fstream>
#include <iostream>
#include <map>
#include <string>

#include "offshore_gnc/can/decode.h"

namespace {

void decodeStream(std::istream& in, bool all, std::map<std::string, long>& skipped, long& decoded) {
  std::string line, error;
  long n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    auto parsed = offshore_gnc::can::parseCandump(line, &error);
    std::optional<std::string> json;
    if (parsed) json = offshore_gnc::can::decodeToJson(*parsed, {}, &error);
    if (json) {
      std::cout << *json << '\n';
      ++decoded;
      continue;
    }
    if (!parsed) error = "malformed: " + error;
    ++skipped[error];
    if (all) std::cout << "{\"line\":" << n << ",\"error\":\"" << error << "\"}\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool all = false;
  std::map<std::string, long> skipped;
  long decoded = 0;
  int files = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--all") {
      all = true;
    } else if (a == "-h" || a == "--help") {
      std::cout << "usage: can_decode [--all] [candump.log ...]  (stdin when no file)\n";
      return 0;
    } else {
      std::ifstream f(a);
      if (!f) {
        std::cerr << "can_decode: cannot open " << a << '\n';
        return 2;
      }
      decodeStream(f, all, skipped, decoded);
      ++files;
    }
  }
  if (files == 0) decodeStream(std::cin, all, skipped, decoded);
  std::cerr << "can_decode: " << decoded << " decoded";
  for (const auto& kv : skipped) std::cerr << ", " << kv.second << " " << kv.first;
  std::cerr << '\n';
  return 0;
}
