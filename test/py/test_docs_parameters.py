"""docs/parameters.md is what param_docs prints from the parameter tables (the reference a user reads is the one
the code validates against)."""
import glob
import os
import subprocess

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def _tool():
    dirs = [d for d in os.environ.get("LD_LIBRARY_PATH", "").split(":") if d]
    dirs += glob.glob(os.path.join(REPO, "build", ".ws*", "devel", "lib"))
    for d in dirs:
        t = os.path.join(d, "offshore_gnc", "param_docs")
        if os.path.exists(t):
            return t
    return None


def test_parameter_reference_is_generated_from_the_tables():
    tool = _tool()
    assert tool, "param_docs not built"
    out = subprocess.run([tool], stdout=subprocess.PIPE, check=True).stdout.decode()
    doc = open(os.path.join(REPO, "docs", "parameters.md"), encoding="utf-8").read()
    assert doc == out, "docs/parameters.md is out of date: run `param_docs > docs/parameters.md`"
