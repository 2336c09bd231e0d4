"""./scripts/campaign SPEC [--missions N] [--jobs J] [--scheduler ADDRESS] [--out DIR] [--resume] [--seed S]

Runs a campaign's missions ROS-free (mission_rosfree, one process per run) on the local cores or a Dask cluster,
stores each run as it finishes (OUT/runs/), then writes and prints the report; the last line printed is one JSON
object. Exit status: 0 every run ran (whatever its outcome), 1 some runs could not run (listed in the report) or the
cluster failed, 2 a bad spec or option, 130 interrupted (--resume goes on). docs/campaign.md."""
import argparse
import datetime
import hashlib
import json
import os
import signal
import subprocess
import sys
import time

from offshore_gnc import tools
from offshore_gnc.campaign import execute, generate, report, runs
from offshore_gnc.campaign import spec as specs


class UsageError(Exception):
    pass


def _args(argv):
    ap = argparse.ArgumentParser(prog="campaign", description=__doc__.split("\n\n")[1])
    ap.add_argument("spec", help="campaign spec, e.g. config/campaigns/envelope.yaml")
    ap.add_argument("--missions", type=int, help="number of runs (default: the spec's `missions`)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count(), help="missions at once on this machine (default: "
                                                                      "the number of cores)")
    ap.add_argument("--scheduler", metavar="ADDRESS", help="run on this Dask cluster's workers (tcp://HOST:PORT)")
    ap.add_argument("--out", help="campaign folder (default: reports/campaign-NAME-SEED-TIME)")
    ap.add_argument("--resume", action="store_true", help="go on with the campaign in --out: only runs not stored")
    ap.add_argument("--seed", type=int, help="the campaign seed instead of the spec's (tuning < %d <= evaluation)"
                    % specs.EVALUATION_SEED_MIN)
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    a = ap.parse_args(argv)
    if a.jobs < 1:
        ap.error("--jobs must be at least 1")
    if a.resume and not a.out:
        ap.error("--resume needs the campaign's folder: --out DIR")
    return a


def _check_faults(spec, scenario_path):
    """Each fault plan through the simulators' own parser (scenario_check --faults), before any run."""
    for i, f in enumerate(spec["faults"]):
        r = subprocess.run([tools.path("scenario_check"), scenario_path, "--faults", f["plan"]],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            raise specs.SpecError("campaign spec '%s': key 'faults[%d].plan': %s" % (spec["file"], i, r.stderr.strip()))


def _scenarios(out, spec, missions):
    """Writes OUT/scenarios/run_NNNNNN.yaml of every run (kept if present, but it must be what this code generates:
    a resumed campaign must not mix two generators); returns {index: sha256 of the text}."""
    os.makedirs(os.path.join(out, "scenarios"), exist_ok=True)
    shas = {}
    for i in range(missions):
        text = generate.scenario_text(spec, i, generate.generate(spec, i))
        path = os.path.join(out, runs.scenario_file(i))
        if os.path.exists(path):
            with open(path) as f:
                if f.read() != text:
                    raise UsageError("%s differs from what this code generates for run %d: the generator changed "
                                     "since the campaign began; start a new campaign" % (path, i))
        else:
            runs.write_atomic(path, text)
        shas[i] = hashlib.sha256(text.encode()).hexdigest()
    return shas


def _meta(out, spec, resume):
    """OUT/campaign.json: the spec and the sessions. A folder holding another campaign, or any campaign without
    --resume, is refused: two campaigns' runs must never mix."""
    path = os.path.join(out, "campaign.json")
    if os.path.exists(path):
        with open(path) as f:
            meta = json.load(f)
        if not resume:
            raise UsageError("%s already holds a campaign: add --resume to go on with it, or choose another --out"
                             % out)
        if meta["fingerprint"] != specs.fingerprint(spec):
            raise UsageError("%s holds campaign '%s' (seed %s) of another spec or seed: it cannot be resumed with this "
                             "one" % (out, meta["spec"]["name"], meta["spec"]["seed"]))
        return meta
    if os.path.isdir(out) and os.listdir(out):
        raise UsageError("%s is not empty and holds no campaign: choose another --out" % out)
    os.makedirs(out, exist_ok=True)
    return {"spec": spec, "fingerprint": specs.fingerprint(spec), "sessions": []}


def _interrupt(*_):
    raise KeyboardInterrupt  # SIGTERM as Ctrl-C: stored runs stay, running ones are killed


def _run(a, spec, out, tool):
    meta = _meta(out, spec, a.resume)
    n = spec["missions"]
    shas = _scenarios(out, spec, n)
    _check_faults(spec, os.path.join(out, runs.scenario_file(0)))
    store = runs.Store(out)
    todo = [i for i in range(n) if i not in store.done()]
    session = {"started": datetime.datetime.now().isoformat(timespec="seconds"), "missions": n,
               "jobs": None if a.scheduler else a.jobs,
               "scheduler": a.scheduler, "ran": 0, "wall_s": 0.0, "interrupted": False}
    meta["sessions"].append(session)
    runs.write_atomic(os.path.join(out, "campaign.json"), json.dumps(meta, indent=1) + "\n")
    progress = execute.Progress(n, n - len(todo), quiet=a.quiet)
    print("campaign '%s': %d runs, %d stored, %d to run on %s; folder %s" % (
        spec["name"], n, n - len(todo), len(todo), "Dask %s" % a.scheduler if a.scheduler else "%d local jobs" % a.jobs,
        out), file=sys.stderr)
    t0 = time.monotonic()
    source = (execute.dask_runs(spec, todo, a.scheduler, tool) if a.scheduler
              else execute.local_runs(spec, todo, a.jobs, tool))
    try:
        for record in source:
            if record["scenario_sha256"] != shas[record["index"]]:
                raise RuntimeError("run %d on %s generated another scenario than this client: the workers run "
                                   "other code" % (record["index"], record["host"]))
            store.put(record)
            progress.update(record)
    except KeyboardInterrupt:
        session["interrupted"] = True
    finally:
        source.close()  # the local pool: pending runs dropped, running missions killed
        session["wall_s"] = round(time.monotonic() - t0, 2)
        session["ran"] = len(store.done() & set(range(n))) - (n - len(todo))  # counted from the store, not events
        progress.close()
        runs.write_atomic(os.path.join(out, "campaign.json"), json.dumps(meta, indent=1) + "\n")
    if session["interrupted"]:
        print("interrupted: %d of %d runs stored; go on with: ./scripts/campaign %s --out %s --resume" % (
            len(store.done() & set(range(n))), n, spec["file"], out), file=sys.stderr)
        return 130
    shown = os.path.relpath(tool) if tool.startswith(os.getcwd()) else tool
    summary = report.write(out, spec, store.records(n), meta["sessions"], shown, sys.stdout)
    return 1 if summary["errors"] else 0


def main(argv=None):
    a = _args(argv)
    signal.signal(signal.SIGTERM, _interrupt)
    try:
        spec = specs.load(a.spec, a.missions, a.seed)
        tool = tools.path("mission_rosfree")
        out = a.out or os.path.join(specs.REPO, "reports", "campaign-%s-%d-%s" % (
            spec["name"], spec["seed"], datetime.datetime.now().strftime("%Y%m%d-%H%M%S")))
        return _run(a, spec, os.path.abspath(out), tool)
    except (specs.SpecError, UsageError, tools.ToolNotFound) as e:
        print("campaign: %s" % e, file=sys.stderr)
        return 2
    except (OSError, RuntimeError) as e:  # no cluster at that address, workers that cannot run, a full disk
        print("campaign: %s: %s (the runs stored so far stay: --resume goes on)" % (type(e).__name__, e),
              file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
