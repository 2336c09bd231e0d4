#pragma once
// Model identification from logs (thesis chapter 3: the transfer functions of eq. 3.24/3.25 and Table 3.2, the
// hydrodynamic coefficients of Table 3.4), ROS-free. The simulated response always comes from the models
// module's own models::UsvModel / models::AuvModel, the code the simulators run; Ceres' Levenberg-Marquardt fits it to the log
// by multiple shooting (docs/model-identification.md argues the choice):
//   - the log is cut into pieces at gaps and unknown (NaN) commands;
//   - actuator stages (USV engine rpm, nozzle) are fitted on whole pieces from their own logged signal;
//   - the hull stage simulates short segments, each from its own free initial state (position, yaw and, for
//     the 3-DOF models, velocities), after an actuator warm-up, against position, yaw and velocities;
//   - residuals are weighted by each signal's noise, re-estimated from the fit's own residuals;
//   - a parameter the log does not excite (its force never changes), or determines only loosely (relative
//     standard error above max_rel_se), is kept at its start value with a message saying why.
// The parameter set is a table (FitParameter rows per vehicle and model type): adding a coefficient is adding
// a row and its field accessor.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/identification/ident_log.h"

namespace offshore_gnc {
namespace identification {

enum class FitVehicle { Usv, Girona500, AColor };
FitVehicle fitVehicleFromName(const std::string& name);  // "usv", "girona500", "acolor"; ConfigError otherwise
std::string fitVehicleName(FitVehicle v);

// One coefficient that can be fitted, named as the model's parameter file names it.
struct FitParameter {
  std::string key;          // YAML key; list elements as "rpm_num[1]"
  std::string group;        // the dynamics it belongs to: rpm, nozzle, surge, sway, heave, yaw
  std::string stage;        // fitted together: rpm, nozzle, hull
  bool magnitude = false;   // the model uses |value|: fitted >= 0, written back with the start value's sign
  bool delay = false;       // a transport delay: scanned on the simulation step, not differentiated
  double nominal = 1.0;     // scale when the start value is 0
  double lower = -1e300;    // lower bound (physical units; magnitudes: 0)
};

struct FitOptions {
  models::EnvironmentParams environment;  // water and air during the log (calm by default)
  double dt = 0.01;               // simulation step [s] (the simulators' step; delays resolve to it)
  double segment = 30.0;          // multiple-shooting segment length [s]
  double warmup = 10.0;           // actuator warm-up before a segment / skipped at a piece's start [s]
  double max_gap = 1.0;           // rows further apart than this split the log [s]
  double min_piece = 20.0;        // shorter pieces are not used [s]
  double max_rel_se = 0.5;        // looser estimates are kept at the start value
  double delay_max = 2.0;         // delays are scanned over [0, delay_max] [s]
  int max_iterations = 60;
  bool estimate = true;           // false: validation only (simulate the given parameters)
  std::vector<std::string> fixed; // keys never to estimate
};

struct ParameterResult {
  FitParameter param;
  double start = 0, value = 0, se = 0;  // values as the file writes them (start's sign for magnitudes)
  bool estimated = false;
  std::string note;                     // why not estimated, or how (delay: scan resolution)
};

struct SignalFit {
  std::string signal;
  std::size_t samples = 0;
  double noise = 0;         // residual RMS of the fit (the weight used) [signal units]
  double segment_fit = 0;   // NRMSE fit [%] of the simulations the estimate minimised
  double open_loop_fit = 0; // NRMSE fit [%] of one open-loop run per piece (from its first segment's state)
  bool motion = true;       // false: the signal varies no more than 3x its residual (noise only; fit % meaningless)
};

// Per row, for the report's plots: measured, the open-loop run and the multiple-shooting segments (NaN
// outside them).
struct FitSeries {
  std::vector<double> t;
  std::map<std::string, std::vector<double>> measured, open_loop, segments;
};

struct FitReport {
  FitVehicle vehicle = FitVehicle::Usv;
  std::string model;                       // dynamic_3dof, nomoto, auv_4dof
  std::vector<ParameterResult> parameters; // every candidate, estimated or not
  std::vector<SignalFit> fits;
  std::vector<std::string> messages;       // what the log lacks and what could not be estimated, and why
  FitSeries series;
  std::size_t rows = 0, pieces = 0, segments = 0, used_rows = 0;
  int iterations = 0;
  double cpu_seconds = 0;
  std::map<std::string, double> stage_cpu_seconds;  // per stage (rpm, nozzle, hull) and "validation"
  bool anything_estimated() const;
  const ParameterResult* find(const std::string& key) const;
};

// The coefficients that can be fitted for this vehicle and the model type of the start file.
std::vector<FitParameter> fitParameters(FitVehicle v, const std::string& params_yaml_text,
                                        const std::string& source);

// The log's command columns for this vehicle (USV: surge,sway,yaw; AUV: c1..cn, one per thruster of the file).
std::vector<std::string> fitCommandColumns(FitVehicle v, const std::string& params_yaml_text,
                                           const std::string& source);

// Fits (or, with estimate = false, validates) the model of the start file against the log. Throws ConfigError
// for a start file or log it cannot use at all (bad file, no usable piece, no measured signal the model makes).
FitReport fitModel(FitVehicle v, const std::string& params_yaml_text, const std::string& params_source,
                   const IdentLog& log, const FitOptions& opt);

// The start file with the estimates written in (comments kept; each fitted line says its standard error). The
// result is checked by loading it with the models' own loader. Throws ConfigError if that fails.
std::string fittedParamsYaml(FitVehicle v, const std::string& start_text, const std::string& source,
                             const FitReport& r);

// NRMSE fit [%] = 100 (1 - |y - y_sim| / |y - mean(y)|) over the rows where both are finite (thesis Figs.
// 3.8-3.12, MATLAB's compare). NaN when fewer than 2 samples or y is constant.
double nrmseFit(const std::vector<double>& measured, const std::vector<double>& simulated);

}  // namespace identification
}  // namespace offshore_gnc
