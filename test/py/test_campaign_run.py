"""Campaigns end to end (docs/campaign.md): 50 missions on the local cores and their report; an interrupted campaign
resumes without losing or repeating a run; a Dask cluster (a scheduler and two workers, separate processes on
loopback) gives the same per-run records as the local pool, also when one worker is killed while it runs a mission."""
import json
import os
import re
import shutil
import signal
import subprocess
import sys

import pytest

from offshore_gnc import tools
from offshore_gnc.campaign import runs
from offshore_gnc.testing.masters import descendants, free_port, kill_tree
from offshore_gnc.testing.poll import wait_until

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SMOKE = os.path.join(REPO, "config", "campaigns", "smoke.yaml")
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join([os.path.join(REPO, "python")] +
                                                   os.environ.get("PYTHONPATH", "").split(os.pathsep)))
TIMEOUT_S = 600


def campaign(*args):
    return [sys.executable, "-m", "offshore_gnc.campaign", SMOKE, "--quiet"] + [str(a) for a in args]


def stored(out):
    """{index: record without its wall times and host}."""
    return {r["index"]: runs.comparable(r) for r in runs.Store(str(out)).records(10 ** 6)}


def last_json(text):
    return json.loads(text.strip().splitlines()[-1])


def wait_for(what, condition, timeout=TIMEOUT_S):
    assert wait_until(condition, timeout, step=0.2), "gave up waiting for " + what


@pytest.fixture(scope="module")
def local50(tmp_path_factory):
    try:
        tools.path("mission_rosfree")
    except tools.ToolNotFound as e:
        pytest.fail("a campaign needs the built mission_rosfree: %s" % e)
    out = tmp_path_factory.mktemp("campaign") / "local"
    r = subprocess.run(campaign("--missions", 50, "--jobs", 2, "--out", out), stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, env=ENV, timeout=TIMEOUT_S)
    assert r.returncode == 0, r.stderr[-3000:]
    return out, last_json(r.stdout), stored(out)


def test_fifty_missions_and_their_report(local50):
    out, last, records = local50
    assert last["missions"] == 50 and sorted(records) == list(range(50))
    assert set(last["outcomes"]) == set(runs.OUTCOMES) and sum(last["outcomes"].values()) == 50
    assert last["errors"] == 0  # mission_rosfree accepted every generated scenario
    assert last["successes"] > 0 and last["collisions"] == last["outcomes"]["collision"]
    assert 0 <= last["success_rate_ci_low"] <= last["success_rate"] <= last["success_rate_ci_high"] <= 1
    assert last["missions_per_s"] > 0
    for f in ("report.md", "report.json", "metrics.png", "success_by_variable.png", "campaign.json"):
        assert os.path.getsize(os.path.join(out, f)) > 0, f
    assert len(os.listdir(os.path.join(out, "scenarios"))) == 50
    md = open(os.path.join(out, "report.md")).read()
    assert len(re.findall(r"^  replay: .*mission_rosfree --scenario .*run_\d{6}\.yaml --auv-model \w+ --seed \d+",
                          md, re.M)) == 10


def test_an_interrupted_campaign_resumes_without_losing_or_repeating_a_run(local50, tmp_path):
    out, n = tmp_path / "resumed", 8
    p = subprocess.Popen(campaign("--missions", n, "--jobs", 2, "--out", out), stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True, env=ENV)
    try:
        wait_for("3 stored runs", lambda: os.path.isdir(out / "runs") and len(runs.Store(str(out)).done()) >= 3)
        p.send_signal(signal.SIGTERM)
        _, err = p.communicate(timeout=60)
    finally:
        kill_tree(p.pid)
    assert p.returncode == 130, err
    first = runs.Store(str(out)).done()
    assert 3 <= len(first) < n, "interrupted too late to test a resume: %d of %d runs stored" % (len(first), n)
    again = subprocess.run(campaign("--missions", n, "--jobs", 2, "--out", out), stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, env=ENV)
    assert again.returncode == 2 and "--resume" in again.stderr  # never mixed into a campaign by accident
    r = subprocess.run(campaign("--missions", n, "--jobs", 2, "--out", out, "--resume"), stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, env=ENV, timeout=TIMEOUT_S)
    assert r.returncode == 0, r.stderr[-3000:]
    assert last_json(r.stdout)["missions"] == n
    sessions = json.load(open(out / "campaign.json"))["sessions"]
    assert [s["ran"] for s in sessions] == [len(first), n - len(first)]  # the second ran only what was missing
    assert stored(out) == {i: local50[2][i] for i in range(n)}
    assert not [f for f in os.listdir(out / "runs") if not re.fullmatch(r"run_\d{6}\.json", f)]


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """tcp://127.0.0.1:PORT of a scheduler and two one-thread workers (each under its nanny, which restarts it)."""
    try:
        import distributed
    except ImportError:
        pytest.fail("python3-distributed is not installed (./scripts/setup installs it)")
    for cli in ("dask-scheduler", "dask-worker"):
        if not shutil.which(cli):
            pytest.fail("%s not found (python3-distributed provides it)" % cli)
    logs = tmp_path_factory.mktemp("dask")
    address = "tcp://127.0.0.1:%d" % free_port()
    procs = [subprocess.Popen(["dask-scheduler", "--host", "127.0.0.1", "--port", address.rsplit(":", 1)[1],
                               "--no-dashboard"], stdout=open(logs / "scheduler.log", "w"), stderr=subprocess.STDOUT,
                              env=ENV, start_new_session=True)]
    procs += [subprocess.Popen(["dask-worker", address, "--nthreads", "1", "--no-dashboard", "--name", "w%d" % i,
                                "--local-directory", str(logs / ("w%d" % i))], stdout=open(logs / ("w%d.log" % i), "w"),
                               stderr=subprocess.STDOUT, env=ENV, start_new_session=True) for i in range(2)]
    try:
        with distributed.Client(address, timeout=60) as c:
            c.wait_for_workers(2, timeout=60)
        yield address
    finally:
        for p in procs:
            kill_tree(p.pid)


@pytest.fixture(scope="module")
def killed_worker_campaign(cluster, tmp_path_factory):
    """A 12-mission campaign on the cluster, one worker SIGKILLed while it runs a mission: (out, last JSON line,
    the run it was running)."""
    import distributed
    out = tmp_path_factory.mktemp("campaign") / "dask"
    log = open(out.parent / "dask_campaign.out", "w+")
    p = subprocess.Popen(campaign("--missions", 12, "--scheduler", cluster, "--out", out), stdout=log,
                         stderr=subprocess.PIPE, text=True, env=ENV)
    with distributed.Client(cluster, timeout=60) as c:
        workers = list(c.run(os.getpid).values())

    def busy():  # a worker and the run index of the mission it is running
        for w in workers:
            for child in descendants(w)[1:]:
                cmd = open("/proc/%d/cmdline" % child).read().split("\0") if os.path.exists("/proc/%d" % child) else []
                m = [re.search(r"run_(\d{6})\.yaml$", a) for a in cmd]
                if any(m):
                    return w, int(next(x for x in m if x).group(1))
        return None
    try:
        wait_for("2 stored runs", lambda: os.path.isdir(out / "runs") and len(runs.Store(str(out)).done()) >= 2)
        wait_for("a worker running a mission", busy)
        victim, index = busy()
        os.kill(victim, signal.SIGKILL)
        _, err = p.communicate(timeout=TIMEOUT_S)
    finally:
        kill_tree(p.pid)
    assert p.returncode == 0, err[-3000:]
    log.seek(0)
    return out, last_json(log.read()), index


def test_the_cluster_gives_the_local_pools_records(local50, killed_worker_campaign):
    out, _, _ = killed_worker_campaign
    assert stored(out) == {i: local50[2][i] for i in range(12)}


def test_a_worker_killed_mid_run_loses_no_run_and_counts_none_twice(killed_worker_campaign):
    out, last, index = killed_worker_campaign
    assert sorted(runs.Store(str(out)).done()) == list(range(12))
    assert index in runs.Store(str(out)).done()  # the run it was running was redone elsewhere
    assert last["missions"] == 12 and sum(last["outcomes"].values()) == 12
    assert json.load(open(out / "campaign.json"))["sessions"][0]["ran"] == 12
