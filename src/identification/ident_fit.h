#pragma once
// Internal to the identification: the fit behind fitModel and StageBench (identification.cpp), by what it does:
//   ident_segments.cpp  the log cut into pieces (gaps, unknown commands) and segments, noise levels, and whether
//                       a log can estimate a group at all (measured, excited);
//   ident_stage.cpp     one stage's least-squares problem (multiple shooting) and its Ceres solution;
//   ident_fit.cpp       the orchestration: stage after stage, delays, loose coefficients, the validation series.
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ident_plant.h"
#include "offshore_gnc/identification/identification.h"
#include "offshore_gnc/models/environment.h"

namespace offshore_gnc {
namespace identification {
namespace ident {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fmt(double v, int precision = 3);
std::string joinKeys(const std::vector<std::string>& keys);

// ---------------------------------------------------------------- segmentation (ident_segments.cpp)
struct Piece {
  std::size_t begin, end;  // rows [begin, end)
};
struct Segment {
  std::size_t warm, begin, end;
};

// Row index of the first row at or after time t within [from, to).
std::size_t rowAt(const IdentLog& log, double t, std::size_t from, std::size_t to);
// Splits the log at gaps and unknown commands; says where and why.
std::vector<Piece> findPieces(const IdentLog& log, const FitOptions& opt, std::vector<std::string>& msg);
// Robust white-noise level of a signal from its second differences within the pieces.
double noiseLevel(const IdentLog& log, const std::string& s, const std::vector<Piece>& pieces);

// ---------------------------------------------------------------- one stage's problem (ident_stage.cpp)
struct Item {
  std::size_t row;  // offset from the segment's begin
  int out;          // index into the plant's outputs
  int slot;         // index into the stage's signals (weight)
  double value;     // measured
};

struct StageProblem {
  const IdentLog* log = nullptr;
  const models::Environment* env = nullptr;
  double dt = 0.02;
  const Plant* base = nullptr;     // current values of everything not in `keys`
  std::vector<std::string> keys;   // continuous parameters of the global block
  std::vector<double> scale;       // physical = x * scale
  std::vector<std::string> signals;
  std::vector<int> angle;          // per slot: 1 when the signal is an angle
  std::vector<double> weight;      // per slot: 1 / noise
  std::vector<Segment> segs;
  std::vector<std::vector<Item>> items;
  bool free_state = false;
  mutable std::vector<double> buf;

  std::unique_ptr<Plant> plantAt(const double* xg) const;
  bool run(const Plant& p, std::size_t k, const double* xl, std::vector<double>& out) const;
  bool residuals(std::size_t k, const double* xg, const double* xl, double* r) const;
  double cost(const double* xg, const std::vector<std::vector<double>>& xl) const;
  void stats(const double* xg, const std::vector<std::vector<double>>& xl, std::vector<double>& rms,
             std::vector<double>& rho) const;
  std::vector<double> rms(const double* xg, const std::vector<std::vector<double>>& xl) const;
};

struct SolveResult {
  int iterations = 0;
  bool usable = false;
  std::vector<double> se;  // per key, relative to scale (NaN when the covariance failed)
};

// Levenberg-Marquardt over the global block xg (bounds from the parameter table) and the segments' states.
SolveResult solve(const StageProblem& sp, std::vector<double>& xg, const std::vector<double>& lower,
                  std::vector<std::vector<double>>& xl, int max_iterations, bool covariance,
                  double function_tolerance = 1e-8);

// ---------------------------------------------------------------- the whole fit (ident_fit.cpp)
double nrmse(const std::vector<double>& y, const std::vector<double>& ys);
// Continuous angle from a wrapped one (NaN kept), so that fits of yaw are not broken by the +-pi jump.
void unwrapInPlace(std::vector<double>& y, std::size_t begin, std::size_t end);

class Fit {
 public:
  Fit(FitVehicle v, const std::string& text, const std::string& source, const IdentLog& log, const FitOptions& opt);
  FitReport run();
  // The pieces, noise levels, results table and excitation: what every stage needs first.
  void prepare();

  // One stage's problem at the start values with the first pass' weights, for comparing optimisers (bench).
  struct Bench {
    StageProblem sp;
    std::vector<double> xg, lower;
    std::vector<std::vector<double>> xl;
  };
  Bench bench(const std::string& stage);

 private:
  ParameterResult& result(const std::string& key);
  // segmentation (ident_segments.cpp)
  std::vector<Segment> segments(const std::string& stage) const;
  std::string cannotEstimate(const std::string& group, const std::string& stage, const std::vector<Segment>& segs,
                             const std::map<std::string, std::vector<double>>& exc) const;
  double spreadOf(const std::string& s) const;
  // the stage's problem (ident_stage.cpp)
  std::vector<std::string> stageSignals(const std::string& stage) const;
  StageProblem problem(const std::string& stage, const std::vector<Segment>& segs,
                       const std::vector<std::string>& keys);
  std::vector<std::vector<double>> initialStates(const StageProblem& sp) const;
  double trackVelocity(const std::string& n, std::size_t b, std::size_t e) const;
  void reweight(StageProblem& sp, const std::vector<double>& xg, const std::vector<std::vector<double>>& xl,
                bool correlated);
  // the orchestration (ident_fit.cpp)
  void fitStage(const std::string& stage);
  void profileDelay(StageProblem& sp, const std::string& key, std::vector<double>& xg,
                    const std::vector<double>& lower, std::vector<std::vector<double>>& xl);
  void scanDelay(StageProblem& sp, const std::string& key, const std::vector<double>& xg,
                 const std::vector<std::vector<double>>& xl, bool fine);
  void notEstimated(const std::string& group, const std::string& stage, const std::string& why);
  void notEstimatedKey(const std::string& key, const std::string& why);
  void stageSegments(StageProblem& sp, const std::vector<std::vector<double>>& xl);
  void series();

  std::unique_ptr<Plant> plant_, start_;
  const IdentLog& log_;
  FitOptions opt_;
  models::Environment env_;
  std::vector<Piece> pieces_;
  std::map<std::string, double> noise_, fit_noise_, spread_;
  std::map<std::string, std::vector<double>> seg_;
  std::vector<ParameterResult> results_;
  std::map<std::string, std::vector<double>> exc_;
  std::map<std::size_t, std::pair<std::size_t, std::vector<double>>> start_state_;  // piece -> (row, state)
  FitReport r_;
};

}  // namespace ident
}  // namespace identification
}  // namespace offshore_gnc
