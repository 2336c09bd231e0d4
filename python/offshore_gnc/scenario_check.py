"""Scenario files are validated by the simulator's own loader (C++, `scenario_check` tool) before anything
starts, so that a typo or impossible geometry is refused with a message naming the key."""
import os
import subprocess

import yaml


class ScenarioError(Exception):
    pass


def load(path, vehicle_configs=()):
    """Validated scenario as a dict; raises ScenarioError naming the problem. With vehicle configs, their
    local origins must be the scenario's (the tool names both when they are not)."""
    if not os.path.isfile(path):
        raise ScenarioError("scenario file not found: %s" % path)
    try:
        r = subprocess.run(["rosrun", "offshore_gnc", "scenario_check", path] + list(vehicle_configs),
                           stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, timeout=60, text=True)
    except FileNotFoundError:
        raise ScenarioError("rosrun not found: source the workspace (devel/setup.bash) first")
    if r.returncode != 0:
        raise ScenarioError("%s: %s" % (path, r.stdout.strip()))
    with open(path) as f:
        return yaml.safe_load(f) or {}
