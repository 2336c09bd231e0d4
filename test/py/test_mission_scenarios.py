"""Every shipped scenario passes the check the main job runs first; bad ones are refused naming the key."""
import glob
import os
import subprocess
import sys

import pytest

from offshore_gnc.testing import run_job

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENARIOS = sorted(glob.glob(os.path.join(REPO, "config", "scenarios", "*.yaml")))


def check(path, *configs):
    r = subprocess.run(["rosrun", "offshore_gnc", "scenario_check", path] + list(configs), stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=60)
    return r.returncode, r.stdout


@pytest.mark.parametrize("path", SCENARIOS, ids=[os.path.basename(p) for p in SCENARIOS])
def test_shipped_scenarios_are_valid(path):
    rc, out = check(path)
    assert rc == 0, out
    assert '"ok": true' in out


@pytest.mark.parametrize("text,needle", [
    ("name: x\nobstacels: []\n", "obstacels"),                                # typo: unknown key
    ("name: x\nmission: {expect: win}\n", "mission.expect"),                  # unknown outcome
    ("name: x\nmission: {max_sim_time: -5}\n", "mission.max_sim_time"),       # impossible value
    ("name: x\nobstacles:\n  - {type: buoy, north: 1, east: 1, radius: -2}\n", "radius"),
])
def test_bad_scenarios_are_refused(tmp_path, text, needle):
    base = open(os.path.join(REPO, "config", "scenarios", "pyhajarvi.yaml")).read()
    # start from the valid default and break one thing
    lines = [l for l in base.splitlines() if not l.startswith(("name:", "obstacles:", "  - {type: buoy"))]
    p = tmp_path / "bad.yaml"
    p.write_text(text + "\n".join(l for l in lines if not l.startswith("mission:")) + "\n")
    rc, out = check(str(p))
    assert rc != 0
    assert needle in out, out


def test_main_job_refuses_a_bad_scenario_before_starting(tmp_path):
    p = tmp_path / "bad.yaml"
    p.write_text("name: x\nunknown_key: 1\n")
    r = run_job([sys.executable, os.path.join(REPO, "python", "offshore_gnc", "mission_job.py"),
                 "--scenario", str(p), "--out", str(tmp_path / "out")], 60)
    assert r.returncode == 2
    assert "refused" in r.stdout and "unknown_key" in r.stdout
    assert not (tmp_path / "out" / "logs").exists()  # nothing was started


def test_a_vehicle_config_on_another_origin_is_refused_naming_both(tmp_path):
    """The simulators place the world by the scenario's origin and the navigation by the vehicle's: two origins
    apart would offset every target by their distance (a target computed 2,520 km away), so the check refuses."""
    default = os.path.join(REPO, "config", "scenarios", "pyhajarvi.yaml")
    usv = os.path.join(REPO, "config", "usv.yaml")
    rc, out = check(default, usv, os.path.join(REPO, "config", "auv_girona500.yaml"))
    assert rc == 0, out
    elsewhere = tmp_path / "usv_palma.yaml"
    elsewhere.write_text(open(usv).read().replace("latitude: 61.4507", "latitude: 39.5500")
                         .replace("longitude: 23.7270", "longitude: 2.6300"))
    rc, out = check(default, str(elsewhere))
    assert rc != 0
    assert "61.450700" in out and "39.550000" in out and "km apart" in out, out
    near = tmp_path / "usv_near.yaml"  # 1.1 m north: the same origin within GPS accuracy
    near.write_text(open(usv).read().replace("latitude: 61.4507", "latitude: 61.45071"))
    rc, out = check(default, str(near))
    assert rc == 0, out
