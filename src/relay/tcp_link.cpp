// TCP links (include/offshore_gnc/relay/tcp_link.h).
#include "offshore_gnc/relay/tcp_link.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace relay {

void setNonBlocking(int fd) {
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
  int one = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
  int buf = 4 << 20;
  setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &buf, sizeof(buf));
  setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &buf, sizeof(buf));
}

int listenTcp(const std::string& host, int port, int& bound) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  int one = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port > 0 ? port : 0);
  if (inet_pton(AF_INET, host.c_str(), &a.sin_addr) != 1) {
    ::close(fd);
    throw ConfigError("relay config: listen host '" + host + "' is not an IPv4 address");
  }
  if (bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0 || listen(fd, 16) != 0) {
    const std::string err = std::strerror(errno);
    ::close(fd);
    throw std::runtime_error("relay: cannot listen on " + host + ":" + std::to_string(port) + ": " + err);
  }
  socklen_t len = sizeof(a);
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  bound = ntohs(a.sin_port);
  setNonBlocking(fd);
  return fd;
}

TcpLink::TcpLink(int fd, bool connecting, double now, std::size_t max_payload, const Authenticator& psk)
    : fd_(fd), connecting_(connecting), opened_(now), last_rx_(now), decoder_(max_payload) {
  decoder_.setAuthenticator(psk);
}

int TcpLink::dial(const std::string& host, int port, bool& in_progress) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  setNonBlocking(fd);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  inet_pton(AF_INET, host.c_str(), &a.sin_addr);
  const int r = connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a));
  if (r != 0 && errno != EINPROGRESS) {
    ::close(fd);
    return -1;
  }
  in_progress = r != 0;
  return fd;
}

void TcpLink::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

std::string TcpLink::finishConnect() {
  int err = 0;
  socklen_t len = sizeof(err);
  getsockopt(fd_, SOL_SOCKET, SO_ERROR, &err, &len);
  if (err) return std::strerror(err);
  connecting_ = false;
  return "";
}

void TcpLink::setKeys(const Authenticator& tx, const Authenticator& rx, std::size_t max_payload) {
  tx_ = tx;
  rx_ = rx;
  decoder_.setAuthenticator(rx);
  decoder_.setMaxPayload(max_payload);
}

void TcpLink::send(FrameHeader h, const std::uint8_t* p, std::size_t n) {
  if (closed()) return;
  h.counter = ++tx_counter_;
  encodeFrame(h, p, n, tx_, out_);
}

std::string TcpLink::flush() {
  while (!closed() && !connecting_ && out_pos_ < out_.size()) {
    const ssize_t r = ::send(fd_, out_.data() + out_pos_, out_.size() - out_pos_, MSG_NOSIGNAL);
    if (r > 0) {
      out_pos_ += static_cast<std::size_t>(r);
    } else {
      if (r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) break;
      return std::string("send failed: ") + std::strerror(errno);
    }
  }
  if (out_pos_ == out_.size()) {
    out_.clear();
    out_pos_ = 0;
  } else if (out_pos_ > (1u << 20) && out_pos_ * 2 > out_.size()) {
    // a peer that never quite catches up: drop what was sent, or the buffer grows for ever
    out_.erase(out_.begin(), out_.begin() + static_cast<std::ptrdiff_t>(out_pos_));
    out_pos_ = 0;
  }
  return "";
}

std::string TcpLink::receive(double now, const std::function<bool(Frame&)>& on_frame, DecodeStatus& bad) {
  static thread_local std::vector<std::uint8_t> buf(1 << 20);
  bad = DecodeStatus::Ok;
  std::size_t budget = 16u << 20;
  while (!closed() && budget > 0) {
    const std::size_t room = std::min(decoder_.room(), buf.size());
    if (room == 0) break;
    const ssize_t r = recv(fd_, buf.data(), room, 0);
    if (r == 0) return "closed by peer";
    if (r < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) break;
      return std::string("recv failed: ") + std::strerror(errno);
    }
    budget -= std::min<std::size_t>(budget, std::size_t(r));
    last_rx_ = now;
    decoder_.feed(buf.data(), std::size_t(r));
    Frame f;
    for (;;) {
      const DecodeStatus s = decoder_.next(f);
      if (s == DecodeStatus::NeedMore) break;
      if (s != DecodeStatus::Ok) {
        bad = s;
        return toString(s);
      }
      if (!on_frame(f)) return "";
    }
  }
  return "";
}

}  // namespace relay
}  // namespace offshore_gnc
