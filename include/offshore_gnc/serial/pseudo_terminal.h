#pragma once
// A pseudo-terminal standing in for a device's serial line (simulators and emulators of serial devices): the
// slave side is raw (binary-clean, no echo) and reachable under a fixed path (a symlink), the master side is
// what the emulator reads and writes. ROS-free; throws std::runtime_error with the reason when it cannot be made.
#include <cstddef>
#include <cstdint>
#include <string>

namespace offshore_gnc {
namespace serial {

class PseudoTerminal {
 public:
  explicit PseudoTerminal(std::string link);  // creates the pty and the symlink `link` -> its slave
  ~PseudoTerminal();                          // closes both sides and removes the symlink
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  // Waits up to timeout_ms for bytes from the device's user; the count read (0 on timeout).
  std::size_t read(std::uint8_t* buf, std::size_t cap, int timeout_ms);
  // Writes all bytes to the device's user; false when not all were written.
  bool write(const std::string& bytes);
  const std::string& link() const { return link_; }
  const std::string& slaveName() const { return slave_name_; }

 private:
  std::string link_, slave_name_;
  int master_ = -1, slave_ = -1;
};

}  // namespace serial
}  // namespace offshore_gnc
