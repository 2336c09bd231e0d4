// Model identification by multiple shooting with Ceres (see identification.h and docs/model-identification.md):
// the public entry points; the fit itself is ident_fit.h's (segmentation, the stage problem, the orchestration).
#include "offshore_gnc/identification/identification.h"

#include <algorithm>

#include "ident_fit.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace identification {

using ident::Fit;
using ident::SolveResult;

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
  return ident::nrmse(measured, simulated);
}

FitReport fitModel(FitVehicle v, const std::string& text, const std::string& source, const IdentLog& log,
                   const FitOptions& opt) {
  Fit f(v, text, source, log, opt);
  return f.run();
}

}  // namespace identification
}  // namespace offshore_gnc
