"""Scenario files are validated by the simulator's own loader (C++, `scenario_check` tool) before anything
starts, so that a typo or impossible geometry is refused with a message naming the key."""
import json
import os
import subprocess

import yaml

from offshore_gnc import tools


class ScenarioError(Exception):
    pass


def _check(path, args):
    """The tool's JSON summary line; raises ScenarioError with its message."""
    if not os.path.isfile(path):
        raise ScenarioError("scenario file not found: %s" % path)
    try:
        r = subprocess.run([tools.path("scenario_check"), path] + list(args), stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, timeout=60, text=True)
    except tools.ToolNotFound as e:
        raise ScenarioError(str(e))
    if r.returncode != 0:
        raise ScenarioError("%s: %s" % (path, r.stdout.strip()))
    return json.loads(r.stdout.strip().splitlines()[-1])


def load(path):
    """Validated scenario as a dict; raises ScenarioError naming the problem."""
    _check(path, [])
    with open(path) as f:
        return yaml.safe_load(f) or {}


def mission(path):
    """How a run of the scenario is judged, as the simulator's loader reads its mission section (defaults filled):
    {expect, max_sim_time, hold_time, target_tolerance}; raises ScenarioError naming the problem."""
    return _check(path, [])["mission"]


def faults(path, plan):
    """The fault plan (offshore_gnc::FaultPlan text, e.g. "usbl@150+60 gps@200+10") checked by the simulators'
    own parser: a list of {name, vehicle, start_s, end_s (None: to the end)}; raises ScenarioError naming the bad
    item."""
    return _check(path, ["--faults", plan])["faults"] if plan.strip() else []
