#pragma once
// A CAN bus for plain gtests (ros_canopen's DummyInterface): frames the test scripts come in at given times,
// the frames sent are kept with their times, the bus state is set by the test, and wait() advances the
// simulated clock the gateway reads. The SocketCAN suite (test/suites/can_vcan.sh) runs the same logic on a
// real vcan0.
#include <deque>
#include <utility>
#include <vector>

#include "offshore_gnc/can/socket_can.h"

namespace offshore_gnc {
namespace can {

class ScriptedBus : public BusInterface {
 public:
  struct Shared {  // what the test keeps after handing the bus to the gateway
    double now = 0.0;
    std::deque<std::pair<double, CanFrame>> incoming;  // (time it arrives, frame)
    std::vector<std::pair<double, CanFrame>> sent;     // (time it left, frame)
    BusState state = BusState::kErrorActive;
    int opens = 0, polls = 0;
  };
  explicit ScriptedBus(Shared& s) : s_(s) {}
  bool open() override { return ++s_.opens, s_.state != BusState::kDown; }
  std::vector<CanFrame> receive(double now, std::size_t max) override {
    std::vector<CanFrame> out;
    while (!s_.incoming.empty() && s_.incoming.front().first <= now && out.size() < max) {
      out.push_back(s_.incoming.front().second);
      s_.incoming.pop_front();
    }
    return out;
  }
  void send(const CanFrame& f) override { queue_.push_back(f); }
  void flush() override {
    if (s_.state == BusState::kBusOff || s_.state == BusState::kDown) return;  // the kernel would refuse them
    for (const auto& f : queue_) s_.sent.emplace_back(s_.now, f);
    queue_.clear();
  }
  void poll(double) override { ++s_.polls; }
  bool wait(double timeout_s) override {
    s_.now += timeout_s > 0.0 ? timeout_s : 1e-4;  // simulated time passes while the gateway waits
    return !s_.incoming.empty() && s_.incoming.front().first <= s_.now;
  }
  BusState state() const override { return s_.state; }
  std::string lastError() const override { return s_.state == BusState::kDown ? "scripted: interface down" : ""; }

 private:
  Shared& s_;
  std::vector<CanFrame> queue_;
};

}  // namespace can
}  // namespace offshore_gnc
