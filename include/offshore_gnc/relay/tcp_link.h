#pragma once
// One TCP connection carrying relay frames (POSIX, non-blocking): what arrives goes through a bounded frame
// decoder, what leaves waits in an output buffer until the socket takes it, and every frame carries the next
// counter under the connection's send key (the handshake sets the keys). No protocol here: the engine says what
// the frames mean.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "offshore_gnc/relay/policy.h"
#include "offshore_gnc/relay/wire.h"

namespace offshore_gnc {
namespace relay {

// Output beyond this is congestion: reliable frames wait in their queue, best-effort ones and replies are dropped.
constexpr std::size_t kOutBufferLimit = 8u << 20;

// Non-blocking, no Nagle delay (small messages), large socket buffers (point clouds: fewer poll rounds a frame).
void setNonBlocking(int fd);
// A listening socket on host:port (port 0: any free one, then `bound` says which); throws naming the address.
int listenTcp(const std::string& host, int port, int& bound);

class TcpLink {
 public:
  // Takes `fd` (a connected socket, or one connect() is still in progress on). Until the handshake, frames are
  // at most `max_payload` bytes and authenticated with `psk`.
  TcpLink(int fd, bool connecting, double now, std::size_t max_payload, const Authenticator& psk);
  ~TcpLink() { close(); }
  TcpLink(const TcpLink&) = delete;
  TcpLink& operator=(const TcpLink&) = delete;
  // Dials host:port without blocking; -1 when the socket cannot even be made or the connect fails at once.
  static int dial(const std::string& host, int port, bool& in_progress);

  int fd() const { return fd_; }
  bool closed() const { return fd_ < 0; }
  void close();
  bool connecting() const { return connecting_; }
  // After poll reported the socket writable: "" when the connect succeeded, else the error.
  std::string finishConnect();
  double opened() const { return opened_; }
  double lastReceived() const { return last_rx_; }

  // The handshake's session keys; frames up to `max_payload` from now on.
  void setKeys(const Authenticator& tx, const Authenticator& rx, std::size_t max_payload);
  void setSendKey(const Authenticator& tx) { tx_ = tx; }
  const Authenticator& sendKey() const { return tx_; }
  const Authenticator& receiveKey() const { return rx_; }
  // Each frame counter once (replayed frames are refused).
  bool fresh(std::uint64_t counter) { return replay_.accept(counter); }

  // Appends one frame with the next counter (nothing once closed).
  void send(FrameHeader h, const std::uint8_t* p, std::size_t n);
  // Writes what the socket takes; "" or why the link must close.
  std::string flush();
  bool pendingOutput() const { return out_pos_ < out_.size(); }
  bool congested() const { return out_.size() - out_pos_ >= kOutBufferLimit; }

  // Reads what arrived (at most 16 MiB a round: one busy peer cannot starve the others) and hands each frame to
  // `on_frame` until it returns false. Returns "" or why the link must close: the peer closed it, the socket
  // failed, or a frame did not decode (`bad` then says how; else it stays Ok).
  std::string receive(double now, const std::function<bool(Frame&)>& on_frame, DecodeStatus& bad);

  std::size_t inputCapacity() const { return decoder_.capacity(); }
  std::size_t outputCapacity() const { return out_.capacity(); }

 private:
  int fd_;
  bool connecting_;
  double opened_, last_rx_;
  FrameDecoder decoder_;
  std::vector<std::uint8_t> out_;
  std::size_t out_pos_ = 0;
  Authenticator tx_, rx_;
  std::uint64_t tx_counter_ = 0;
  ReplayWindow replay_;
};

}  // namespace relay
}  // namespace offshore_gnc
