#pragma once
// Path-following indicators of thesis Tables 4.4 and 5.1 from cross-track error samples: RMSE, SD, MAE.
#include <cstddef>
#include <istream>
#include <string>
#include <vector>

namespace offshore_gnc {
namespace guidance {

struct TrackingMetrics {
  std::size_t samples = 0;
  double rmse = 0.0;   // sqrt(mean(e^2))
  double sd = 0.0;     // population standard deviation of e
  double mae = 0.0;    // mean(|e|)
  double max_abs = 0.0;
  double mean = 0.0;
};

// Non-finite samples are skipped (counted in `skipped` when given).
TrackingMetrics computeMetrics(const std::vector<double>& e, std::size_t* skipped = nullptr);

// CSV with a header line naming the columns; takes the column `column` (e.g. cross_track_error) and, when a
// `mode` column exists, only rows whose mode equals `mode_filter` (< 0: all rows). Throws std::runtime_error
// naming the line on malformed input.
std::vector<double> readCsvColumn(std::istream& in, const std::string& column, int mode_filter = -1);

}  // namespace guidance
}  // namespace offshore_gnc
