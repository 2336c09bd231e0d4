// Model identification by multiple shooting with Ceres (see identification.h and docs/model-identification.md).
#include "offshore_gnc/identification/identification.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>

#include <ceres/ceres.h>

#include "ident_plant.h"
#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace identification {

using ident::Plant;

FitVehicle fitVehicleFromName(const std::string& name) {
  if (name == "usv") return FitVehicle::Usv;
  if (name == "girona500") return FitVehicle::Girona500;
  if (name == "acolor") return FitVehicle::AColor;
  throw ConfigError("vehicle '" + name + "' is not one of: usv, girona500, acolor");
}

std::string fitVehicleName(FitVehicle v) {
  return v == FitVehicle::Usv ? "usv" : (v == FitVehicle::Girona500 ? "girona500" : "acolor");
}

bool FitReport::anything_estimated() const {
  return std::any_of(parameters.begin(), parameters.end(), [](const ParameterResult& p) { return p.estimated; });
}

const ParameterResult* FitReport::find(const std::string& key) const {
  for (const auto& p : parameters)
    if (p.param.key == key) return &p;
  return nullptr;
}

std::vector<FitParameter> fitParameters(FitVehicle v, const std::string& text, const std::string& source) {
  return ident::makePlant(v, text, source)->parameters();
}

std::vector<std::string> fitCommandColumns(FitVehicle v, const std::string& text, const std::string& source) {
  return ident::makePlant(v, text, source)->commands();
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fmt(double v, int precision = 3) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

std::string joinKeys(const std::vector<std::string>& keys) {
  std::string s;
  for (const auto& k : keys) s += (s.empty() ? "" : ", ") + k;
  return s;
}

struct Piece {
  std::size_t begin, end;  // rows [begin, end)
};
struct Segment {
  std::size_t warm, begin, end;
};

// Row index of the first row at or after time t within [from, to).
std::size_t rowAt(const IdentLog& log, double t, std::size_t from, std::size_t to) {
  return static_cast<std::size_t>(std::lower_bound(log.t.begin() + from, log.t.begin() + to, t - 1e-9) -
                                  log.t.begin());
}

// Splits the log at gaps and unknown commands; says where and why.
std::vector<Piece> findPieces(const IdentLog& log, const FitOptions& opt, std::vector<std::string>& msg) {
  std::vector<Piece> pieces;
  const std::size_t n = log.rows();
  std::vector<std::string> gaps, nans;
  std::size_t a = 0;
  auto close = [&](std::size_t end) {
    if (end <= a) return;
    if (log.t[end - 1] - log.t[a] >= opt.min_piece) {
      pieces.push_back({a, end});
    } else if (end - a > 1) {
      msg.push_back("t " + fmt(log.t[a], 6) + "-" + fmt(log.t[end - 1], 6) + " s is only " +
                    fmt(log.t[end - 1] - log.t[a]) + " s between breaks (shorter than " + fmt(opt.min_piece) +
                    " s): not used");
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    bool known = true;
    std::string which;
    for (Eigen::Index k = 0; k < log.commands.cols(); ++k)
      if (!std::isfinite(log.commands(static_cast<Eigen::Index>(i), k))) {
        known = false;
        which = log.command_names[k];
      }
    if (!known) {
      // a run of rows with an unknown command: one message for the run
      std::size_t j = i;
      while (j + 1 < n && !std::isfinite(log.commands.row(static_cast<Eigen::Index>(j + 1)).sum())) ++j;
      nans.push_back("rows " + std::to_string(i + 1) + "-" + std::to_string(j + 1) + " (t " + fmt(log.t[i], 6) +
                     "-" + fmt(log.t[j], 6) + " s): command '" + which +
                     "' is not a number, so the motion from there to the next known command cannot be simulated");
      close(i + 1);  // row i is still a measurement of the piece before
      a = j + 1;
      i = j;
      continue;
    }
    if (i + 1 < n && log.t[i + 1] - log.t[i] > opt.max_gap) {
      gaps.push_back(fmt(log.t[i + 1] - log.t[i]) + " s between t " + fmt(log.t[i], 6) + " and " +
                     fmt(log.t[i + 1], 6) + " s (rows " + std::to_string(i + 1) + "-" + std::to_string(i + 2) + ")");
      close(i + 1);
      a = i + 1;
    }
  }
  close(n);
  auto report = [&](const std::vector<std::string>& what, const std::string& head) {
    if (what.empty()) return;
    std::string s = head;
    for (std::size_t i = 0; i < what.size() && i < 5; ++i) s += (i ? "; " : " ") + what[i];
    if (what.size() > 5) s += "; and " + std::to_string(what.size() - 5) + " more";
    msg.push_back(s);
  };
  report(gaps, "the log has gaps longer than " + fmt(opt.max_gap) +
                   " s (the commands in them are unknown; the model restarts after each from the measured state):");
  report(nans, "the log has rows without a command:");
  return pieces;
}

// Robust white-noise level of a signal from its second differences within the pieces.
double noiseLevel(const IdentLog& log, const std::string& s, const std::vector<Piece>& pieces) {
  const auto it = log.measured.find(s);
  if (it == log.measured.end()) return kNaN;
  std::vector<double> d2, all;
  for (const auto& p : pieces) {
    std::vector<double> y;
    for (std::size_t i = p.begin; i < p.end; ++i)
      if (std::isfinite(it->second[i])) y.push_back(it->second[i]);
    for (std::size_t i = 1; i + 1 < y.size(); ++i) {
      double d = (y[i + 1] - y[i]) - (y[i] - y[i - 1]);
      if (ident::isAngle(s)) d = wrapAngle(y[i + 1] - y[i]) - wrapAngle(y[i] - y[i - 1]);
      d2.push_back(d);
    }
    all.insert(all.end(), y.begin(), y.end());
  }
  if (all.empty()) return kNaN;
  const auto [lo, hi] = std::minmax_element(all.begin(), all.end());
  const double floor = 1e-9 + 1e-6 * (*hi - *lo);
  if (d2.size() < 5) return floor;
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const double m = median(d2);
  for (double& d : d2) d = std::abs(d - m);
  return std::max(floor, 1.4826 * median(d2) / std::sqrt(6.0));
}

double nrmse(const std::vector<double>& y, const std::vector<double>& ys) {
  double mean = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < y.size(); ++i)
    if (std::isfinite(y[i]) && std::isfinite(ys[i])) {
      mean += y[i];
      ++n;
    }
  if (n < 2) return kNaN;
  mean /= static_cast<double>(n);
  double e = 0, d = 0;
  for (std::size_t i = 0; i < y.size(); ++i)
    if (std::isfinite(y[i]) && std::isfinite(ys[i])) {
      e += (y[i] - ys[i]) * (y[i] - ys[i]);
      d += (y[i] - mean) * (y[i] - mean);
    }
  if (d <= 0.0) return kNaN;
  return 100.0 * (1.0 - std::sqrt(e / d));
}

// Continuous angle from a wrapped one (NaN kept), so that fits of yaw are not broken by the +-pi jump.
void unwrapInPlace(std::vector<double>& y, std::size_t begin, std::size_t end) {
  double last = kNaN, offset = 0;
  for (std::size_t i = begin; i < end; ++i) {
    if (!std::isfinite(y[i])) continue;
    const double raw = y[i];
    if (std::isfinite(last)) offset += wrapAngle(raw - last) - (raw - last);
    last = raw;
    y[i] = raw + offset;
  }
}

// ---------------------------------------------------------------- one stage's least-squares problem
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

  std::unique_ptr<Plant> plantAt(const double* xg) const {
    auto p = base->clone();
    for (std::size_t j = 0; j < keys.size(); ++j) p->set(keys[j], xg[j] * scale[j]);
    return p;
  }
  bool run(const Plant& p, std::size_t k, const double* xl, std::vector<double>& out) const {
    const Segment& s = segs[k];
    out.resize((s.end - s.begin) * p.outputs().size());
    return p.simulate(*log, *env, dt, s.warm, s.begin, s.end, free_state ? xl : nullptr, out.data());
  }
  bool residuals(std::size_t k, const double* xg, const double* xl, double* r) const {
    const auto p = plantAt(xg);
    if (!run(*p, k, xl, buf)) return false;
    const std::size_t no = p->outputs().size();
    const auto& it = items[k];
    for (std::size_t i = 0; i < it.size(); ++i) {
      double d = it[i].value - buf[it[i].row * no + static_cast<std::size_t>(it[i].out)];
      if (angle[static_cast<std::size_t>(it[i].slot)]) d = wrapAngle(d);
      r[i] = d * weight[static_cast<std::size_t>(it[i].slot)];
    }
    return true;
  }
  // Sum of squares at xg for all segments (the local states as given).
  double cost(const double* xg, const std::vector<std::vector<double>>& xl) const {
    double c = 0;
    for (std::size_t k = 0; k < segs.size(); ++k) {
      std::vector<double> r(items[k].size());
      if (!residuals(k, xg, xl[k].data(), r.data())) return std::numeric_limits<double>::infinity();
      for (double v : r) c += v * v;
    }
    return c;
  }
  // Unweighted residual RMS and lag-1 autocorrelation per slot.
  void stats(const double* xg, const std::vector<std::vector<double>>& xl, std::vector<double>& rms,
             std::vector<double>& rho) const {
    std::vector<double> sum(signals.size(), 0.0), cnt(signals.size(), 0.0), lag(signals.size(), 0.0);
    for (std::size_t k = 0; k < segs.size(); ++k) {
      std::vector<double> r(items[k].size());
      if (!residuals(k, xg, xl[k].data(), r.data())) continue;
      std::vector<double> last(signals.size(), kNaN);
      for (std::size_t i = 0; i < r.size(); ++i) {
        const auto s = static_cast<std::size_t>(items[k][i].slot);
        const double u = r[i] / weight[s];
        sum[s] += u * u;
        cnt[s] += 1;
        if (std::isfinite(last[s])) lag[s] += u * last[s];
        last[s] = u;
      }
    }
    rms.assign(signals.size(), kNaN);
    rho.assign(signals.size(), 0.0);
    for (std::size_t s = 0; s < sum.size(); ++s) {
      if (cnt[s] <= 0) continue;
      rms[s] = std::sqrt(sum[s] / cnt[s]);
      rho[s] = sum[s] > 0 ? std::clamp(lag[s] / sum[s], 0.0, 0.99) : 0.0;
    }
  }
  std::vector<double> rms(const double* xg, const std::vector<std::vector<double>>& xl) const {
    std::vector<double> r, rho;
    stats(xg, xl, r, rho);
    return r;
  }
};

struct SegmentCost {
  const StageProblem* p;
  std::size_t k;
  bool operator()(double const* const* x, double* r) const {
    return p->residuals(k, p->keys.empty() ? nullptr : x[0], p->free_state ? x[p->keys.empty() ? 0 : 1] : nullptr, r);
  }
};

struct SolveResult {
  int iterations = 0;
  bool usable = false;
  std::vector<double> se;  // per key, relative to scale (NaN when the covariance failed)
};

// Levenberg-Marquardt over the global block xg (bounds from the parameter table) and the segments' states.
SolveResult solve(const StageProblem& sp, std::vector<double>& xg, const std::vector<double>& lower,
                  std::vector<std::vector<double>>& xl, int max_iterations, bool covariance,
                  double function_tolerance = 1e-8) {
  ceres::Problem::Options po;
  ceres::Problem problem(po);
  const bool global = !sp.keys.empty();
  ceres::NumericDiffOptions nd;
  for (std::size_t k = 0; k < sp.segs.size(); ++k) {
    if (sp.items[k].empty()) continue;
    auto* cf = new ceres::DynamicNumericDiffCostFunction<SegmentCost, ceres::FORWARD>(
        new SegmentCost{&sp, k}, ceres::TAKE_OWNERSHIP, nd);
    std::vector<double*> blocks;
    if (global) {
      cf->AddParameterBlock(static_cast<int>(xg.size()));
      blocks.push_back(xg.data());
    }
    if (sp.free_state) {
      cf->AddParameterBlock(static_cast<int>(xl[k].size()));
      blocks.push_back(xl[k].data());
    }
    cf->SetNumResiduals(static_cast<int>(sp.items[k].size()));
    problem.AddResidualBlock(cf, nullptr, blocks);
  }
  SolveResult res;
  if (problem.NumResidualBlocks() == 0) return res;
  if (global)
    for (std::size_t j = 0; j < xg.size(); ++j)
      if (lower[j] > -1e299) problem.SetParameterLowerBound(xg.data(), static_cast<int>(j), lower[j]);
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = sp.free_state ? ceres::DENSE_SCHUR : ceres::DENSE_QR;
  if (sp.free_state && global) {
    auto* ordering = new ceres::ParameterBlockOrdering;
    for (std::size_t k = 0; k < sp.segs.size(); ++k)
      if (!sp.items[k].empty()) ordering->AddElementToGroup(xl[k].data(), 0);
    ordering->AddElementToGroup(xg.data(), 1);
    so.linear_solver_ordering.reset(ordering);
  }
  so.max_num_iterations = max_iterations;
  so.function_tolerance = function_tolerance;
  so.parameter_tolerance = 1e-8;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  const std::clock_t c0 = std::clock();
  ceres::Solve(so, &problem, &summary);
  if (std::getenv("OFFSHORE_GNC_FIT_DEBUG"))
    std::fprintf(stderr, "solve: %zu params, %d residual blocks, %zu iterations, %.2f s, cost %g -> %g\n",
                 xg.size(), problem.NumResidualBlocks(), summary.iterations.size(),
                 double(std::clock() - c0) / CLOCKS_PER_SEC, summary.initial_cost, summary.final_cost);
  res.iterations = static_cast<int>(summary.iterations.size());
  res.usable = summary.IsSolutionUsable();
  res.se.assign(xg.size(), kNaN);
  if (covariance && global && res.usable) {
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    co.null_space_rank = 0;
    co.num_threads = 1;
    ceres::Covariance cov(co);
    const std::vector<std::pair<const double*, const double*>> blocks{{xg.data(), xg.data()}};
    const std::clock_t c1 = std::clock();
    const bool ok = cov.Compute(blocks, &problem);
    if (std::getenv("OFFSHORE_GNC_FIT_DEBUG"))
      std::fprintf(stderr, "covariance: %.2f s\n", double(std::clock() - c1) / CLOCKS_PER_SEC);
    if (ok) {
      std::vector<double> c(xg.size() * xg.size());
      cov.GetCovarianceBlock(xg.data(), xg.data(), c.data());
      for (std::size_t j = 0; j < xg.size(); ++j) res.se[j] = std::sqrt(std::max(0.0, c[j * xg.size() + j]));
    }
  }
  return res;
}

// ---------------------------------------------------------------- the whole fit
class Fit {
 public:
  Fit(FitVehicle v, const std::string& text, const std::string& source, const IdentLog& log, const FitOptions& opt)
      : plant_(ident::makePlant(v, text, source)), start_(plant_->clone()), log_(log), opt_(opt),
        env_(opt.environment) {
    requireRange("dt", opt.dt, 1e-4, 1.0);
    requireRange("segment", opt.segment, 1.0, 1e5);
    requireRange("warmup", opt.warmup, 0.0, 1e4);
    requireRange("max_gap", opt.max_gap, 1e-3, 1e5);
    requireRange("max_rel_se", opt.max_rel_se, 1e-3, 1e3);
    r_.vehicle = v;
    r_.model = plant_->model();
    r_.rows = log.rows();
    if (log.command_names != plant_->commands())
      throw ConfigError(log.source + ": the log's command columns (" + joinKeys(log.command_names) +
                        ") are not the model's (" + joinKeys(plant_->commands()) + ")");
  }

  FitReport run() {
    const std::clock_t c0 = std::clock();
    prepare();
    std::vector<std::string> stages;
    for (const auto& p : plant_->parameters())
      if (std::find(stages.begin(), stages.end(), p.stage) == stages.end()) stages.push_back(p.stage);
    for (const auto& s : stages) {
      const std::clock_t c1 = std::clock();
      fitStage(s);
      r_.stage_cpu_seconds[s] = static_cast<double>(std::clock() - c1) / CLOCKS_PER_SEC;
    }
    const std::clock_t c2 = std::clock();
    series();
    r_.stage_cpu_seconds["validation"] = static_cast<double>(std::clock() - c2) / CLOCKS_PER_SEC;
    r_.parameters = results_;
    r_.cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    return r_;
  }

  // The pieces, noise levels, results table and excitation: what every stage needs first.
  void prepare() {
    pieces_ = findPieces(log_, opt_, r_.messages);
    r_.pieces = pieces_.size();
    if (pieces_.empty())
      throw ConfigError(log_.source + ": no usable stretch of log (at least " + fmt(opt_.min_piece) +
                        " s without a gap or an unknown command): nothing can be simulated");
    for (const auto& p : pieces_) r_.used_rows += p.end - p.begin;
    for (const auto& s : plant_->outputs()) {
      noise_[s] = noiseLevel(log_, s, pieces_);
      spread_[s] = spreadOf(s);
      const std::size_t c = log_.count(s);
      if (c > 0 && c < log_.rows() / 2 && log_.rows() > 10)
        r_.messages.push_back("'" + s + "' has a value in " + std::to_string(c) + " of " +
                              std::to_string(log_.rows()) + " rows (the others are left out of the fit)");
    }
    for (const auto& p : plant_->parameters()) {
      ParameterResult pr;
      pr.param = p;
      pr.start = pr.value = start_->get(p.key);
      results_.push_back(pr);
    }
    for (const auto& p : pieces_) {  // what the commands do to the start model: which dynamics they excite
      const auto x = plant_->excitation(log_, env_, opt_.dt, p.begin, p.end);
      for (const auto& kv : x) {
        auto& v = exc_[kv.first];
        v.resize(log_.rows(), kNaN);
        std::copy(kv.second.begin(), kv.second.end(), v.begin() + static_cast<std::ptrdiff_t>(p.begin));
      }
    }
  }

  // One stage's problem at the start values with the first pass' weights, for comparing optimisers (bench).
  struct Bench {
    StageProblem sp;
    std::vector<double> xg, lower;
    std::vector<std::vector<double>> xl;
  };
  Bench bench(const std::string& stage) {
    prepare();
    Bench b;
    std::vector<std::string> keys;
    const auto segs = segments(stage);
    for (const auto& p : plant_->parameters())  // what model_fit would estimate (excited, not a delay)
      if (p.stage == stage && !p.delay && cannotEstimate(p.group, stage, segs, exc_).empty()) keys.push_back(p.key);
    if (keys.empty()) throw ConfigError("nothing to estimate in stage '" + stage + "' of this model from this log");
    b.sp = problem(stage, segs, keys);
    b.xl = initialStates(b.sp);
    for (std::size_t j = 0; j < keys.size(); ++j) {
      const double v = start_->get(keys[j]);
      const FitParameter& fp = result(keys[j]).param;
      b.xg.push_back(fp.magnitude ? std::abs(v) / b.sp.scale[j] : v / b.sp.scale[j]);
      b.lower.push_back(fp.magnitude ? 0.0 : std::max(-1e300, fp.lower / b.sp.scale[j]));
    }
    reweight(b.sp, b.xg, b.xl, false);
    return b;
  }

 private:
  ParameterResult& result(const std::string& key) {
    for (auto& p : results_)
      if (p.param.key == key) return p;
    throw std::logic_error("unknown parameter " + key);
  }

  std::vector<std::string> stageSignals(const std::string& stage) const {
    std::set<std::string> mine;
    for (const auto& p : plant_->parameters())
      if (p.stage == stage) mine.insert(ident::groupSignal(p.group));
    std::vector<std::string> s;
    for (const auto& o : plant_->outputs()) {
      const bool actuator = o == "rpm" || o == "nozzle";
      // actuator stages fit their own signal only; the hull stage every motion signal
      if ((stage == "hull" && !actuator) || (stage != "hull" && mine.count(o))) s.push_back(o);
    }
    return s;
  }

  std::vector<Segment> segments(const std::string& stage) const {
    std::vector<Segment> segs;
    const bool hull = stage == "hull";
    const double w = plant_->warmup(opt_);
    for (const auto& p : pieces_) {
      const std::size_t b0 = rowAt(log_, log_.t[p.begin] + w, p.begin, p.end);
      if (b0 + 2 >= p.end) continue;
      if (!hull) {
        segs.push_back({p.begin, b0, p.end});
        continue;
      }
      std::size_t b = b0;
      while (b + 2 < p.end) {
        std::size_t e = rowAt(log_, log_.t[b] + opt_.segment, b, p.end);
        if (e >= p.end || log_.t[p.end - 1] - log_.t[e] < 0.5 * opt_.segment) e = p.end;
        const std::size_t warm = w > 0 ? rowAt(log_, log_.t[b] - w, p.begin, b) : b;
        segs.push_back({warm, b, e});
        b = e;
      }
    }
    return segs;
  }

  // What the log must hold for a group, and whether its commands excite it. Empty: fine; else the reason.
  std::string cannotEstimate(const std::string& group, const std::string& stage, const std::vector<Segment>& segs,
                             const std::map<std::string, std::vector<double>>& exc) const {
    const std::string sig = ident::groupSignal(group);
    if (stage != "hull" && !log_.has(sig, 10)) return "the log has no '" + sig + "' column (or fewer than 10 values)";
    if (stage == "hull") {
      const bool pos = log_.has("north", 10) && log_.has("east", 10);
      bool ok = log_.has(sig, 10);
      if (group == "surge" || group == "sway") ok = ok || pos;
      if (group == "yaw") ok = ok || log_.has("yaw_rad", 10);
      if (group == "heave") ok = ok || log_.has("down", 10);
      if (!ok) return "the log measures neither '" + sig + "' nor the position or heading it shows in";
    }
    const auto e = exc.find(group);
    if (e == exc.end()) {  // no force of its own: its motion must be in the log, well above the noise
      if (!log_.has(sig, 10)) return "the log has no '" + sig + "' column to show the motion";
      const auto& y = log_.measured.at(sig);
      double s = 0, s2 = 0, n = 0;
      for (const auto& g : segs)
        for (std::size_t i = g.begin; i < g.end; ++i)
          if (std::isfinite(y[i])) {
            s += y[i];
            s2 += y[i] * y[i];
            n += 1;
          }
      const double sd = n > 1 ? std::sqrt(std::max(0.0, s2 / n - (s / n) * (s / n))) : 0.0;
      const double need = std::max(0.05, 3.0 * noise_.at(sig));
      if (sd < need)
        return "'" + sig + "' varies by only " + fmt(sd) + " (standard deviation; its noise is " +
               fmt(noise_.at(sig)) + ", at least " + fmt(need) +
               " is needed): the log has no such motion to estimate it from";
      return "";
    }
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, mx = 0;
    for (const auto& g : segs)
      for (std::size_t i = g.begin; i < g.end; ++i) {
        const double v = e->second[i];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        mx = std::max(mx, std::abs(v));
      }
    if (!(mx > 0) || hi - lo <= 0.05 * mx) {
      std::string cmds;
      for (Eigen::Index k = 0; k < log_.commands.cols(); ++k) {
        double clo = 1e300, chi = -1e300;
        for (const auto& g : segs)
          for (std::size_t i = g.begin; i < g.end; ++i) {
            clo = std::min(clo, log_.commands(static_cast<Eigen::Index>(i), k));
            chi = std::max(chi, log_.commands(static_cast<Eigen::Index>(i), k));
          }
        cmds += (cmds.empty() ? "" : ", ") + log_.command_names[static_cast<std::size_t>(k)] +
                (chi - clo < 1e-9 ? " constant at " + fmt(clo) : " " + fmt(clo) + ".." + fmt(chi));
      }
      return "its input (" + std::string(stage == "hull" ? "force" : "set-point") +
             ") does not change over the log (commands: " + cmds + "), so nothing in the log excites it";
    }
    return "";
  }

  void fitStage(const std::string& stage) {
    std::vector<Segment> segs = segments(stage);
    std::vector<std::string> keys, delays, groups;
    for (const auto& p : plant_->parameters())
      if (p.stage == stage && std::find(groups.begin(), groups.end(), p.group) == groups.end())
        groups.push_back(p.group);
    if (segs.empty()) {
      for (const auto& g : groups) notEstimated(g, stage, "the log has no stretch long enough after the warm-up");
      return;
    }
    for (const auto& g : groups) {
      const std::string why = opt_.estimate ? cannotEstimate(g, stage, segs, exc_) : "validation only";
      if (!why.empty()) {
        notEstimated(g, stage, why);
        continue;
      }
      for (const auto& p : plant_->parameters()) {
        if (p.stage != stage || p.group != g) continue;
        if (std::find(opt_.fixed.begin(), opt_.fixed.end(), p.key) != opt_.fixed.end()) {
          result(p.key).note = "kept fixed (--fix)";
          continue;
        }
        (p.delay ? delays : keys).push_back(p.key);
      }
    }
    StageProblem sp = problem(stage, segs, keys);
    if (sp.signals.empty()) return;
    const bool any = !keys.empty() || !delays.empty();
    if (!any && !sp.free_state) {
      stageSegments(sp, std::vector<std::vector<double>>(segs.size()));
      return;
    }
    std::vector<std::vector<double>> xl = initialStates(sp);
    std::vector<double> xg(keys.size(), 1.0), lower(keys.size());
    for (std::size_t j = 0; j < keys.size(); ++j) {
      const double v = start_->get(keys[j]);
      const FitParameter& fp = result(keys[j]).param;
      xg[j] = fp.magnitude ? std::abs(v) / sp.scale[j] : v / sp.scale[j];
      lower[j] = fp.magnitude ? 0.0 : fp.lower / sp.scale[j];
    }
    // Pass 1 balances the signals by their misfit at the start (so that a drifting track does not swamp the
    // velocities), pass 2 weights them by the residuals of pass 1: each signal's own noise level.
    reweight(sp, xg, xl, false);
    for (const auto& d : delays) scanDelay(sp, d, xg, xl, false);
    SolveResult sr = solve(sp, xg, lower, xl, opt_.max_iterations / 2, false, 1e-5);
    r_.iterations += sr.iterations;
    reweight(sp, xg, xl, true);
    sr = solve(sp, xg, lower, xl, opt_.max_iterations, delays.empty());
    r_.iterations += sr.iterations;
    if (!delays.empty()) {
      // A delay trades against the lags around it: walk it step by step while the cost with the other
      // coefficients re-fitted at each step (the profile) falls, then take the standard errors there.
      for (const auto& d : delays) profileDelay(sp, d, xg, lower, xl);
      sr = solve(sp, xg, lower, xl, opt_.max_iterations, true);
      r_.iterations += sr.iterations;
    }
    // A coefficient the log determines only loosely is not an estimate: keep the start value, say why, refit.
    std::vector<std::string> loose;
    for (std::size_t j = 0; j < keys.size(); ++j) {
      const double rel = sr.se[j] / std::max(std::abs(xg[j]), 1e-12);
      if (!std::isfinite(sr.se[j]) || rel > opt_.max_rel_se) loose.push_back(keys[j]);
    }
    if (!loose.empty()) {
      for (const auto& k : loose) {
        const std::size_t j = static_cast<std::size_t>(std::find(keys.begin(), keys.end(), k) - keys.begin());
        notEstimatedKey(k, std::isfinite(sr.se[j])
                               ? "this log determines it only to +-" + fmt(100.0 * sr.se[j] / std::abs(xg[j]), 2) +
                                     " % (relative standard error, limit " + fmt(100.0 * opt_.max_rel_se, 2) +
                                     " %): too little of its effect is in the log"
                               : "its standard error cannot be computed (the log does not determine it)");
      }
      std::vector<std::string> keep;
      std::vector<double> xk, lk;
      for (std::size_t j = 0; j < keys.size(); ++j)
        if (std::find(loose.begin(), loose.end(), keys[j]) == loose.end()) {
          keep.push_back(keys[j]);
          xk.push_back(xg[j]);
          lk.push_back(lower[j]);
        }
      keys = keep;
      xg = xk;
      lower = lk;
      const auto noise = sp.weight;
      sp = problem(stage, segs, keys);
      sp.weight = noise;
      sr = solve(sp, xg, lower, xl, opt_.max_iterations, true);
      r_.iterations += sr.iterations;
    }
    for (std::size_t j = 0; j < keys.size(); ++j) {
      ParameterResult& pr = result(keys[j]);
      const double v = xg[j] * sp.scale[j];
      pr.value = pr.param.magnitude ? (pr.start < 0 ? -v : v) : v;
      pr.se = sr.se[j] * sp.scale[j];
      pr.estimated = true;
      plant_->set(keys[j], v);
    }
    for (const auto& d : delays) {
      ParameterResult& pr = result(d);
      pr.value = plant_->get(d);
      pr.se = opt_.dt / std::sqrt(12.0);
      pr.estimated = true;
      pr.note = "scanned on the " + fmt(opt_.dt) + " s simulation step (standard error: its resolution)";
    }
    if (!sr.usable && !keys.empty())
      r_.messages.push_back("stage '" + stage + "': the optimiser did not reach a usable solution");
    stageSegments(sp, xl);
  }

  StageProblem problem(const std::string& stage, const std::vector<Segment>& segs,
                       const std::vector<std::string>& keys) {
    StageProblem sp;
    sp.log = &log_;
    sp.env = &env_;
    sp.dt = opt_.dt;
    sp.base = plant_.get();
    sp.keys = keys;
    for (const auto& k : keys) {
      const double v = start_->get(k);
      sp.scale.push_back(std::abs(v) > 0 ? std::abs(v) : result(k).param.nominal);
    }
    sp.free_state = stage == "hull";
    sp.segs = segs;
    const auto& outs = plant_->outputs();
    for (const auto& s : stageSignals(stage)) {
      if (!log_.has(s)) continue;
      sp.signals.push_back(s);
      sp.angle.push_back(ident::isAngle(s) ? 1 : 0);
      sp.weight.push_back(1.0 / noise_.at(s));
    }
    sp.items.resize(segs.size());
    for (std::size_t k = 0; k < segs.size(); ++k)
      for (std::size_t i = segs[k].begin; i < segs[k].end; ++i)
        for (std::size_t s = 0; s < sp.signals.size(); ++s) {
          const double v = log_.measured.at(sp.signals[s])[i];
          if (!std::isfinite(v)) continue;
          const int o = static_cast<int>(std::find(outs.begin(), outs.end(), sp.signals[s]) - outs.begin());
          sp.items[k].push_back({i - segs[k].begin, o, static_cast<int>(s), v});
        }
    return sp;
  }

  // A segment's initial state from the log: the measured value at its first row, else the nearest one within
  // the segment, else (velocities) from the track, else 0.
  std::vector<std::vector<double>> initialStates(const StageProblem& sp) const {
    std::vector<std::vector<double>> xl(sp.segs.size());
    if (!sp.free_state) return xl;
    const auto& names = plant_->freeState();
    for (std::size_t k = 0; k < sp.segs.size(); ++k) {
      const Segment& g = sp.segs[k];
      for (const auto& n : names) {
        double v = kNaN;
        const auto it = log_.measured.find(n);
        if (it != log_.measured.end())
          for (std::size_t i = g.begin; i < g.end && !std::isfinite(v); ++i) v = it->second[i];
        if (!std::isfinite(v)) v = trackVelocity(n, g.begin, g.end);
        xl[k].push_back(std::isfinite(v) ? v : 0.0);
      }
    }
    return xl;
  }

  // u, v or r from the logged track and heading over the first 2 s of a segment (when not logged).
  double trackVelocity(const std::string& n, std::size_t b, std::size_t e) const {
    if (!log_.has("north") || !log_.has("east") || !log_.has("yaw_rad")) return kNaN;
    const auto &N = log_.measured.at("north"), &E = log_.measured.at("east"), &Y = log_.measured.at("yaw_rad");
    auto ok = [&](std::size_t i) { return std::isfinite(N[i]) && std::isfinite(E[i]) && std::isfinite(Y[i]); };
    std::size_t i = b;
    while (i < e && !ok(i)) ++i;
    if (i >= e) return kNaN;
    std::size_t j = i;
    for (std::size_t k = i + 1; k < e && log_.t[k] <= log_.t[i] + 2.0; ++k)
      if (ok(k)) j = k;
    if (j == i) return kNaN;
    const double dt = log_.t[j] - log_.t[i];
    const double vn = (N[j] - N[i]) / dt, ve = (E[j] - E[i]) / dt, c = std::cos(Y[i]), s = std::sin(Y[i]);
    if (n == "u") return c * vn + s * ve;
    if (n == "v") return -s * vn + c * ve;
    if (n == "r_rad_s") return wrapAngle(Y[j] - Y[i]) / dt;
    return kNaN;
  }

  // Weights = 1 / residual level. With `correlated`, each signal's level is raised by its residuals' lag-1
  // autocorrelation rho (AR(1) variance inflation sqrt((1 + rho) / (1 - rho))): slowly wandering errors such
  // as the GPS-compass' do not count as many independent samples, so that the standard errors stay honest.
  void reweight(StageProblem& sp, const std::vector<double>& xg, const std::vector<std::vector<double>>& xl,
                bool correlated) {
    std::vector<double> rms, rho;
    sp.stats(xg.data(), xl, rms, rho);
    for (std::size_t s = 0; s < sp.signals.size(); ++s) {
      // a noise-free signal (simulated, or quantised) must not weigh a million times the others
      const double floor = std::max(1e-3 * noise_.at(sp.signals[s]), 1e-4 * spread_.at(sp.signals[s]));
      const double inflate = correlated ? std::sqrt((1.0 + rho[s]) / (1.0 - rho[s])) : 1.0;
      if (std::isfinite(rms[s])) sp.weight[s] = 1.0 / (std::max(rms[s], floor) * inflate);
    }
  }

  void profileDelay(StageProblem& sp, const std::string& key, std::vector<double>& xg,
                    const std::vector<double>& lower, std::vector<std::vector<double>>& xl) {
    double best = sp.cost(xg.data(), xl);
    int direction = 0;  // keep walking the way that helped
    for (int step = 0; step < 40; ++step) {
      const double cur = plant_->get(key);
      bool moved = false;
      for (int dir : {direction ? direction : -1, direction ? 0 : 1}) {
        if (dir == 0 || cur + dir * opt_.dt < -1e-12) continue;
        plant_->set(key, std::max(0.0, cur + dir * opt_.dt));
        std::vector<double> g = xg;
        std::vector<std::vector<double>> l = xl;
        r_.iterations += solve(sp, g, lower, l, opt_.max_iterations / 2, false, 1e-6).iterations;
        const double c = sp.cost(g.data(), l);
        if (c < best) {
          best = c;
          xg = g;
          xl = l;
          direction = dir;
          moved = true;
          break;
        }
        plant_->set(key, cur);
      }
      if (!moved) break;
    }
  }

  // Standard deviation of a measured signal over the pieces (0 when not logged).
  double spreadOf(const std::string& s) const {
    const auto it = log_.measured.find(s);
    if (it == log_.measured.end()) return 0.0;
    double sum = 0, sum2 = 0, n = 0;
    for (const auto& p : pieces_)
      for (std::size_t i = p.begin; i < p.end; ++i)
        if (std::isfinite(it->second[i])) {
          sum += it->second[i];
          sum2 += it->second[i] * it->second[i];
          n += 1;
        }
    return n > 1 ? std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n))) : 0.0;
  }

  // A delay by scanning the step grid (the simulated delay is piecewise constant in it, so no gradient).
  void scanDelay(StageProblem& sp, const std::string& key, const std::vector<double>& xg,
                 const std::vector<std::vector<double>>& xl, bool fine) {
    const double cur = plant_->get(key);
    std::vector<double> grid;
    if (!fine) {
      const double step = std::max(opt_.dt, opt_.delay_max / 20.0);
      for (double d = 0; d <= opt_.delay_max + 1e-9; d += step) grid.push_back(d);
    }
    const double lo = std::max(0.0, cur - (fine ? 3 : 0) * opt_.dt), hi = cur + (fine ? 3 : 0) * opt_.dt;
    for (double d = lo; d <= hi + 1e-9; d += opt_.dt) grid.push_back(d);
    double best = cur, best_cost = std::numeric_limits<double>::infinity();
    for (double d : grid) {
      plant_->set(key, d);
      const double c = sp.cost(xg.data(), xl);
      if (c < best_cost) {
        best_cost = c;
        best = d;
      }
    }
    if (!fine) {  // refine around the coarse minimum
      for (double d = std::max(0.0, best - std::max(opt_.dt, opt_.delay_max / 20.0)); d <= best + opt_.delay_max / 20.0;
           d += opt_.dt) {
        plant_->set(key, d);
        const double c = sp.cost(xg.data(), xl);
        if (c < best_cost) {
          best_cost = c;
          best = d;
        }
      }
    }
    plant_->set(key, best);
  }

  void notEstimated(const std::string& group, const std::string& stage, const std::string& why) {
    std::vector<std::string> keys;
    for (const auto& p : plant_->parameters())
      if (p.stage == stage && p.group == group) keys.push_back(p.key);
    for (const auto& k : keys) result(k).note = why;
    if (why != "validation only")
      r_.messages.push_back(joinKeys(keys) + " (" + group + "): not estimated, kept at the start values: " + why);
  }
  void notEstimatedKey(const std::string& key, const std::string& why) {
    ParameterResult& pr = result(key);
    pr.note = why;
    pr.value = pr.start;
    r_.messages.push_back(key + " (" + pr.param.group + "): not estimated, kept at the start value " +
                          fmt(pr.start, 6) + ": " + why);
  }

  // The simulations the stage minimised, kept per row for the fits and plots; final noise levels.
  void stageSegments(StageProblem& sp, const std::vector<std::vector<double>>& xl) {
    sp.base = plant_.get();  // the estimates are in plant_ now
    sp.keys.clear();
    sp.scale.clear();
    const auto& outs = plant_->outputs();
    const auto rms = sp.rms(nullptr, xl);
    for (std::size_t s = 0; s < sp.signals.size(); ++s) fit_noise_[sp.signals[s]] = rms[s];
    std::vector<double> buf;
    for (std::size_t k = 0; k < sp.segs.size(); ++k) {
      if (!sp.run(*plant_, k, sp.free_state ? xl[k].data() : nullptr, buf)) continue;
      for (const auto& s : sp.signals) {
        auto& v = seg_[s];
        v.resize(log_.rows(), kNaN);
        const std::size_t o = static_cast<std::size_t>(std::find(outs.begin(), outs.end(), s) - outs.begin());
        for (std::size_t i = sp.segs[k].begin; i < sp.segs[k].end; ++i)
          v[i] = buf[(i - sp.segs[k].begin) * outs.size() + o];
      }
    }
    if (sp.free_state) {
      r_.segments = sp.segs.size();
      for (const auto& pc : pieces_)  // each piece's first segment: the open-loop run starts from its state
        for (std::size_t k = 0; k < sp.segs.size(); ++k)
          if (sp.segs[k].begin >= pc.begin && sp.segs[k].begin < pc.end) {
            start_state_[pc.begin] = {sp.segs[k].begin, xl[k]};
            break;
          }
    }
  }

  void series() {
    FitSeries& fs = r_.series;
    fs.t = log_.t;
    const auto& outs = plant_->outputs();
    for (const auto& s : outs) {
      if (!log_.has(s)) continue;
      fs.measured[s] = log_.measured.at(s);
      fs.open_loop[s].assign(log_.rows(), kNaN);
    }
    std::vector<double> buf;
    for (const auto& p : pieces_) {
      // from the state the first segment estimated (after the warm-up), else from the first measured state
      const auto st = start_state_.find(p.begin);
      const std::size_t b = st == start_state_.end() ? p.begin : st->second.first;
      buf.resize((p.end - b) * outs.size());
      if (!plant_->simulate(log_, env_, opt_.dt, p.begin, b, p.end,
                            st == start_state_.end() ? nullptr : st->second.second.data(), buf.data())) {
        r_.messages.push_back("the open-loop run from t " + fmt(log_.t[p.begin], 6) + " s did not stay finite");
        continue;
      }
      for (std::size_t o = 0; o < outs.size(); ++o) {
        if (!fs.open_loop.count(outs[o])) continue;
        auto& v = fs.open_loop[outs[o]];
        for (std::size_t i = b; i < p.end; ++i) v[i] = buf[(i - b) * outs.size() + o];
      }
    }
    for (const auto& s : outs) {
      if (!fs.measured.count(s)) continue;
      std::vector<double>& m = fs.measured[s];
      std::vector<double>& ol = fs.open_loop[s];
      auto& sg = seg_[s];
      sg.resize(log_.rows(), kNaN);
      if (ident::isAngle(s)) {
        for (const auto& p : pieces_) {
          unwrapInPlace(m, p.begin, p.end);
          unwrapInPlace(ol, p.begin, p.end);
        }
        // segment yaw onto the measured branch
        for (std::size_t i = 0; i < sg.size(); ++i)
          if (std::isfinite(sg[i]) && std::isfinite(m[i]))
            sg[i] = m[i] + wrapAngle(sg[i] - m[i]);
      }
      fs.segments[s] = sg;
      SignalFit f;
      f.signal = s;
      f.samples = log_.count(s);
      f.noise = fit_noise_.count(s) ? fit_noise_[s] : kNaN;
      f.segment_fit = nrmse(m, sg);
      f.open_loop_fit = nrmse(m, ol);
      f.motion = !(spread_.at(s) <= 3.0 * (std::isfinite(f.noise) ? f.noise : noise_.at(s)));
      r_.fits.push_back(f);
    }
  }

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

}  // namespace

struct ident::StageBench::Impl {
  IdentLog log;
  std::unique_ptr<Fit> fit;
  Fit::Bench b;
};

ident::StageBench::StageBench(FitVehicle v, const std::string& text, const std::string& source, IdentLog log,
                              const FitOptions& opt, const std::string& stage)
    : impl_(std::make_unique<Impl>()) {
  impl_->log = std::move(log);
  impl_->fit = std::make_unique<Fit>(v, text, source, impl_->log, opt);
  impl_->b = impl_->fit->bench(stage);
}
ident::StageBench::~StageBench() = default;
int ident::StageBench::globals() const { return static_cast<int>(impl_->b.xg.size()); }
int ident::StageBench::locals() const { return impl_->b.sp.free_state ? static_cast<int>(impl_->b.xl[0].size()) : 0; }
int ident::StageBench::segments() const { return static_cast<int>(impl_->b.sp.segs.size()); }
std::vector<int> ident::StageBench::residualCounts() const {
  std::vector<int> n;
  for (const auto& it : impl_->b.sp.items) n.push_back(static_cast<int>(it.size()));
  return n;
}
std::vector<double> ident::StageBench::x0() const {
  std::vector<double> x = impl_->b.xg;
  for (const auto& l : impl_->b.xl) x.insert(x.end(), l.begin(), l.end());
  return x;
}
std::vector<double> ident::StageBench::lower() const {
  std::vector<double> x = impl_->b.lower;
  x.resize(x.size() + static_cast<std::size_t>(segments() * locals()), -1e300);
  return x;
}
bool ident::StageBench::residuals(const double* x, double* r) const {
  const auto& sp = impl_->b.sp;
  const int ng = globals(), nl = locals();
  for (std::size_t k = 0; k < sp.segs.size(); ++k) {
    if (!sp.residuals(k, x, x + ng + static_cast<int>(k) * nl, r)) return false;
    r += sp.items[k].size();
  }
  return true;
}
int ident::StageBench::solveCeres(std::vector<double>& x, int max_iterations, double* final_cost) {
  auto& b = impl_->b;
  const int ng = globals(), nl = locals();
  std::copy(x.begin(), x.begin() + ng, b.xg.begin());
  for (std::size_t k = 0; k < b.xl.size(); ++k)
    std::copy(x.begin() + ng + static_cast<long>(k) * nl, x.begin() + ng + static_cast<long>(k + 1) * nl, b.xl[k].begin());
  const SolveResult r = solve(b.sp, b.xg, b.lower, b.xl, max_iterations, false);
  x = x0();
  if (final_cost) *final_cost = 0.5 * b.sp.cost(b.xg.data(), b.xl);
  return r.iterations;
}

double nrmseFit(const std::vector<double>& measured, const std::vector<double>& simulated) {
  return nrmse(measured, simulated);
}

FitReport fitModel(FitVehicle v, const std::string& text, const std::string& source, const IdentLog& log,
                   const FitOptions& opt) {
  Fit f(v, text, source, log, opt);
  return f.run();
}

}  // namespace identification
}  // namespace offshore_gnc
