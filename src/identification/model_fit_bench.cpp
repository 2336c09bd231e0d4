// C API over one stage of the identification (ident::StageBench), for bench/model_fit.sh: SciPy's least_squares
// (ctypes) and Ceres solve exactly the same residuals, the models' own simulation, from the same start.
#include <cstring>
#include <exception>
#include <memory>
#include <string>

#include "ident_plant.h"
#include "offshore_gnc/models/csv_table.h"
#include "offshore_gnc/identification/ident_log.h"

using namespace offshore_gnc::models;
using namespace offshore_gnc::identification;


extern "C" {

// NULL on error, with the message in err.
void* ofg_fit_open(const char* vehicle, const char* params, const char* log, const char* stage, char* err, int errlen) {
  try {
    const FitVehicle v = fitVehicleFromName(vehicle);
    const std::string text = readTextFile(params);
    IdentLog l = readIdentLogCsv(log, fitCommandColumns(v, text, params));
    return new ident::StageBench(v, text, params, std::move(l), FitOptions(), stage);
  } catch (const std::exception& e) {
    std::strncpy(err, e.what(), static_cast<std::size_t>(errlen - 1));
    err[errlen - 1] = 0;
    return nullptr;
  }
}

void ofg_fit_close(void* h) { delete static_cast<ident::StageBench*>(h); }

// globals, locals per segment, segments; residual count of each segment into counts (size segments)
void ofg_fit_sizes(void* h, int* globals, int* locals, int* segments) {
  const auto* b = static_cast<ident::StageBench*>(h);
  *globals = b->globals();
  *locals = b->locals();
  *segments = b->segments();
}

void ofg_fit_counts(void* h, int* counts) {
  const auto c = static_cast<ident::StageBench*>(h)->residualCounts();
  std::copy(c.begin(), c.end(), counts);
}

void ofg_fit_start(void* h, double* x, double* lower) {
  const auto* b = static_cast<ident::StageBench*>(h);
  const auto x0 = b->x0(), lo = b->lower();
  std::copy(x0.begin(), x0.end(), x);
  std::copy(lo.begin(), lo.end(), lower);
}

int ofg_fit_residuals(void* h, const double* x, double* r) {
  return static_cast<ident::StageBench*>(h)->residuals(x, r) ? 1 : 0;
}

// Ceres (as model_fit runs it) from x; x is overwritten with the solution. Returns the iterations.
int ofg_fit_ceres(void* h, double* x, int n, int max_iterations, double* final_cost) {
  std::vector<double> v(x, x + n);
  const int it = static_cast<ident::StageBench*>(h)->solveCeres(v, max_iterations, final_cost);
  std::copy(v.begin(), v.end(), x);
  return it;
}
}
