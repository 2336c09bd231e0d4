# Model identification: model_fit on a 10-min simulated GPS-compass log (hidden coefficients 30 % off), and its hull stage by Ceres vs SciPy least_squares on the same residuals
# Usage: ./scripts/bench model_fit [DURATION_S]   (default 600)
# 1. model_manoeuvre (standard plan) -> sim_log (the simulators' UsvSimulation: GPS-compass noise, rpm noise
#    5 rpm) on a boat with X_u, X_uu, X_udot, N_r, N_rr, N_rdot and eq. 3.24's coefficients 30 % off the config's.
# 2. model_fit from the config: wall and CPU time, the recovered coefficients' errors, the fits.
# 3. The hull stage (Table 3.4, multiple shooting) alone from the config's coefficients (actuators as fitted):
#    Ceres (what model_fit uses) vs SciPy least_squares (trf, the sparse Jacobian pattern given, 2-point
#    differences), both calling the same C++ residuals through liboffshore_gnc_model_fit_bench.so.
# Last line: one JSON object.
set -euo pipefail
cd "$REPO"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
BIN="$WS/devel/lib/offshore_gnc" LIB="$WS/devel/lib/liboffshore_gnc_model_fit_bench.so" \
  /usr/bin/python3 - "$work" "${1:-600}" <<'PY'
import ctypes, json, os, re, resource, subprocess, sys, time
import numpy as np
from scipy.optimize import least_squares
from scipy.sparse import lil_matrix

work, duration = sys.argv[1], sys.argv[2]
BIN, LIB = os.environ["BIN"], os.environ["LIB"]
USV = "config/models/usv.yaml"
factors = {"X_u": 1.3, "X_uu": 1.3, "X_udot": 0.7, "N_r": 0.7, "N_rr": 1.3, "N_rdot": 1.3}
rpm = {"rpm_num": [0.317 * 1.3, 2.793 * 1.3, 1.828 * 1.3], "rpm_den": [1.0, 3.499 * 1.3, 1.828 * 1.3]}
text = open(USV).read()
truth = {}
for k, f in factors.items():
    truth[k] = float(re.search(r"^%s:\s*(\S+)" % k, text, re.M).group(1)) * f
    text = re.sub(r"^%s:.*$" % k, "%s: %r" % (k, truth[k]), text, flags=re.M)
for k, v in rpm.items():
    text = re.sub(r"^%s:.*$" % k, "%s: %s" % (k, v), text, flags=re.M)
    for i, x in enumerate(v):
        truth["%s[%d]" % (k, i)] = x
open(work + "/true.yaml", "w").write(text)
run = lambda *a: subprocess.run(list(a), check=True, stdout=subprocess.PIPE, text=True).stdout
run(BIN + "/model_manoeuvre", "--vehicle", "usv", "--params", USV, "--duration", duration, "--output", work + "/cmd.csv")
run(BIN + "/sim_log", "--vehicle", "usv", "--params", work + "/true.yaml", "--input", work + "/cmd.csv",
    "--output", work + "/log.csv", "--rpm-sigma", "5", "--seed", "5")

t0, c0 = time.time(), resource.getrusage(resource.RUSAGE_CHILDREN)
out = run(BIN + "/model_fit", "--vehicle", "usv", "--params", USV, "--input", work + "/log.csv",
          "--output", work + "/fit.yaml", "--report", work + "/rep", "--no-plots")
wall = time.time() - t0
c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
print(out)
rep = json.load(open(work + "/rep/fit.json"))
err = {p["key"]: round(100 * abs(abs(p["value"]) - abs(truth[p["key"]])) / abs(truth[p["key"]]), 2)
       for p in rep["parameters"] if p["estimated"] and p["key"] in truth}
fits = {f["signal"]: round(min(f["segment_fit_pct"], f["open_loop_fit_pct"]), 1) for f in rep["fits"] if f["motion"]}

# the hull stage alone: the config's hull coefficients, the actuators as fitted
fitted = open(work + "/fit.yaml").read()
start = open(USV).read()
for k in ("rpm_num", "rpm_den", "nozzle_delay", "nozzle_time_constant"):
    start = re.sub(r"^%s:.*$" % k, re.search(r"^%s:.*$" % k, fitted, re.M).group(0), start, flags=re.M)
open(work + "/start_hull.yaml", "w").write(start)
lib = ctypes.CDLL(LIB)
lib.ofg_fit_open.restype = ctypes.c_void_p
lib.ofg_fit_open.argtypes = [ctypes.c_char_p] * 4 + [ctypes.c_char_p, ctypes.c_int]
for f, nargs in (("ofg_fit_close", 1), ("ofg_fit_sizes", 4), ("ofg_fit_counts", 2), ("ofg_fit_start", 3),
                 ("ofg_fit_residuals", 3)):
    getattr(lib, f).argtypes = [ctypes.c_void_p] * nargs
lib.ofg_fit_ceres.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_void_p]
errbuf = ctypes.create_string_buffer(1000)
h = lib.ofg_fit_open(b"usv", (work + "/start_hull.yaml").encode(), (work + "/log.csv").encode(), b"hull", errbuf, 1000)
if not h:
    sys.exit("ofg_fit_open: " + errbuf.value.decode())
ng, nl, ns = ctypes.c_int(), ctypes.c_int(), ctypes.c_int()
lib.ofg_fit_sizes(h, ctypes.byref(ng), ctypes.byref(nl), ctypes.byref(ns))
ng, nl, ns = ng.value, nl.value, ns.value
counts = np.zeros(ns, dtype=np.int32)
lib.ofg_fit_counts(h, counts.ctypes.data)
n, m = ng + nl * ns, int(counts.sum())
x0, lower = np.zeros(n), np.zeros(n)
lib.ofg_fit_start(h, x0.ctypes.data, lower.ctypes.data)
lower[lower < -1e299] = -np.inf

xc, cost_c = x0.copy(), ctypes.c_double()
p0 = time.process_time()
it_c = lib.ofg_fit_ceres(h, xc.ctypes.data, n, 60, ctypes.byref(cost_c))
ceres_s = time.process_time() - p0

r = np.zeros(m)
def fun(x):
    x = np.ascontiguousarray(x, dtype=float)
    if not lib.ofg_fit_residuals(h, x.ctypes.data, r.ctypes.data):
        return np.full(m, 1e6)
    return r.copy()
S = lil_matrix((m, n), dtype=int)
row = 0
for k in range(ns):
    S[row:row + counts[k], :ng] = 1
    S[row:row + counts[k], ng + k * nl:ng + (k + 1) * nl] = 1
    row += counts[k]
p0 = time.process_time()
sol = least_squares(fun, x0, jac_sparsity=S.tocsr(), bounds=(lower, np.inf), method="trf", x_scale="jac",
                    ftol=1e-8, xtol=1e-8, gtol=1e-10, max_nfev=200)
scipy_s = time.process_time() - p0
lib.ofg_fit_close(h)
result = {
    "log_s": float(duration), "rows": rep["rows"], "segments": rep["segments"],
    "model_fit_wall_s": round(wall, 2), "model_fit_cpu_s": round(c1.ru_utime + c1.ru_stime - c0.ru_utime - c0.ru_stime, 2),
    "error_pct": err, "fit_pct_min": fits,
    "hull_stage": {"parameters": ng, "segments": ns, "residuals": m,
                   "ceres_cpu_s": round(ceres_s, 2), "ceres_iterations": it_c, "ceres_cost": round(cost_c.value, 2),
                   "scipy_cpu_s": round(scipy_s, 2), "scipy_nfev": int(sol.nfev), "scipy_cost": round(float(sol.cost), 2),
                   "scipy_status": int(sol.status),
                   "scipy_over_ceres_time": round(scipy_s / max(ceres_s, 1e-9), 2)},
}
print(json.dumps(result))
PY
