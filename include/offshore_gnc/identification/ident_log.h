#pragma once
// A vehicle log for model identification (ROS-free): timed commands as model_run takes them plus whatever was
// measured. Built from a CSV (named columns) or, by model_fit's bag reader, from a rosbag of our launch files.
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "offshore_gnc/models/csv_table.h"

namespace offshore_gnc {
namespace identification {

// The measured signals the identification knows (column names of the CSV): NED position [m], yaw [rad]
// (clockwise from north), body velocities over ground [m/s], yaw rate [rad/s], USV engine rpm and nozzle
// position P_nozzle (-10000..10000, < 0 turns to starboard: model_run's `nozzle` column).
extern const std::vector<std::string> kLogSignals;  // north east down yaw_rad u v w r_rad_s rpm nozzle

struct IdentLog {
  std::string source;
  std::vector<double> t;                    // non-decreasing [s]
  std::vector<std::string> command_names;   // "surge,sway,yaw" (USV) or "c1".."cn" (AUV thrusters)
  Eigen::MatrixXd commands;                 // rows x commands; NaN = the command is not known there
  std::map<std::string, std::vector<double>> measured;  // signal -> value per row; NaN = not measured
  std::vector<std::string> notes;           // what the reader did (e.g. lat/lon converted), for the report
  std::size_t rows() const { return t.size(); }
  // The signal is in the log with at least `min_samples` finite values.
  bool has(const std::string& signal, std::size_t min_samples = 1) const;
  std::size_t count(const std::string& signal) const;  // finite values of a signal
};

// From a CSV with a header: `t`, the command columns, then any of kLogSignals (other columns are ignored and
// listed in notes). `lat_deg,lon_deg` instead of north/east are converted to a local NED frame at the first
// fix (the fit needs relative motion only). Empty cells and "nan" are missing values. Throws ConfigError when
// the header, `t` or a command column is missing, or nothing measured is in it.
IdentLog identLogFromCsv(const models::CsvTable& csv, const std::vector<std::string>& command_names,
                         const std::string& source);
IdentLog readIdentLogCsv(const std::string& path, const std::vector<std::string>& command_names);

}  // namespace identification
}  // namespace offshore_gnc
