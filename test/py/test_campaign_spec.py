"""Campaign specs and the scenarios generated from them (docs/campaign.md): bad specs are refused naming the key,
generation is a pure function of (spec, index), every generated scenario is valid, and the envelope's current
limits are the AUV models' own."""
import concurrent.futures
import hashlib
import math
import os
import subprocess
import sys

import pytest
import yaml

from offshore_gnc import tools
from offshore_gnc.campaign import generate, spec

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ENVELOPE = os.path.join(REPO, "config", "campaigns", "envelope.yaml")
SMOKE = os.path.join(REPO, "config", "campaigns", "smoke.yaml")


def tool(name):
    try:
        return tools.path(name)
    except tools.ToolNotFound as e:
        pytest.fail("cannot check generated scenarios against the simulator's loader: %s" % e)


def smoke_doc():
    with open(SMOKE) as f:
        return yaml.safe_load(f)


@pytest.mark.parametrize("change,key", [
    (lambda d: d.update(currnet={}), "'currnet' is not a known key"),
    (lambda d: d["current"].update(speed=[0.3, 0.1]), "'current.speed'"),
    (lambda d: d["wind"].update(speed=50), "'wind.speed' = 50 is out of range"),
    (lambda d: d["wind"].update(speed="fast"), "'wind.speed' must be a number"),
    (lambda d: d["obstacles"].update(type={"boat": 1}), "'obstacles.type.boat'"),
    (lambda d: d["obstacles"].update(count=[0, 2.5]), "'obstacles.count'"),
    (lambda d: d["faults"][0].update(probability=1.5), "'faults[0].probability'"),
    (lambda d: d["faults"].append({"plan": "sonar@10", "probability": 0.95}), "'faults' probabilities"),
    (lambda d: d["faults"][0].update(probabilty=0.1), "'faults[0].probabilty' is not a known key"),
    (lambda d: d["site"].update(shipped=["atlantis"]), "'site.shipped[0]'"),
    (lambda d: d["site"].update(origins=[{"name": "x", "latitude": 95, "longitude": 0}]), "'site.origins[0].latitude'"),
    (lambda d: d.update(auv_model=["nautilus"]), "'auv_model.nautilus'"),
    (lambda d: d["area"].pop("distance_m"), "'area.distance_m' is missing"),
    (lambda d: d.update(purpose="evaluation"), "'seed' = 7 is a tuning seed"),
    (lambda d: d.update(seed=1000), "'seed' = 1000 is an evaluation seed"),
    (lambda d: d["current"].update(speed=[0.3, 0.4]), "'current.speed' starts at 0.3 m/s, above the acolor's"),
    (lambda d: d["target"].update(depth_m=0.2), "'target.depth_m'"),
    (lambda d: d["waves"].update(fetch_m=-5), "'waves.fetch_m' = -5 is out of range"),
    (lambda d: d["waves"].update(amplitude=0.2), "'waves.amplitude' is not a known key"),
])
def test_bad_specs_are_refused_naming_the_key(change, key):
    doc = smoke_doc()
    change(doc)
    with pytest.raises(spec.SpecError) as e:
        spec.validate(doc)
    assert key in str(e.value)


def test_a_bad_fault_plan_is_refused_by_the_simulators_parser(tmp_path):
    doc = smoke_doc()
    doc["faults"][0]["plan"] = "usbx@60"
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump(doc))
    tool("mission_rosfree")
    r = subprocess.run([sys.executable, "-m", "offshore_gnc.campaign", str(bad), "--missions", "1",
                        "--out", str(tmp_path / "out")], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       env=dict(os.environ, PYTHONPATH=os.path.join(REPO, "python")), timeout=120)
    assert r.returncode == 2, r.stderr
    assert "faults[0].plan" in r.stderr and "unknown fault 'usbx'" in r.stderr, r.stderr


def texts(s, n):
    return [generate.scenario_text(s, i, generate.generate(s, i)) for i in range(n)]


def test_generation_is_a_pure_function_of_spec_and_index():
    s = spec.load(ENVELOPE)
    first = texts(s, 40)
    assert texts(s, 40) == first
    assert generate.generate(s, 17) == generate.generate(spec.load(ENVELOPE), 17)
    assert len(set(first)) == 40
    # another interpreter (another hash seed): the same files
    code = ("import hashlib, sys; from offshore_gnc.campaign import generate, spec; s = spec.load(%r); "
            "print(hashlib.sha256(''.join(generate.scenario_text(s, i, generate.generate(s, i)) "
            "for i in range(40)).encode()).hexdigest())" % ENVELOPE)
    out = subprocess.run([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True, check=True,
                         env=dict(os.environ, PYTHONPATH=os.path.join(REPO, "python"), PYTHONHASHSEED="123")).stdout
    assert out.strip() == hashlib.sha256("".join(first).encode()).hexdigest()
    # another campaign seed: other runs
    assert texts(spec.validate(yaml.safe_load(open(ENVELOPE)), seed=1001), 40) != first


def test_each_variable_has_its_own_stream():
    """Changing one distribution leaves every other variable of every run as it was."""
    a = spec.load(ENVELOPE)
    b = spec.load(ENVELOPE)
    b["wind"]["speed"] = [0.0, 3.0]
    for i in range(20):
        ra, rb = generate.generate(a, i), generate.generate(b, i)
        assert ra["scenario"]["current"] == rb["scenario"]["current"]
        assert ra["scenario"]["targets"] == rb["scenario"]["targets"]
        assert ra["options"] == rb["options"]


def test_every_generated_scenario_passes_the_simulators_check(tmp_path):
    """40 of the envelope's (each check loads the simulator's libraries: 0.1-0.8 s); the smoke campaign's 50 are
    checked by mission_rosfree itself in test_campaign_run.py (a refused scenario is an error there)."""
    check, s = tool("scenario_check"), spec.load(ENVELOPE)

    def one(i):
        f = tmp_path / ("envelope_%d.yaml" % i)
        f.write_text(generate.scenario_text(s, i, generate.generate(s, i)))
        r = subprocess.run([check, str(f)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        return i, r.returncode, r.stdout
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        bad = [x for x in pool.map(one, range(40)) if x[1] != 0]
    assert not bad, bad
    kinds = {o["type"] for i in range(40) for o in generate.generate(s, i)["scenario"]["obstacles"]}
    assert kinds == {"buoy", "vessel"}


def test_the_envelope_is_what_the_issue_asks():
    s = spec.load(ENVELOPE)
    assert s["purpose"] == "evaluation" and s["seed"] >= spec.EVALUATION_SEED_MIN
    runs = [generate.generate(s, i) for i in range(400)]
    v = [r["variables"] for r in runs]
    assert {x["auv_model"] for x in v} == {"girona500", "acolor"}
    assert len({x["site"] for x in v}) == 8
    assert {x["obstacles"] for x in v} == {0, 1, 2, 3}
    assert sum(x["obstacles_dropped"] > 0 for x in v) < 0.05 * len(v)
    assert all(3 <= x["target_depth_m"] <= 10 and x["wind_speed_m_s"] <= 8 for x in v)
    assert all(200 <= x["fetch_m"] <= 10000 for x in v) and max(x["fetch_m"] for x in v) > 9000
    for r in runs:
        limit = s["current"]["stem_limit"][r["options"]["auv_model"]]
        assert r["variables"]["current_speed_m_s"] <= min(0.5, limit) + 1e-3
        sc = r["scenario"]
        t, c = sc["targets"][0], sc["auv"]["coverage"]
        assert c["north_min"] <= t["north"] <= c["north_max"] and c["east_min"] <= t["east"] <= c["east_max"]
        # planned from the band, the same for every run: the tilted fan (0.44 m above to 5.37 m below the AUV at its
        # 10 m range) centred on 3-10 m
        assert abs(c["depth"] - 4.03) < 0.01
        # and, if that finds nothing, back at 5.54 m, where the fan sees 10 m deep 7 m off
        assert abs(c["second_depth"] - 5.54) < 0.01
        assert math.hypot(c["north_min"], c["east_min"]) >= 20 or math.hypot(t["north"], t["east"]) >= 20


def _steady_speed(params, commands):
    """model_run: the through-water surge and sway speed after 300 s of constant thruster commands."""
    header = "t," + ",".join("c%d" % (i + 1) for i in range(len(commands)))
    row = ",".join(str(c) for c in commands)
    r = subprocess.run([tool("model_run"), "--vehicle", "auv", "--params", os.path.join(REPO, "config", "models",
                                                                                       params),
                        "--input", "-", "--output", "-", "--every", "1000"],
                       input="%s\n0,%s\n300,%s\n" % (header, row, row), stdout=subprocess.PIPE, text=True, check=True)
    last = r.stdout.strip().splitlines()[-1].split(",")
    return float(last[5]), float(last[6])  # u, v


def test_the_envelopes_current_limits_are_the_models():
    """stem_limit = the through-water speed the stack can command minus half the cruise speed (docs/campaign.md):
    the Girona500 at full ahead on its two surge thrusters (cruise 0.3 m/s), the aColor at its one surge PWM,
    1609 us = command 0.2725 on each horizontal thruster (cruise 0.5 m/s)."""
    limits = spec.load(ENVELOPE)["current"]["stem_limit"]
    g_ahead, _ = _steady_speed("girona500.yaml", [-1, -1, 0, 0, 0])
    _, g_abeam = _steady_speed("girona500.yaml", [0, 0, 0, 0, -1])
    a_cruise, _ = _steady_speed("acolor.yaml", [0.2725] * 4 + [0, 0])
    assert abs(g_ahead - 0.64) < 0.01 and abs(g_abeam + 0.28) < 0.01 and abs(a_cruise - 0.50) < 0.01
    assert limits["girona500"] == pytest.approx(g_ahead - 0.3 / 2, abs=0.01)
    assert limits["acolor"] == pytest.approx(a_cruise - 0.5 / 2, abs=0.01)
