"""The co-operative mission end to end, as the main job runs it: two real masters, both vehicle stacks in
simulation, the relay between them; then the report's figures against stated bounds."""
import json
import os
import subprocess
import sys

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
JOB = os.path.join(REPO, "python", "offshore_gnc", "mission_job.py")

# Bounds (docs/mission.md): the sonar's horizontal localisation within 2 m; the USV never touches the buoy.
MAX_TARGET_ERROR_M = 2.0
MIN_CLEARANCE_M = 0.0


def run(scenario, out):
    r = subprocess.run([sys.executable, JOB, "--scenario", os.path.join(REPO, "config", "scenarios", scenario),
                        "--out", str(out), "--rate", "20", "--quiet"], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=600)
    metrics = json.load(open(os.path.join(str(out), "metrics.json")))
    return r, metrics


def test_default_mission_succeeds(tmp_path):
    r, m = run("pyhajarvi.yaml", tmp_path / "default")
    assert r.returncode == 0, r.stdout[-3000:]
    assert m["success"] is True
    assert m["usv_final_phase"] == "ARRIVED" and m["auv_final_phase"] == "TARGET_FOUND"
    assert m["target_error_m"] is not None and m["target_error_m"] < MAX_TARGET_ERROR_M, m
    assert m["min_clearance_m"] is not None and m["min_clearance_m"] > MIN_CLEARANCE_M, m
    assert m["usv_xte_samples"] > 0 and m["usv_rmse_m"] is not None
    for f in ("map.png", "cross_track.png", "summary.md", "usv.bag", "auv.bag"):
        assert os.path.getsize(os.path.join(str(tmp_path / "default"), f)) > 0, f


def test_no_target_scenario_ends_with_no_target(tmp_path):
    r, m = run("no_target.yaml", tmp_path / "none")
    assert r.returncode == 0, r.stdout[-3000:]  # the expected outcome of this scenario
    assert m["auv_final_phase"] == "NO_TARGET"
    assert m["usv_final_phase"] in ("STATION_KEEPING", "PEER_LOST")
    assert m["target_error_m"] is None  # nothing was detected, nothing is reported as found
