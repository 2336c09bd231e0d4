// One stage's least-squares problem (ident_fit.h): multiple shooting over the log's segments, the residuals
// weighted per signal, and its Levenberg-Marquardt solution with Ceres.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <set>

#include <ceres/ceres.h>

#include "ident_fit.h"
#include "offshore_gnc/common/angles.h"

namespace offshore_gnc {
namespace identification {
namespace ident {

std::unique_ptr<Plant> StageProblem::plantAt(const double* xg) const {
  auto p = base->clone();
  for (std::size_t j = 0; j < keys.size(); ++j) p->set(keys[j], xg[j] * scale[j]);
  return p;
}

bool StageProblem::run(const Plant& p, std::size_t k, const double* xl, std::vector<double>& out) const {
  const Segment& s = segs[k];
  out.resize((s.end - s.begin) * p.outputs().size());
  return p.simulate(*log, *env, dt, s.warm, s.begin, s.end, free_state ? xl : nullptr, out.data());
}

bool StageProblem::residuals(std::size_t k, const double* xg, const double* xl, double* r) const {
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
double StageProblem::cost(const double* xg, const std::vector<std::vector<double>>& xl) const {
  double c = 0;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    std::vector<double> r(items[k].size());
    if (!residuals(k, xg, xl[k].data(), r.data())) return std::numeric_limits<double>::infinity();
    for (double v : r) c += v * v;
  }
  return c;
}

// Unweighted residual RMS and lag-1 autocorrelation per slot.
void StageProblem::stats(const double* xg, const std::vector<std::vector<double>>& xl, std::vector<double>& rms,
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

std::vector<double> StageProblem::rms(const double* xg, const std::vector<std::vector<double>>& xl) const {
  std::vector<double> r, rho;
  stats(xg, xl, r, rho);
  return r;
}

struct SegmentCost {
  const StageProblem* p;
  std::size_t k;
  bool operator()(double const* const* x, double* r) const {
    return p->residuals(k, p->keys.empty() ? nullptr : x[0], p->free_state ? x[p->keys.empty() ? 0 : 1] : nullptr, r);
  }
};

// Levenberg-Marquardt over the global block xg (bounds from the parameter table) and the segments' states.
SolveResult solve(const StageProblem& sp, std::vector<double>& xg, const std::vector<double>& lower,
                  std::vector<std::vector<double>>& xl, int max_iterations, bool covariance,
                  double function_tolerance) {
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

std::vector<std::string> Fit::stageSignals(const std::string& stage) const {
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

StageProblem Fit::problem(const std::string& stage, const std::vector<Segment>& segs,
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
std::vector<std::vector<double>> Fit::initialStates(const StageProblem& sp) const {
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
double Fit::trackVelocity(const std::string& n, std::size_t b, std::size_t e) const {
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
void Fit::reweight(StageProblem& sp, const std::vector<double>& xg, const std::vector<std::vector<double>>& xl,
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

}  // namespace ident
}  // namespace identification
}  // namespace offshore_gnc
