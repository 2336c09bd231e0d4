"""docs/parameters.md and cfg/*.cfg are what param_docs prints from the parameter tables (the reference a user
reads and the dynamic_reconfigure forms are the tables the code validates against); the launch files' component
blocks are what it prints from the vehicles' manifests (config/vehicles/, which the ROS-free stacks read too)."""
import glob
import os
import subprocess
import xml.etree.ElementTree as ET

import pytest
import yaml

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def _tool():
    dirs = [d for d in os.environ.get("LD_LIBRARY_PATH", "").split(":") if d]
    dirs += glob.glob(os.path.join(REPO, "build", ".ws*", "devel", "lib"))
    for d in dirs:
        t = os.path.join(d, "offshore_gnc", "param_docs")
        if os.path.exists(t):
            return t
    return None


def _generated(*args):
    tool = _tool()
    assert tool, "param_docs not built"
    return subprocess.run([tool, *args], stdout=subprocess.PIPE, check=True).stdout.decode()


def test_parameter_reference_is_generated_from_the_tables():
    doc = open(os.path.join(REPO, "docs", "parameters.md"), encoding="utf-8").read()
    assert doc == _generated(), "docs/parameters.md is out of date: run `param_docs > docs/parameters.md`"


# Every .cfg: a hand-written one is a form param_docs does not know, and fails here.
@pytest.mark.parametrize("path", sorted(glob.glob(os.path.join(REPO, "cfg", "*.cfg"))), ids=os.path.basename)
def test_reconfigure_form_is_generated_from_the_tables(path):
    form = os.path.splitext(os.path.basename(path))[0]
    cmd = "param_docs --cfg %s > cfg/%s.cfg" % (form, form)
    assert open(path, encoding="utf-8").read() == _generated("--cfg", form), "cfg/%s.cfg is out of date: run `%s`" % (
        form, cmd)
    assert os.access(path, os.X_OK), "cfg/%s.cfg must be executable (catkin runs it as its own generator)" % form


# Every launch file: one a manifest names has its block as param_docs writes it; any other has no block (one left
# behind when its components moved would go stale unseen).
@pytest.mark.parametrize("path", sorted(glob.glob(os.path.join(REPO, "launch", "*.launch"))), ids=os.path.basename)
def test_launch_file_components_are_generated_from_the_manifests(path):
    name = os.path.basename(path)
    text = open(path, encoding="utf-8").read()
    if name not in _generated("--launch-files").split():
        assert "BEGIN generated" not in text, "launch/%s has a generated block but no manifest names it" % name
        return
    cmd = "param_docs --launch launch/%s > /tmp/%s && mv /tmp/%s launch/%s" % (name, name, name, name)
    assert text == _generated("--launch", path), "launch/%s is out of date: run `%s`" % (name, cmd)


def test_manifests_name_only_launch_files_and_nodelets_that_exist():
    plugins = {c.get("name") for c in ET.parse(os.path.join(REPO, "nodelet_plugins.xml")).iter("class")}
    manifests = sorted(glob.glob(os.path.join(REPO, "config", "vehicles", "*.yaml")))
    assert [os.path.basename(m) for m in manifests] == ["auv.yaml", "usv.yaml"]
    for m in manifests:
        components = yaml.safe_load(open(m, encoding="utf-8"))["components"]
        for key, c in components.items():
            assert c["nodelet"] in plugins, "%s: component %s runs %s, which nodelet_plugins.xml does not declare" % (
                m, key, c["nodelet"])
    for name in _generated("--launch-files").split():
        assert os.path.exists(os.path.join(REPO, "launch", name)), name
