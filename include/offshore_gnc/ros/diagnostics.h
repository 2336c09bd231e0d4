#pragma once
// Publishes a core's Counters (bad input, drops, recoveries) as diagnostic key-values, so every nodelet
// reports its health the same way. Level: WARN once any counter in `warn_on` has moved since start.
#include <diagnostic_updater/diagnostic_updater.h>

#include <set>
#include <string>

#include "offshore_gnc/common/counters.h"

namespace offshore_gnc {
namespace ros_util {

inline void addCounters(diagnostic_updater::DiagnosticStatusWrapper& stat, const Counters& counters,
                        const std::set<std::string>& warn_on = {}) {
  bool warn = false;
  for (const auto& kv : counters.snapshot()) {
    stat.add(kv.first, kv.second);
    if (kv.second > 0 && warn_on.count(kv.first)) warn = true;
  }
  if (warn) stat.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "bad input seen (see counters)");
}

}  // namespace ros_util
}  // namespace offshore_gnc
