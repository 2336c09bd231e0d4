"""docs/parameters.md and cfg/*.cfg are what param_docs prints from the parameter tables (the reference a user
reads and the dynamic_reconfigure forms are the tables the code validates against)."""
import glob
import os
import subprocess

import pytest

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
