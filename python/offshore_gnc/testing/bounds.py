#!/usr/bin/python3
"""The bounds of the measured mission-level figures (test/bounds.yaml, issue 30): what the tests read, what records a
rostest check's figures, what measures each case over several runs, and the audit of each bound against its runs.

    python3 -m offshore_gnc.testing.bounds measure [CASE ...] [--runs N] [--bin DIR]   (./scripts/measure_bounds)
    python3 -m offshore_gnc.testing.bounds audit
measure runs each case (all by default) on seeds 1..N (rostest: N times) and writes its values into
test/bounds_measured.yaml; audit prints each bound beside its runs and exits non-zero on a breach of the rule in
test/bounds.yaml's header. Python 3 standard library and PyYAML only.
"""
import argparse
import datetime
import functools
import glob
import json
import os
import subprocess
import sys
import tempfile

import yaml

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
BOUNDS = os.path.join(REPO, "test", "bounds.yaml")
MEASURED = os.path.join(REPO, "test", "bounds_measured.yaml")
RECORD_ENV = "OFFSHORE_GNC_BOUNDS_RECORD"  # set by `measure` for a rostest: where its check appends its figures
MIN_RUNS = 5
SPREADS = 3.0
FLOOR = 0.1  # ... or a tenth of the mean, for a figure whose runs hardly differ (a rostest's timing does)


@functools.lru_cache(maxsize=None)
def load(path=BOUNDS):
    """test/bounds.yaml's cases, read once per process (each bound a test reads comes from here)."""
    with open(path) as f:
        return yaml.safe_load(f)["cases"]


def _figure(case, figure):
    try:
        return load()[case]["bounds"][figure]
    except KeyError:
        raise KeyError("test/bounds.yaml has no bound for %s/%s" % (case, figure))


def upper(case, figure):
    """The figure's upper bound: the test asserts value <= it."""
    return float(_figure(case, figure)["max"])


def lower(case, figure):
    """The figure's lower bound: the test asserts value >= it."""
    return float(_figure(case, figure)["min"])


def breaches(metrics, case):
    """Each figure of `case` that `metrics` (metrics.json's keys) lacks or has outside its bounds: [] when all keep
    them. A test asserts `not breaches(m, case)`."""
    out = []
    for figure, bound in load()[case]["bounds"].items():
        v = metrics.get(figure)
        if v is None:
            out.append("%s: none" % figure)
        elif "max" in bound and v > bound["max"]:
            out.append("%s: %.4g over its max %.4g" % (figure, v, bound["max"]))
        elif "min" in bound and v < bound["min"]:
            out.append("%s: %.4g under its min %.4g" % (figure, v, bound["min"]))
    return out


def record(case, figure, value):
    """A rostest check's measured figure, appended (one JSON line) where `measure` asked for it; nothing otherwise."""
    path = os.environ.get(RECORD_ENV)
    if path:
        with open(path, "a") as f:
            f.write(json.dumps({"case": case, "figure": figure, "value": value}) + "\n")


# ------------------------------------------------------------------ the audit

def audit_figure(bound, values):
    """The problems of one figure's bound against its measured values (an empty list when it keeps the rule)."""
    values = [v for v in values if v is not None]
    if len(values) < MIN_RUNS and "why" not in bound:
        return ["%d measured values, %d needed" % (len(values), MIN_RUNS)]
    problems = []
    if not values:
        return problems
    lo, hi = min(values), max(values)
    mean, spread = sum(values) / len(values), hi - lo
    allowed = max(SPREADS * spread, FLOOR * abs(mean))
    if "max" in bound:
        if hi > bound["max"]:
            problems.append("a run gave %.4g over its max %.4g" % (hi, bound["max"]))
        elif bound["max"] - mean > allowed and "why" not in bound:
            problems.append("max %.4g is %.3g above the mean %.4g, over %g x the spread %.3g (or %g of the mean)"
                            % (bound["max"], bound["max"] - mean, mean, SPREADS, spread, FLOOR))
    if "min" in bound:
        if lo < bound["min"]:
            problems.append("a run gave %.4g under its min %.4g" % (lo, bound["min"]))
        elif mean - bound["min"] > allowed and "why" not in bound:
            problems.append("min %.4g is %.3g below the mean %.4g, over %g x the spread %.3g (or %g of the mean)"
                            % (bound["min"], mean - bound["min"], mean, SPREADS, spread, FLOOR))
    return problems


def audit(cases, measured):
    """(lines to print, problems): each figure of each case beside its measured runs."""
    lines, problems = [], []
    for name, case in cases.items():
        runs = (measured or {}).get(name, {})
        for figure, bound in case["bounds"].items():
            values = runs.get("values", {}).get(figure, [])
            got = [v for v in values if v is not None]
            span = "%.4g-%.4g over %d runs" % (min(got), max(got), len(got)) if got else "not measured"
            limits = " ".join("%s %s" % (k, bound[k]) for k in ("min", "max") if k in bound)
            lines.append("%-28s %-28s %-16s %s%s" % (name, figure, limits, span, " (why: %s)" % bound["why"]
                                                      if "why" in bound else ""))
            problems += ["%s/%s: %s" % (name, figure, p) for p in audit_figure(bound, values)]
    return lines, problems


# ------------------------------------------------------------------ measuring

def _scenario(case, tmp):
    path = os.path.join(REPO, "config", "scenarios", case["scenario"])
    if "sea_state" not in case:
        return path
    with open(path) as f:  # the scenario with another sea state, as the test writes it
        text = f.read()
    if "sea_state: field_day" not in text:
        raise SystemExit("%s: no 'sea_state: field_day' to replace" % path)
    out = os.path.join(tmp, "scenario.yaml")
    with open(out, "w") as f:
        f.write(text.replace("sea_state: field_day", "sea_state: " + case["sea_state"]))
    return out


def _radio(case, tmp):
    if "radio" not in case:
        return []
    out = os.path.join(tmp, "radio.yaml")
    with open(out, "w") as f:
        yaml.safe_dump(case["radio"], f)
    return ["--radio", out]


def _mission_run(case, seed, bin_dir, tmp):
    """One run of a rosfree or ros case: its metrics (the keys of metrics.json)."""
    common = ["--scenario", _scenario(case, tmp), "--auv-model", case.get("auv_model", "girona500"),
              "--seed", str(seed)] + _radio(case, tmp) + [str(a) for a in case.get("args", [])]
    if case["runner"] == "rosfree":
        r = subprocess.run([os.path.join(bin_dir, "mission_rosfree")] + common, capture_output=True, text=True)
        if r.returncode not in (0, 1):
            raise RuntimeError("mission_rosfree failed: " + r.stderr[-2000:])
        return json.loads(r.stdout.strip().splitlines()[-1])
    out = os.path.join(tmp, "job")
    r = subprocess.run([sys.executable, os.path.join(REPO, "python", "offshore_gnc", "mission_job.py")] + common
                       + ["--rate", "20", "--quiet", "--out", out], capture_output=True, text=True)
    path = os.path.join(out, "metrics.json")
    if not os.path.exists(path):
        raise RuntimeError("the job wrote no metrics.json: " + r.stdout[-2000:])
    with open(path) as f:
        return json.load(f)


def _rostest_run(name, case, tmp):
    """One run of a rostest case: the figures its check recorded."""
    found = glob.glob(os.path.join(REPO, "test", "rostest", "*", case["test"]))
    if len(found) != 1:
        raise SystemExit("%s: no single test/rostest/*/%s" % (name, case["test"]))
    rec = os.path.join(tmp, "record.jsonl")
    if os.path.exists(rec):
        os.remove(rec)
    env = dict(os.environ, **{RECORD_ENV: rec})
    r = subprocess.run(["rostest", found[0]], capture_output=True, text=True, env=env)
    got = {}
    if os.path.exists(rec):
        for line in open(rec):
            x = json.loads(line)
            if x["case"] == name:
                got[x["figure"]] = x["value"]
    got["outcome"] = "success" if r.returncode == 0 else "failed"
    return got


def measure(names, runs, bin_dir):
    cases = load()
    commit = subprocess.run(["git", "-C", REPO, "describe", "--always", "--dirty"], capture_output=True,
                            text=True).stdout.strip()
    for name in names or list(cases):
        case = cases[name]
        values = {f: [] for f in case["bounds"]}
        left_out = {}
        for seed in range(1, runs + 1):
            with tempfile.TemporaryDirectory() as tmp:
                m = _rostest_run(name, case, tmp) if case["runner"] == "rostest" else \
                    _mission_run(case, seed, bin_dir, tmp)
            outcome = m.get("outcome")
            if outcome not in case.get("outcomes", ["success"]):
                left_out[seed] = outcome
            else:
                for f in values:
                    values[f].append(m.get(f))
            print("%s run %d: %s %s" % (name, seed, outcome, {f: m.get(f) for f in values}), file=sys.stderr,
                  flush=True)
        measured = {}
        if os.path.exists(MEASURED):  # read again: another measurement may have written its cases meanwhile
            with open(MEASURED) as f:
                measured = yaml.safe_load(f) or {}
        measured[name] = {"commit": commit, "date": datetime.date.today().isoformat(),
                          "runs": runs, "left_out": left_out, "values": values}
        with open(MEASURED, "w") as f:  # after each case: a long measurement keeps what it has
            f.write("# Written by ./scripts/measure_bounds (offshore_gnc.testing.bounds): each case's figures over "
                    "its runs (seeds 1..runs;\n# rostest: repeated runs). Runs with an outcome its test does not "
                    "accept are in left_out. Do not edit by hand.\n")
            yaml.safe_dump(measured, f, sort_keys=True, default_flow_style=None, width=110)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="what", required=True)
    m = sub.add_parser("measure")
    m.add_argument("cases", nargs="*")
    m.add_argument("--runs", type=int, default=10)
    m.add_argument("--bin", default=os.path.join(REPO, "build", ".ws", "devel", "lib", "offshore_gnc"))
    sub.add_parser("audit")
    a = ap.parse_args(argv)
    if a.what == "measure":
        unknown = set(a.cases) - set(load())
        if unknown:
            ap.error("no such case: " + ", ".join(sorted(unknown)))
        measure(a.cases, a.runs, a.bin)
        return 0
    measured = yaml.safe_load(open(MEASURED)) if os.path.exists(MEASURED) else {}
    lines, problems = audit(load(), measured)
    print("\n".join(lines))
    for p in problems:
        print("breach: " + p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
