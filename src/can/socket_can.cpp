#include "offshore_gnc/can/socket_can.h"

#include <fcntl.h>
#include <libsocketcan.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace offshore_gnc {
namespace can {

const char* toString(BusState s) {
  switch (s) {
    case BusState::kDown: return "down";
    case BusState::kErrorActive: return "error_active";
    case BusState::kErrorWarning: return "error_warning";
    case BusState::kErrorPassive: return "error_passive";
    case BusState::kBusOff: return "bus_off";
  }
  return "?";
}

bool BusMonitor::onErrorFrame(const CanFrame& f) {
  const BusState before = state_;
  const std::uint32_t cls = f.id & CAN_ERR_MASK;
  counters_.increment("error_frames");
  if (cls & CAN_ERR_TX_TIMEOUT) counters_.increment("tx_timeouts");
  if (cls & CAN_ERR_LOSTARB) counters_.increment("lost_arbitration");
  if (cls & CAN_ERR_PROT) counters_.increment("protocol_errors");
  if (cls & CAN_ERR_ACK) counters_.increment("no_ack");
  if (cls & CAN_ERR_BUSERROR) counters_.increment("bus_errors");
  if (cls & CAN_ERR_CRTL) {
    counters_.increment("controller_problems");
    const std::uint8_t c = f.len > 1 ? f.data[1] : 0;
    if (c & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) state_ = BusState::kErrorPassive;
    else if (c & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) state_ = BusState::kErrorWarning;
    if (c & CAN_ERR_CRTL_ACTIVE) state_ = BusState::kErrorActive;
    if (c & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW)) counters_.increment("controller_overflows");
  }
  if (cls & CAN_ERR_BUSOFF) {
    state_ = BusState::kBusOff;
    counters_.increment("bus_off");
  }
  if (cls & CAN_ERR_RESTARTED) {
    state_ = BusState::kErrorActive;
    counters_.increment("restarted");
  }
  return state_ != before;
}

SocketCan::SocketCan(SocketCanOptions options, Counters& counters)
    : opt_(std::move(options)), counters_(counters), monitor_(counters) {
  monitor_.set(BusState::kDown);
}

SocketCan::~SocketCan() { close(); }

void SocketCan::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool SocketCan::open() {
  close();
  auto fail = [&](const std::string& what) {
    last_error_ = what + " on " + opt_.iface + ": " + std::strerror(errno);
    close();
    monitor_.set(BusState::kDown);
    return false;
  };
  if (opt_.iface.empty() || opt_.iface.size() >= IFNAMSIZ) {
    errno = EINVAL;
    return fail("interface name");
  }
  fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd_ < 0) return fail("socket(AF_CAN)");
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, opt_.iface.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd_, SIOCGIFINDEX, &ifr) < 0) return fail("SIOCGIFINDEX");
  ifindex_ = static_cast<unsigned>(ifr.ifr_ifindex);

  std::vector<can_filter> filters;
  for (const auto& f : opt_.filters)
    filters.push_back({(f.id & CAN_EFF_MASK) | CAN_EFF_FLAG, (f.mask & CAN_EFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG});
  if (!filters.empty() &&
      ::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(), static_cast<socklen_t>(filters.size() * sizeof(can_filter))) < 0)
    return fail("CAN_RAW_FILTER");
  can_err_mask_t err_mask = CAN_ERR_MASK;
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) < 0) return fail("CAN_RAW_ERR_FILTER");
  const int own = opt_.receive_own ? 1 : 0;
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof own) < 0) return fail("CAN_RAW_RECV_OWN_MSGS");
  fd_enabled_ = false;
  if (opt_.fd && ::ioctl(fd_, SIOCGIFMTU, &ifr) == 0 && ifr.ifr_mtu == CANFD_MTU) {
    const int on = 1;
    fd_enabled_ = ::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof on) == 0;
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(ifindex_);
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) return fail("bind");
  ifr.ifr_flags = 0;
  const bool up = ::ioctl(fd_, SIOCGIFFLAGS, &ifr) == 0 && (ifr.ifr_flags & IFF_UP);
  monitor_.set(up ? BusState::kErrorActive : BusState::kDown);
  last_error_.clear();
  return true;
}

void SocketCan::goDown(int err) {
  if (monitor_.state() != BusState::kDown) {
    counters_.increment("interface_down");
    last_error_ = opt_.iface + ": " + std::strerror(err);
  }
  monitor_.set(BusState::kDown);
}

std::vector<CanFrame> SocketCan::receive(double now, std::size_t max) {
  std::vector<CanFrame> out;
  if (fd_ < 0) return out;
  canfd_frame raw{};
  while (out.size() < max) {
    const ssize_t n = ::read(fd_, &raw, sizeof raw);
    if (n < 0) {
      if (errno == ENETDOWN || errno == ENODEV || errno == ENXIO) goDown(errno);
      else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) counters_.increment("read_errors");
      break;
    }
    if (n != CAN_MTU && n != CANFD_MTU) {
      counters_.increment("short_reads");
      continue;
    }
    if (monitor_.state() == BusState::kDown) monitor_.set(BusState::kErrorActive);  // traffic: it is back
    CanFrame f;
    f.fd = n == CANFD_MTU;
    f.error = raw.can_id & CAN_ERR_FLAG;
    f.rtr = raw.can_id & CAN_RTR_FLAG;
    f.extended = raw.can_id & CAN_EFF_FLAG;
    f.id = raw.can_id & (f.error ? CAN_ERR_MASK : f.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    f.len = std::min<std::uint8_t>(raw.len, f.fd ? CANFD_MAX_DLEN : CAN_MAX_DLEN);
    std::memcpy(f.data.data(), raw.data, f.len);
    if (f.error) {
      if (monitor_.onErrorFrame(f) && monitor_.state() == BusState::kBusOff) {
        busoff_since_ = now;
        restart_backoff_ = 0.0;
      }
      continue;
    }
    counters_.increment("rx_frames");
    out.push_back(f);
  }
  return out;
}

void SocketCan::send(const CanFrame& f) {
  if (f.len > (f.fd ? 64 : 8)) {
    counters_.increment("tx_invalid");
    return;
  }
  if (queue_.size() >= opt_.tx_queue) {
    queue_.pop_front();
    counters_.increment("tx_dropped");
  }
  queue_.push_back(f);
}

void SocketCan::flush() {
  // Nothing leaves while the bus is off or down: the queue keeps the newest frames for the restart.
  while (fd_ >= 0 && !queue_.empty() && monitor_.state() != BusState::kBusOff && monitor_.state() != BusState::kDown) {
    const CanFrame& f = queue_.front();
    canfd_frame raw{};
    // Error frames can only be sent on virtual interfaces: tests inject them to emulate a failing controller.
    raw.can_id = f.id | (f.extended ? CAN_EFF_FLAG : 0U) | (f.rtr ? CAN_RTR_FLAG : 0U) | (f.error ? CAN_ERR_FLAG : 0U);
    raw.len = f.len;
    std::memcpy(raw.data, f.data.data(), f.len);
    const bool as_fd = f.fd && fd_enabled_;
    if (f.fd && !fd_enabled_) {
      counters_.increment("tx_fd_unsupported");
      queue_.pop_front();
      continue;
    }
    const ssize_t n = ::write(fd_, &raw, as_fd ? CANFD_MTU : CAN_MTU);
    if (n < 0) {
      if (errno == ENOBUFS || errno == EAGAIN) counters_.increment("tx_busy");  // retry on the next flush
      else if (errno == ENETDOWN || errno == ENODEV || errno == ENXIO) goDown(errno);
      else {
        counters_.increment("write_errors");
        queue_.pop_front();
      }
      return;
    }
    counters_.increment("tx_frames");
    queue_.pop_front();
  }
}

void SocketCan::poll(double now) {
  if (monitor_.state() == BusState::kBusOff && opt_.auto_restart && busoff_since_ >= 0 &&
      now - busoff_since_ >= opt_.restart_delay) {
    counters_.increment("restart_requests");
    busoff_since_ = now + restart_backoff_;  // retry later, backing off, while the controller stays off
    restart_backoff_ = std::min(2.0 * restart_backoff_ + opt_.restart_delay, 5.0);
    // Needs CAP_NET_ADMIN and a real controller with restart-ms 0; virtual interfaces refuse it.
    if (can_do_restart(opt_.iface.c_str()) != 0) counters_.increment("restart_failed");
  }
  if (monitor_.state() != BusState::kDown && fd_ >= 0) return;
  if (now - last_reopen_ < opt_.reopen_period) return;
  last_reopen_ = now;
  // A deleted + re-created interface has a new index: the old binding is dead and we must reopen.
  const unsigned idx = if_nametoindex(opt_.iface.c_str());
  if (fd_ < 0 || idx != ifindex_) {
    if (idx == 0) return;
    if (open()) counters_.increment("reopened");
    return;
  }
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, opt_.iface.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd_, SIOCGIFFLAGS, &ifr) == 0 && (ifr.ifr_flags & IFF_UP)) {
    monitor_.set(BusState::kErrorActive);
    counters_.increment("interface_up");
  }
}

bool SocketCan::wait(double timeout_s) {
  if (fd_ < 0) {
    ::usleep(static_cast<useconds_t>(timeout_s * 1e6));
    return false;
  }
  pollfd p{fd_, POLLIN, 0};
  return ::poll(&p, 1, static_cast<int>(timeout_s * 1000.0)) > 0 && (p.revents & (POLLIN | POLLERR));
}

}  // namespace can
}  // namespace offshore_gnc
