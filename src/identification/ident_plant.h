#pragma once
// Internal to the identification: one vehicle model behind a common face, so that the fitting code never knows
// which vehicle it fits. Each plant owns its parameter struct and runs the models module's own model on it.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/identification/ident_log.h"
#include "offshore_gnc/identification/identification.h"

namespace offshore_gnc {
namespace identification {
namespace ident {

class Plant {
 public:
  virtual ~Plant() = default;
  virtual std::unique_ptr<Plant> clone() const = 0;
  virtual std::string model() const = 0;                     // dynamic_3dof, nomoto, auv_4dof
  virtual const std::vector<FitParameter>& parameters() const = 0;
  virtual double get(const std::string& key) const = 0;      // the value in the parameter struct
  virtual void set(const std::string& key, double v) = 0;
  virtual const std::vector<std::string>& commands() const = 0;  // log command columns
  virtual const std::vector<std::string>& outputs() const = 0;   // simulated signals (kLogSignals names)
  virtual const std::vector<std::string>& freeState() const = 0; // a hull segment's free initial state
  virtual double warmup(const FitOptions& opt) const = 0;        // actuator memory to run before a segment [s]
  // Runs log rows [warm, end): reset at row `warm` to the measured state there, commands held row to row
  // (zero-order hold, steps <= dt), at row `begin` the free state is set to x0 (when given), and the outputs of
  // rows [begin, end) are written to out (row-major, outputs().size() per row). False when the parameters are
  // refused by the model or the run is not finite.
  virtual bool simulate(const IdentLog& log, const models::Environment& env, double dt, std::size_t warm,
                        std::size_t begin, std::size_t end, const double* x0, double* out) const = 0;
  // Per group: the force or set-point the logged commands give, per row of [begin, end) (what excites it).
  // A group not in the map has no force of its own (USV sway): its motion decides.
  virtual std::map<std::string, std::vector<double>> excitation(const IdentLog& log, const models::Environment& env,
                                                                double dt, std::size_t begin,
                                                                std::size_t end) const = 0;
  // Checks the values by the model's own validation (ConfigError).
  virtual void validate() const = 0;
};

std::unique_ptr<Plant> makePlant(FitVehicle v, const std::string& yaml_text, const std::string& source);

// One stage's least-squares problem exactly as the fit poses it (start values, first-pass weights), so that
// another optimiser can be compared on the same residuals (bench/model_fit.sh: Ceres vs SciPy).
class StageBench {
 public:
  StageBench(FitVehicle v, const std::string& text, const std::string& source, IdentLog log, const FitOptions& opt,
             const std::string& stage);
  ~StageBench();
  int globals() const;   // the coefficients (scaled: 1 = start value)
  int locals() const;    // per segment (its free initial state)
  int segments() const;
  std::vector<int> residualCounts() const;  // per segment
  std::vector<double> x0() const;           // globals, then each segment's locals
  std::vector<double> lower() const;        // same layout; -1e300 = none
  bool residuals(const double* x, double* r) const;
  int solveCeres(std::vector<double>& x, int max_iterations, double* final_cost);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Signal helpers shared by the plants and the fit.
bool isAngle(const std::string& signal);  // yaw_rad: differences are wrapped
std::string groupSignal(const std::string& group);  // surge -> u, yaw -> r_rad_s, rpm -> rpm, ...

}  // namespace ident
}  // namespace identification
}  // namespace offshore_gnc
