// The whole fit (ident_fit.h): the stages in order (each estimating what the log excites, delays scanned, loose
// coefficients kept at their start values) and the validation series.
#include <algorithm>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include "ident_fit.h"
#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace identification {
namespace ident {

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

Fit::Fit(FitVehicle v, const std::string& text, const std::string& source, const IdentLog& log, const FitOptions& opt)
    : plant_(makePlant(v, text, source)), start_(plant_->clone()), log_(log), opt_(opt), env_(opt.environment) {
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

FitReport Fit::run() {
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
void Fit::prepare() {
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

Fit::Bench Fit::bench(const std::string& stage) {
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

ParameterResult& Fit::result(const std::string& key) {
  for (auto& p : results_)
    if (p.param.key == key) return p;
  throw std::logic_error("unknown parameter " + key);
}

void Fit::fitStage(const std::string& stage) {
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

void Fit::profileDelay(StageProblem& sp, const std::string& key, std::vector<double>& xg,
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

// A delay by scanning the step grid (the simulated delay is piecewise constant in it, so no gradient).
void Fit::scanDelay(StageProblem& sp, const std::string& key, const std::vector<double>& xg,
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

void Fit::notEstimated(const std::string& group, const std::string& stage, const std::string& why) {
  std::vector<std::string> keys;
  for (const auto& p : plant_->parameters())
    if (p.stage == stage && p.group == group) keys.push_back(p.key);
  for (const auto& k : keys) result(k).note = why;
  if (why != "validation only")
    r_.messages.push_back(joinKeys(keys) + " (" + group + "): not estimated, kept at the start values: " + why);
}

void Fit::notEstimatedKey(const std::string& key, const std::string& why) {
  ParameterResult& pr = result(key);
  pr.note = why;
  pr.value = pr.start;
  r_.messages.push_back(key + " (" + pr.param.group + "): not estimated, kept at the start value " +
                        fmt(pr.start, 6) + ": " + why);
}

// The simulations the stage minimised, kept per row for the fits and plots; final noise levels.
void Fit::stageSegments(StageProblem& sp, const std::vector<std::vector<double>>& xl) {
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

void Fit::series() {
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

}  // namespace ident
}  // namespace identification
}  // namespace offshore_gnc
