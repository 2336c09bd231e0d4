#include "offshore_gnc/can/frame.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace offshore_gnc {
namespace can {
namespace {

constexpr std::uint32_t kErrFlag = 0x20000000U;  // CAN_ERR_FLAG as candump prints it
constexpr std::size_t kFdLengths[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool fail(std::string* error, const char* what) {
  if (error) *error = what;
  return false;
}

bool parseFrame(const std::string& s, CanFrame& f, std::string* error) {
  const auto hash = s.find('#');
  if (hash == std::string::npos) return fail(error, "no '#' between id and data");
  const std::string id = s.substr(0, hash);
  if (id.size() != 3 && id.size() != 8) return fail(error, "id must have 3 (standard) or 8 (extended) hex digits");
  std::uint32_t v = 0;
  for (char c : id) {
    const int h = hexValue(c);
    if (h < 0) return fail(error, "id is not hexadecimal");
    v = (v << 4) | static_cast<std::uint32_t>(h);
  }
  f.extended = id.size() == 8;
  if (f.extended && (v & kErrFlag)) {
    f.error = true;
    v &= ~kErrFlag;
  }
  if (v > (f.extended ? 0x1FFFFFFFU : 0x7FFU)) return fail(error, "id out of range");
  f.id = v;
  std::size_t pos = hash + 1;
  if (pos < s.size() && s[pos] == '#') {  // CAN FD: one flags nibble, then data
    f.fd = true;
    if (pos + 1 >= s.size() || hexValue(s[pos + 1]) < 0) return fail(error, "FD frame without flags nibble");
    pos += 2;
  } else if (pos < s.size() && (s[pos] == 'R' || s[pos] == 'r')) {
    f.rtr = true;
    f.len = 0;
    return true;
  }
  std::size_t n = 0;
  for (; pos < s.size(); pos += 2) {
    if (s[pos] == '.') {  // cansend allows '.' separators
      --pos;
      continue;
    }
    if (pos + 1 >= s.size()) return fail(error, "odd number of data hex digits");
    const int hi = hexValue(s[pos]), lo = hexValue(s[pos + 1]);
    if (hi < 0 || lo < 0) return fail(error, "data is not hexadecimal");
    if (n >= (f.fd ? 64U : 8U)) return fail(error, "too many data bytes");
    f.data[n++] = static_cast<std::uint8_t>((hi << 4) | lo);
  }
  if (f.fd) {
    bool valid = false;
    for (auto l : kFdLengths) valid = valid || l == n;
    if (!valid) return fail(error, "invalid CAN FD length");
  }
  f.len = static_cast<std::uint8_t>(n);
  return true;
}

}  // namespace

std::optional<CandumpLine> parseCandump(const std::string& line, std::string* error) {
  CandumpLine out;
  std::size_t pos = 0;
  auto skipSpace = [&] {
    while (pos < line.size() && std::isspace(static_cast<unsigned char>(line[pos]))) ++pos;
  };
  auto word = [&] {
    skipSpace();
    const std::size_t start = pos;
    while (pos < line.size() && !std::isspace(static_cast<unsigned char>(line[pos]))) ++pos;
    return line.substr(start, pos - start);
  };
  std::string w = word();
  if (!w.empty() && w.front() == '(') {
    if (w.back() != ')' || w.size() < 3) {
      if (error) *error = "unterminated timestamp";
      return std::nullopt;
    }
    char* end = nullptr;
    const std::string num = w.substr(1, w.size() - 2);
    out.stamp = std::strtod(num.c_str(), &end);
    if (num.empty() || end != num.c_str() + num.size() || !std::isfinite(out.stamp)) {
      if (error) *error = "timestamp is not a finite number";
      return std::nullopt;
    }
    w = word();
  }
  out.iface = w;
  const std::string frame = word();
  if (out.iface.empty() || frame.empty()) {
    if (error) *error = "expected '(timestamp) iface id#data'";
    return std::nullopt;
  }
  if (!parseFrame(frame, out.frame, error)) return std::nullopt;
  return out;
}

std::string formatCansend(const CanFrame& f) {
  char buf[16];
  std::string s;
  std::snprintf(buf, sizeof buf, f.extended ? "%08X" : "%03X", f.id | (f.error ? kErrFlag : 0U));
  s += buf;
  s += f.fd ? "##0" : "#";
  if (f.rtr) return s + "R";
  for (std::size_t i = 0; i < f.len && i < f.data.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%02X", f.data[i]);
    s += buf;
  }
  return s;
}

}  // namespace can
}  // namespace offshore_gnc
