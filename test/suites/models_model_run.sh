#!/usr/bin/env bash
# model_run as a user runs it (thesis Fig. 3.10 workflow): a CSV of joystick / thruster commands in, a CSV of
# states out; a bad parameter file and a non-finite command are reported. Env: TEST_RESULTS_DIR, WS.
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env model-run
# shellcheck disable=SC1091
set +u; source "$ws/devel/setup.bash"; set -u
export PATH="/usr/bin:/bin:$PATH"
cd "$REPO"
# The binary of this workspace: rosrun would find the copies other workspaces built inside the repository.
/usr/bin/python3 - "$work" "$ws/devel/lib/offshore_gnc/model_run" <<'PY' > "$work/check.log" 2>&1
import csv, io, math, subprocess, sys
work, exe = sys.argv[1], sys.argv[2]
run = lambda args, inp: subprocess.run([exe] + args, input=inp.encode(),
                                       capture_output=True)
# USV: 60 s full ahead from rest -> steady surge speed of the 3-DOF model (about 3.27 m/s, 6.4 kt).
r = run(["--vehicle", "usv", "--params", "config/models/usv.yaml", "--every", "100", "--output", work + "/usv.csv"],
        "t,surge,sway,yaw\n0,1,0,0\n60,1,0,0\n")
assert r.returncode == 0, r.stderr
rows = list(csv.DictReader(open(work + "/usv.csv")))
assert len(rows) == 60 and abs(float(rows[-1]["t"]) - 60) < 1e-9, len(rows)
u = float(rows[-1]["u"]); assert 3.2 < u < 3.35, u
assert abs(float(rows[-1]["rpm"]) - 1820) < 1, rows[-1]["rpm"]
assert all(math.isfinite(float(v)) for row in rows for v in row.values())
# Nomoto model from the same file with one key changed.
text = open("config/models/usv.yaml").read().replace("model: dynamic_3dof", "model: nomoto")
open(work + "/nomoto.yaml", "w").write(text)
r = run(["--vehicle", "usv", "--params", work + "/nomoto.yaml"], "0,1,0,0\n60,1,0,0\n")
last = r.stdout.decode().strip().splitlines()[-1].split(",")
assert r.returncode == 0 and abs(float(last[5]) - 2.93e-3 * 1820) < 1e-2, (r.stderr, last)
# AUV: NaN command rejected and counted, previous kept; state stays finite.
r = run(["--vehicle", "auv", "--params", "config/models/girona500.yaml", "--env", "config/models/environment_lake.yaml"],
        "0,-1,-1,0,0,0\n1,nan,0,0,0,0\n2,0,0,0,0,0\n")
assert r.returncode == 0, r.stderr
assert b"rejected_commands = 1" in r.stderr, r.stderr
assert "nan" not in r.stdout.decode().lower()
# A parameter file with a missing key is refused, naming it.
open(work + "/bad.yaml", "w").write(text.replace("X_uu: 315.45\n", ""))
r = run(["--vehicle", "usv", "--params", work + "/bad.yaml"], "0,0,0,0\n")
assert r.returncode == 1 and b"'X_uu' is missing" in r.stderr, r.stderr
# Wrong column count is refused with the line number.
r = run(["--vehicle", "usv", "--params", "config/models/usv.yaml"], "0,0,0\n")
assert r.returncode == 1 and b"line 1" in r.stderr, r.stderr
print("ok")
PY
junit_check_log models model_run_cli "$work/check.log"
junit_write models_model_run "$out/models_model_run.xml"
