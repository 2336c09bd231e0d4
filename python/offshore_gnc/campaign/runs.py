"""One run of a campaign (mission_rosfree on run i's generated scenario, in a subprocess), its outcome class, and
the store that keeps one JSON file per run."""
import hashlib
import json
import os
import socket
import subprocess
import tempfile
import threading
import time

from offshore_gnc import tools
from offshore_gnc.campaign import generate

OUTCOMES = ("success", "collision", "missed_target", "wrong_target", "off_station", "safety_abort", "timeout",
            "stack_died")  # closed_loop/outcome.h's
RUN_TIMEOUT_S = 900.0  # wall time; a mission takes 1-10 s, so this only catches a hung process
# What differs between two runs of the same (spec, index): when and where they ran.
VOLATILE = ("run_wall_s", "host")
VOLATILE_RESULT = ("wall_time_s",)

_live = set()  # running mission processes of this process (the local pool kills them on an interrupt)
_live_lock = threading.Lock()


def outcome_class(result, returncode):
    """The run's outcome class (one of OUTCOMES): mission_rosfree's `outcome` (closed_loop/outcome.h); a run that
    never ran (refused its scenario or options, crashed, hung) is stack_died."""
    if result is None or returncode not in (0, 1) or result.get("outcome") not in OUTCOMES:
        return "stack_died"
    return result["outcome"]


def scenario_file(index):
    """Run `index`'s scenario file, relative to the campaign's folder."""
    return os.path.join("scenarios", "run_%06d.yaml" % index)


def _mission(argv):
    """(returncode or None when killed for hanging, stdout, stderr) of one mission process."""
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    with _live_lock:
        _live.add(p)
    try:
        out, err = p.communicate(timeout=RUN_TIMEOUT_S)
        return p.returncode, out, err
    except subprocess.TimeoutExpired:
        p.kill()
        out, err = p.communicate()
        return None, out, err + "\nkilled after %.0f s of wall time" % RUN_TIMEOUT_S
    finally:
        with _live_lock:
            _live.discard(p)


def kill_running():
    with _live_lock:
        for p in _live:
            p.kill()


def _tool(fallback):
    """This machine's mission_rosfree (a Dask worker's own workspace), else the path the client found."""
    try:
        return tools.path("mission_rosfree")
    except tools.ToolNotFound:
        return fallback


def _last_json(text):
    for line in reversed(text.strip().splitlines()):
        try:
            v = json.loads(line)
            return v if isinstance(v, dict) else None
        except ValueError:
            continue
    return None


def run_one(spec, index, tool=None):
    """Run `index` of the campaign `spec` (spec.load's dict) and its record. A pure function of (spec, index) but for
    the VOLATILE keys, wherever it runs: the scenario is generated here from the spec, never read from a disk."""
    run = generate.generate(spec, index)
    text = generate.scenario_text(spec, index, run)
    opts = run["options"]
    with tempfile.TemporaryDirectory(prefix="campaign-run-") as tmp:
        path = os.path.join(tmp, os.path.basename(scenario_file(index)))
        with open(path, "w") as f:
            f.write(text)
        argv = [_tool(tool) or "mission_rosfree", "--scenario", path, "--auv-model", opts["auv_model"],
                "--seed", str(opts["seed"])] + [a for fault in opts["faults"] for a in ("--fault", fault)]
        t0 = time.monotonic()
        try:
            rc, out, err = _mission(argv)
        except OSError as e:  # no such tool here
            rc, out, err = None, "", "cannot start %s: %s" % (argv[0], e)
        wall = time.monotonic() - t0
    result = _last_json(out)
    outcome = outcome_class(result, rc)
    ran = result is not None and rc in (0, 1)
    return {"index": index, "outcome": outcome, "options": opts, "variables": run["variables"],
            "scenario": scenario_file(index), "scenario_sha256": hashlib.sha256(text.encode()).hexdigest(),
            "returncode": rc, "result": result,
            # a run that never ran (refused, crashed, hung): its reason, for the report's list of errors
            "error": None if ran else (err.strip()[-2000:] or "exit %s, no JSON line" % rc),
            "run_wall_s": round(wall, 3), "host": socket.gethostname()}


def comparable(record):
    """The record without what depends on when and where it ran (for comparing two runs of the same index)."""
    r = {k: v for k, v in record.items() if k not in VOLATILE}
    if r.get("result"):
        r["result"] = {k: v for k, v in r["result"].items() if k not in VOLATILE_RESULT}
    return r


def write_atomic(path, text):
    """Write via a temporary file in the same folder and a rename: a reader (or a resumed campaign) sees the old file
    or the whole new one, never half of it."""
    d = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp-", suffix=os.path.basename(path))
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


class Store:
    """OUT/runs/run_NNNNNN.json, one per run index: a run is stored once it finished, and stored again (with the same
    content) only if it was run again, so a campaign counts each index once however often it was interrupted."""

    def __init__(self, out):
        self.dir = os.path.join(out, "runs")
        os.makedirs(self.dir, exist_ok=True)

    def path(self, index):
        return os.path.join(self.dir, "run_%06d.json" % index)

    def done(self):
        return {int(f[4:10]) for f in os.listdir(self.dir) if f.startswith("run_") and f.endswith(".json")}

    def put(self, record):
        write_atomic(self.path(record["index"]), json.dumps(record, sort_keys=True) + "\n")

    def records(self, missions):
        """The stored records of runs 0..missions-1, in index order."""
        out = []
        for i in sorted(i for i in self.done() if i < missions):
            with open(self.path(i)) as f:
                out.append(json.load(f))
        return out
