// tracking_metrics: cross-track RMSE / SD / MAE (thesis Tables 4.4 and 5.1) from a recorded run.
//   tracking_metrics run.bag [/usv/guidance/status]   GuidanceStatus samples in MODE_FOLLOW_PATH
//   tracking_metrics run.csv [column]                 CSV with a header; rows with a `mode` column other than 1
//                                                     (follow path) are skipped; default column cross_track_error
// Prints one JSON object.
#include <offshore_gnc/GuidanceStatus.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "offshore_gnc/guidance/metrics.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s RUN.bag [status_topic] | RUN.csv [column]\n", argv[0]);
    return 2;
  }
  const std::string file = argv[1];
  std::vector<double> e;
  try {
    if (file.size() > 4 && file.substr(file.size() - 4) == ".bag") {
      const std::string topic = argc > 2 ? argv[2] : "/usv/guidance/status";
      rosbag::Bag bag(file, rosbag::bagmode::Read);
      rosbag::View view(bag, rosbag::TopicQuery(topic));
      for (const auto& m : view) {
        const auto s = m.instantiate<offshore_gnc::GuidanceStatus>();
        if (s && s->mode == offshore_gnc::GuidanceStatus::MODE_FOLLOW_PATH) e.push_back(s->cross_track_error);
      }
    } else {
      std::ifstream in(file);
      if (!in) throw std::runtime_error("cannot open " + file);
      e = offshore_gnc::guidance::readCsvColumn(in, argc > 2 ? argv[2] : "cross_track_error", 1);
    }
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "tracking_metrics: %s\n", ex.what());
    return 1;
  }
  std::size_t skipped = 0;
  const auto m = offshore_gnc::guidance::computeMetrics(e, &skipped);
  if (m.samples == 0) {
    std::fprintf(stderr, "tracking_metrics: no path-following samples in %s\n", file.c_str());
    return 1;
  }
  std::printf("{\"samples\": %zu, \"skipped_non_finite\": %zu, \"rmse_m\": %.4f, \"sd_m\": %.4f, \"mae_m\": %.4f, "
              "\"max_abs_m\": %.4f, \"mean_m\": %.4f}\n",
              m.samples, skipped, m.rmse, m.sd, m.mae, m.max_abs, m.mean);
  return 0;
}
