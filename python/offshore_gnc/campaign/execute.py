"""Running a campaign's runs: on the local cores (a pool of J mission processes) or on an existing Dask cluster's
workers. Both call runs.run_one, so a run's record is the same wherever it ran; each is stored as it arrives."""
import concurrent.futures
import sys
import time
import uuid

from offshore_gnc.campaign import runs

RESUBMIT = 3  # a run whose worker died this many more times than Dask itself retries is an error, not a loop


def local_runs(spec, todo, jobs, tool):
    """Records of runs `todo` as they finish, J at a time. Threads suffice: each waits on its own mission process.
    On an interrupt the pending runs are dropped and the running processes killed (their runs are redone on
    --resume, none is stored half)."""
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=jobs)
    try:
        futures = [pool.submit(runs.run_one, spec, i, tool) for i in todo]
        for f in concurrent.futures.as_completed(futures):
            yield f.result()
    finally:
        pool.shutdown(wait=False, cancel_futures=True)
        runs.kill_running()


def dask_runs(spec, todo, address, tool):
    """Records of runs `todo` from the Dask cluster at `address`, as they finish. A worker killed mid-run: the
    scheduler gives its runs to another worker (up to its allowed-failures), and a run that still fails
    (KilledWorker, a lost connection) is submitted again, RESUBMIT times at most."""
    from distributed import Client, as_completed  # python3-distributed: only a cluster campaign needs it

    def can_run():  # on each worker before any mission; nested, so Dask ships it by value, not by module
        try:
            import offshore_gnc.campaign.runs  # noqa: F401 (the tasks' own module)
        except ImportError as e:
            return "cannot import offshore_gnc.campaign (%s): start the worker with the workspace sourced" % e
        return None

    with Client(address, timeout=30) as client:
        problems = {w: p for w, p in client.run(can_run).items() if p}
        if problems:
            raise RuntimeError("Dask workers cannot run missions: " +
                               "; ".join("%s: %s" % kv for kv in problems.items()))
        session = uuid.uuid4().hex[:8]

        def submit(i, attempt):
            return client.submit(runs.run_one, spec, i, tool, key="campaign-%s-%d-%d" % (session, i, attempt),
                                 pure=False)
        futures = {submit(i, 0): i for i in todo}
        attempts = {}
        pending = as_completed(list(futures))
        for f in pending:
            i = futures.pop(f)
            try:
                record = f.result()
            except Exception as e:  # the task's worker died too often, or the task raised
                attempts[i] = attempts.get(i, 0) + 1
                if attempts[i] > RESUBMIT:
                    raise RuntimeError("run %d failed on the cluster %d times, last: %r" % (i, attempts[i], e))
                again = submit(i, attempts[i])
                futures[again] = i
                pending.add(again)
                continue
            finally:
                f.release()
            yield record


class Progress:
    """One updating line on a terminal; a line every `every_s` seconds (and at the end) otherwise. On stderr: stdout
    is the report's."""

    def __init__(self, total, done, stream=sys.stderr, every_s=10.0, quiet=False):
        self.total, self.done, self.ran, self.ok = total, done, 0, 0
        self.stream, self.every_s, self.quiet = stream, every_s, quiet
        self.tty = stream.isatty()
        self.t0 = self.last = time.monotonic()
        self.width = 0

    def update(self, record):
        self.done += 1
        self.ran += 1
        self.ok += record["outcome"] == "success"
        now = time.monotonic()
        if self.tty or now - self.last >= self.every_s or self.done == self.total:
            self.last = now
            self._show(now)

    def _show(self, now):
        if self.quiet:
            return
        rate = self.ran / max(now - self.t0, 1e-9)
        eta = (self.total - self.done) / rate if rate > 0 else 0.0
        bar = "#" * int(30 * self.done / self.total)
        line = "[%-30s] %d/%d runs, %d of this session's %d successful, %.2f missions/s, %d min %02d s to go" % (
            bar, self.done, self.total, self.ok, self.ran, rate, eta // 60, eta % 60)
        if self.tty:
            self.stream.write("\r" + line.ljust(self.width))
            self.width = len(line)
        else:
            self.stream.write(line + "\n")
        self.stream.flush()

    def close(self):
        if self.tty and self.width and not self.quiet:
            self.stream.write("\n")
            self.stream.flush()
