// UDP links (include/offshore_gnc/relay/udp_link.h).
#include "offshore_gnc/relay/udp_link.h"

#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "offshore_gnc/relay/tcp_link.h"

namespace offshore_gnc {
namespace relay {

std::string UdpSocket::open(const std::string& host, int port, bool listening) {
  fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(listening ? port : 0);
  if (!listening || inet_pton(AF_INET, host.c_str(), &a.sin_addr) != 1) a.sin_addr.s_addr = INADDR_ANY;
  if (fd_ < 0 || bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) {
    const std::string err = std::strerror(errno);
    close();
    return err;
  }
  socklen_t len = sizeof(a);
  getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
  port_ = ntohs(a.sin_port);
  int buf = 4 << 20;  // room for bursts of large best-effort messages
  setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &buf, sizeof(buf));
  setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &buf, sizeof(buf));
  setNonBlocking(fd_);
  return "";
}

void UdpSocket::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool UdpSocket::sendTo(const sockaddr_in& to, const std::vector<std::uint8_t>& bytes) {
  const ssize_t r = sendto(fd_, bytes.data(), bytes.size(), MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&to),
                           sizeof(to));
  return r == static_cast<ssize_t>(bytes.size());
}

bool UdpSocket::receive(std::vector<std::uint8_t>& buf, std::size_t& n, sockaddr_in& from) {
  socklen_t len = sizeof(from);
  const ssize_t r = recvfrom(fd_, buf.data(), buf.size(), MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &len);
  if (r < 0) return false;
  n = std::size_t(r);
  return true;
}

bool DatagramPath::connect(int fd, std::uint16_t udp_port) {
  socklen_t alen = sizeof(to);
  if (!udp_port || getpeername(fd, reinterpret_cast<sockaddr*>(&to), &alen) != 0 || to.sin_family != AF_INET)
    return false;
  to.sin_port = htons(udp_port);
  enabled = true;
  return true;
}

bool DatagramPath::send(UdpSocket& s, FrameHeader h, const std::uint8_t* p, std::size_t n, const Authenticator& key) {
  static thread_local std::vector<std::uint8_t> buf;
  buf.clear();
  h.counter = ++tx_counter;
  encodeFrame(h, p, n, key, buf);
  return s.sendTo(to, buf);
}

bool DatagramPath::accept(std::uint64_t counter, std::uint64_t& lost) {
  lost = 0;
  if (!replay.accept(counter)) return false;
  if (counter > rx_max + 1 && rx_max > 0) lost = counter - rx_max - 1;
  rx_max = std::max(rx_max, counter);
  return true;
}

}  // namespace relay
}  // namespace offshore_gnc
