// libFuzzer target: arbitrary text through the candump parser and every decoder behind can_decode.
// Built by `scripts/fuzz candump` (clang, -fsanitize=fuzzer,address,undefined); not part of the catkin build.
#include <cmath>
#include <cstdint>
#include <string>

#include "offshore_gnc/can/decode.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string line(reinterpret_cast<const char*>(data), size);
  std::string error;
  auto parsed = offshore_gnc::can::parseCandump(line, &error);
  if (!parsed) {
    if (error.empty()) __builtin_trap();  // every rejection must say why
    return 0;
  }
  if (parsed->frame.len > (parsed->frame.fd ? 64 : 8)) __builtin_trap();
  auto json = offshore_gnc::can::decodeToJson(*parsed, {}, &error);
  if (json) {  // numbers are never nan/inf: look at every value after the (quoted, free-text) iface
    const std::string tail = json->substr(json->find("\"pgn\":"));
    for (const char* bad : {":nan", ":-nan", ":inf", ":-inf"})
      if (tail.find(bad) != std::string::npos || json->rfind("{\"t\"" + std::string(bad), 0) == 0) __builtin_trap();
  }
  // What we print must parse back to the same frame.
  auto again = offshore_gnc::can::parseCandump("can0 " + offshore_gnc::can::formatCansend(parsed->frame));
  if (!again || again->frame.id != parsed->frame.id || again->frame.len != parsed->frame.len) __builtin_trap();
  return 0;
}
