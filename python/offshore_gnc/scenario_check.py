"""Scenario files are validated by the simulator's own loader (C++, `scenario_check` tool) before anything
starts, so that a typo or impossible geometry is refused with a message naming the key."""
import os
import subprocess

import yaml


class ScenarioError(Exception):
    pass


def load(path):
    """Validated scenario as a dict; raises ScenarioError naming the problem."""
    if not os.path.isfile(path):
        raise ScenarioError("scenario file not found: %s" % path)
    try:
        r = subprocess.run(["rosrun", "offshore_gnc", "scenario_check", path], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, timeout=60, text=True)
    except FileNotFoundError:
        raise ScenarioError("rosrun not found: source the workspace (devel/setup.bash) first")
    if r.returncode != 0:
        raise ScenarioError("%s: %s" % (path, r.stdout.strip()))
    with open(path) as f:
        return yaml.safe_load(f) or {}
