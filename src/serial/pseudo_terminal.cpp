// Pseudo-terminal for serial-device emulators (include/offshore_gnc/serial/pseudo_terminal.h).
#include "offshore_gnc/serial/pseudo_terminal.h"

#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace offshore_gnc {
namespace serial {

PseudoTerminal::PseudoTerminal(std::string link) : link_(std::move(link)) {
  if (::openpty(&master_, &slave_, nullptr, nullptr, nullptr) != 0)
    throw std::runtime_error(std::string("openpty failed: ") + std::strerror(errno));
  termios t{};
  tcgetattr(slave_, &t);
  cfmakeraw(&t);  // binary protocols: nothing may be translated or echoed back
  tcsetattr(slave_, TCSANOW, &t);
  char name[256] = {};
  ttyname_r(slave_, name, sizeof name);
  slave_name_ = name;
  ::unlink(link_.c_str());
  if (::symlink(name, link_.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::close(master_);
    ::close(slave_);
    throw std::runtime_error("cannot create " + link_ + " -> " + slave_name_ + ": " + why);
  }
}

PseudoTerminal::~PseudoTerminal() {
  ::close(master_);
  ::close(slave_);
  ::unlink(link_.c_str());
}

std::size_t PseudoTerminal::read(std::uint8_t* buf, std::size_t cap, int timeout_ms) {
  pollfd p{master_, POLLIN, 0};
  if (::poll(&p, 1, timeout_ms) <= 0 || !(p.revents & POLLIN)) return 0;
  const ssize_t n = ::read(master_, buf, cap);
  return n > 0 ? static_cast<std::size_t>(n) : 0;
}

bool PseudoTerminal::write(const std::string& bytes) {
  return bytes.empty() || ::write(master_, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
}

}  // namespace serial
}  // namespace offshore_gnc
