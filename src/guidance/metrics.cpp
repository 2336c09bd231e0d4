#include "offshore_gnc/guidance/metrics.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace offshore_gnc {
namespace guidance {

TrackingMetrics computeMetrics(const std::vector<double>& e, std::size_t* skipped) {
  TrackingMetrics m;
  double sum = 0, sum2 = 0, sum_abs = 0;
  std::size_t bad = 0;
  for (double v : e) {
    if (!std::isfinite(v)) {
      ++bad;
      continue;
    }
    ++m.samples;
    sum += v;
    sum2 += v * v;
    sum_abs += std::abs(v);
    m.max_abs = std::max(m.max_abs, std::abs(v));
  }
  if (skipped) *skipped = bad;
  if (m.samples == 0) return m;
  const double n = static_cast<double>(m.samples);
  m.mean = sum / n;
  m.rmse = std::sqrt(sum2 / n);
  m.mae = sum_abs / n;
  m.sd = std::sqrt(std::max(0.0, sum2 / n - m.mean * m.mean));
  return m;
}

namespace {
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    while (!cell.empty() && (cell.back() == '\r' || cell.back() == ' ')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(cell.begin());
    out.push_back(cell);
  }
  return out;
}
}  // namespace

std::vector<double> readCsvColumn(std::istream& in, const std::string& column, int mode_filter) {
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("CSV is empty (a header line is required)");
  const auto head = split(line);
  int col = -1, mode_col = -1;
  for (std::size_t i = 0; i < head.size(); ++i) {
    if (head[i] == column) col = static_cast<int>(i);
    if (head[i] == "mode") mode_col = static_cast<int>(i);
  }
  if (col < 0) throw std::runtime_error("CSV header has no column '" + column + "'");
  std::vector<double> out;
  int n = 1;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    const auto cells = split(line);
    if (static_cast<int>(cells.size()) <= std::max(col, mode_col))
      throw std::runtime_error("CSV line " + std::to_string(n) + " has too few columns");
    try {
      if (mode_filter >= 0 && mode_col >= 0 && std::stoi(cells[mode_col]) != mode_filter) continue;
      out.push_back(std::stod(cells[col]));
    } catch (const std::exception&) {
      throw std::runtime_error("CSV line " + std::to_string(n) + ": not a number");
    }
  }
  return out;
}

}  // namespace guidance
}  // namespace offshore_gnc
