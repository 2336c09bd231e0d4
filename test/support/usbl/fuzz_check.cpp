#include "usbl/fuzz_check.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "offshore_gnc/usbl/seatrac.h"

namespace offshore_gnc {
namespace usbl {

namespace {
[[noreturn]] void violated(const char* what) {
  std::fprintf(stderr, "usbl codec invariant violated: %s\n", what);
  std::abort();
}
}  // namespace

std::size_t fuzzCodecOnce(const std::uint8_t* data, std::size_t n) {
  StreamDecoder whole(120), bytewise(120);
  std::vector<StreamDecoder::Event> a, b;
  whole.feed(data, n, a);
  for (std::size_t i = 0; i < n; ++i) bytewise.feed(data + i, 1, b);
  if (a.size() != b.size()) violated("chunking changed the number of events");
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].reason != b[i].reason || a[i].line != b[i].line) violated("chunking changed an event");
    if (!a[i].message) continue;
    const Message& m = *a[i].message;
    if (auto f = std::get_if<FixMessage>(&m.body))
      if (f->fix.usbl_rssi.size() > kMaxUsblChannels) violated("more than 4 channels accepted");
    // Re-encoding a decoded frame gives the same bytes (hex case aside), so nothing was silently dropped.
    std::string again = encodeFrame(m);
    again.resize(again.size() - 2);  // CR LF
    std::string line = a[i].line;
    for (auto& c : line) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (again != line) violated("decode/encode round trip differs");
  }
  // The binary entry point on the raw bytes (as if they were an already de-hexed payload).
  std::size_t decoded = 0;
  for (const auto& e : a) decoded += e.message ? 1 : 0;
  std::string reason;
  if (n > 0) {
    auto m = decodePayload((data[0] & 1) != 0, data + 1, n - 1, &reason);
    if (m && encodePayload(*m) != std::vector<std::uint8_t>(data + 1, data + n)) violated("binary round trip differs");
    if (!m && reason.empty()) violated("rejection without a reason");
  }
  return decoded;
}

}  // namespace usbl
}  // namespace offshore_gnc
