#pragma once
// Named event counters for bad input and other conditions a user should see in diagnostics.
// Cores count; the nodelet layer publishes the counts through diagnostic_updater. Thread-safe.
#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace offshore_gnc {

class Counters {
 public:
  void increment(const std::string& name, std::uint64_t by = 1) {
    std::lock_guard<std::mutex> lock(mutex_);
    counts_[name] += by;
  }
  std::uint64_t get(const std::string& name) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = counts_.find(name);
    return it == counts_.end() ? 0 : it->second;
  }
  std::map<std::string, std::uint64_t> snapshot() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }
  std::uint64_t total() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::uint64_t t = 0;
    for (const auto& kv : counts_) t += kv.second;
    return t;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::uint64_t> counts_;
};

}  // namespace offshore_gnc
