"""The suite's bounds on measured mission-level figures (test/bounds.yaml, issue 30): each set from at least five runs
(test/bounds_measured.yaml, ./scripts/measure_bounds) and no looser than three times their spread, and each read from
that one place by the tests that assert it."""
import glob
import os
import re

from offshore_gnc.testing import bounds

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def test_every_bound_keeps_the_rule_against_its_measured_runs():
    import yaml
    with open(bounds.MEASURED) as f:
        measured = yaml.safe_load(f)
    lines, problems = bounds.audit(bounds.load(), measured)
    assert lines and not problems, "\n".join(problems)


def test_the_audit_catches_a_loose_bound_a_breached_one_and_too_few_runs():
    runs = [1.0, 1.2, 1.1, 1.3, 1.0]  # mean 1.12, spread 0.3: an upper bound up to 2.02, a lower one down to 0.22
    assert bounds.audit_figure({"max": 2.0}, runs) == []
    assert bounds.audit_figure({"min": 0.3}, runs) == []
    assert "over 3 x the spread" in bounds.audit_figure({"max": 2.1}, runs)[0]
    assert "over 3 x the spread" in bounds.audit_figure({"min": 0.2}, runs)[0]
    assert bounds.audit_figure({"max": 2.1, "why": "a requirement"}, runs) == []
    assert "over its max" in bounds.audit_figure({"max": 1.25}, runs)[0]
    assert "under its min" in bounds.audit_figure({"min": 1.05, "why": "a requirement"}, runs)[0]
    assert "5 needed" in bounds.audit_figure({"max": 2.0}, runs[:4] + [None])[0]
    assert bounds.audit_figure({"min": 1.0, "why": "a requirement"}, []) == []
    steady = [10.0, 10.01, 10.02, 10.0, 10.01]  # spread 0.02: a tenth of the mean, 1.0, is the margin
    assert bounds.audit_figure({"max": 11.0}, steady) == [] and bounds.audit_figure({"max": 11.1}, steady) != []


def test_each_case_is_read_by_a_test_and_each_bound_by_its_case():
    """No bound in the file that no test reads, and no test asserting a case's figure the file does not bound."""
    sources = {}
    for path in glob.glob(os.path.join(REPO, "test", "unit", "closed_loop", "*.cpp")) \
            + glob.glob(os.path.join(REPO, "test", "py", "test_mission_*.py")) \
            + glob.glob(os.path.join(REPO, "test", "rostest", "*", "*.py")):
        sources[path] = open(path).read()
    cases = bounds.load()
    for name, case in cases.items():
        for figure in case["bounds"]:
            reads = [p for p, text in sources.items()
                     if re.search(r'breaches\(\w+, "%s"\)' % name, text)  # every figure of the case
                     or (re.search(r'"%s"' % name, text) and re.search(r'"%s"' % figure, text))]
            assert reads, "%s/%s: no test reads it" % (name, figure)
    for path, text in sources.items():
        for name in re.findall(r'breaches\(\w+, "(\w+)"\)', text):
            assert name in cases, "%s: case %s not in test/bounds.yaml" % (os.path.relpath(path, REPO), name)
        for name, figure in re.findall(r'(?:upper|lower)\(\s*"(\w+)",\s*"(\w+)"\)', text):
            assert name in cases and figure in cases[name]["bounds"], "%s: %s/%s not in test/bounds.yaml" \
                % (os.path.relpath(path, REPO), name, figure)


def test_breaches_names_each_figure_out_of_its_bounds_or_missing():
    case = next(iter(bounds.load()))
    figures = bounds.load()[case]["bounds"]
    inside = {f: (b["max"] if "max" in b else b["min"]) for f, b in figures.items()}
    assert bounds.breaches(inside, case) == []
    f, b = next((f, b) for f, b in figures.items() if "max" in b)
    assert bounds.breaches(dict(inside, **{f: b["max"] * 1.01 + 0.01}), case) == [
        "%s: %.4g over its max %.4g" % (f, b["max"] * 1.01 + 0.01, b["max"])]
    assert bounds.breaches(dict(inside, **{f: None}), case) == ["%s: none" % f]
