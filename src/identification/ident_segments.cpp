// Segmentation (ident_fit.h): the log cut into pieces and segments, the signals' noise and spread, and whether a log
// can estimate a group of parameters at all.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "ident_fit.h"
#include "offshore_gnc/common/angles.h"

namespace offshore_gnc {
namespace identification {
namespace ident {

std::string fmt(double v, int precision) {
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

std::vector<Segment> Fit::segments(const std::string& stage) const {
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
std::string Fit::cannotEstimate(const std::string& group, const std::string& stage, const std::vector<Segment>& segs,
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

// Standard deviation of a measured signal over the pieces (0 when not logged).
double Fit::spreadOf(const std::string& s) const {
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

}  // namespace ident
}  // namespace identification
}  // namespace offshore_gnc
