#pragma once
// Best-effort topics in UDP datagrams: one socket per relay, and per link a datagram path with the peer's
// address (its TCP address, the port from its hello), our frame counter and the replay window of what arrives.
// Same frames and session keys as the link's TCP side; datagrams may be lost or reordered (loss is counted,
// nothing is resent).
#include <netinet/in.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "offshore_gnc/relay/policy.h"
#include "offshore_gnc/relay/wire.h"

namespace offshore_gnc {
namespace relay {

class UdpSocket {
 public:
  ~UdpSocket() { close(); }
  // Bound to host:port when the relay listens there (peers know it), else to any free port. "" or the error.
  std::string open(const std::string& host, int port, bool listening);
  void close();
  bool isOpen() const { return fd_ >= 0; }
  int fd() const { return fd_; }
  int port() const { return port_; }
  bool sendTo(const sockaddr_in& to, const std::vector<std::uint8_t>& bytes);
  // One datagram into `buf` (false: none waiting).
  bool receive(std::vector<std::uint8_t>& buf, std::size_t& n, sockaddr_in& from);

 private:
  int fd_ = -1, port_ = 0;
};

struct DatagramPath {
  bool enabled = false;
  sockaddr_in to{};
  std::uint64_t tx_counter = 0, rx_max = 0;
  ReplayWindow replay;

  // Sets the peer's address from the TCP connection `fd` and the UDP port its hello gave; false when unknown.
  bool connect(int fd, std::uint16_t udp_port);
  bool from(const sockaddr_in& a) const {
    return enabled && to.sin_port == a.sin_port && to.sin_addr.s_addr == a.sin_addr.s_addr;
  }
  // Encodes one frame with the next counter under `key` and sends it (false: the socket took none of it).
  bool send(UdpSocket& s, FrameHeader h, const std::uint8_t* p, std::size_t n, const Authenticator& key);
  // A received frame's counter: false when replayed; `lost` counts the datagrams skipped over (a reordered one
  // that arrives later is still within the window).
  bool accept(std::uint64_t counter, std::uint64_t& lost);
};

}  // namespace relay
}  // namespace offshore_gnc
