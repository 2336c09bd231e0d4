"""Start several real ROS masters on free ports, run nodes against each, tear everything down.

Each vehicle of the co-operative system has its own master (thesis chapter 5), so the integration tests need
more than the one master rostest gives. Usage:

    with MasterSet(VEHICLES) as ms:  # offshore_gnc.VEHICLES: usv, auv
        ms["usv"].set_param("/site/origin", "61.4507,23.7270")  # the site (launch/site.launch in a launch file)
        ms["usv"].run(["rosrun", "nodelet", "nodelet", "standalone", "offshore_gnc/WorldFrames"], name="frames")
        msg = ms["usv"].wait_for_message("/origin", timeout=10)

Every process is started in its own process group and killed on exit, also when the test body raises, and
at interpreter exit or SIGTERM as a last resort. Logs go to one folder per MasterSet (kept on failure).
"""
import atexit
import os
import shutil
import signal
import socket
import subprocess
import tempfile
import time

import yaml

from offshore_gnc import VEHICLES

from .poll import wait_until

_LIVE = set()  # every Popen still running, for the atexit / SIGTERM safety net


def free_port():
    """A TCP port that was free a moment ago (bind to 0 and let the kernel choose)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def descendants(pid):
    """pid and every process below it (from /proc). roslaunch starts its nodes in process groups of their own:
    signalling its group does not reach them, and once it is gone they are orphans nobody would stop."""
    children = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open("/proc/%s/stat" % d) as f:
                    ppid = int(f.read().rsplit(")", 1)[1].split()[1])
                children.setdefault(ppid, []).append(int(d))
            except (OSError, ValueError, IndexError):
                pass
    todo, tree = [pid], []
    while todo:
        p = todo.pop()
        tree.append(p)
        todo += children.get(p, [])
    return tree


def kill_tree(pid, sig=signal.SIGKILL):
    for p in descendants(pid):
        try:
            os.kill(p, sig)
        except (ProcessLookupError, PermissionError):
            pass


def run_job(argv, timeout):
    """Runs a command (the mission job) to its end in a session of its own and returns its CompletedProcess
    (stdout and stderr as one text). On timeout its whole process tree (masters, launches, rviz) is killed before
    TimeoutExpired is raised: subprocess.run's timeout killed only the job, and its orphans went on burning both
    cores through the rest of the suite."""
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        out, _ = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        kill_tree(p.pid)
        out, _ = p.communicate()
        raise subprocess.TimeoutExpired(argv, timeout, output=out)
    return subprocess.CompletedProcess(argv, p.returncode, out)


def _kill(proc, grace=5.0):
    """SIGINT the process group (ROS nodes shut down cleanly), then SIGTERM, then SIGKILL; finally SIGKILL
    whatever of its process tree is left."""
    tree = descendants(proc.pid) if proc.poll() is None else []
    if proc.poll() is None:
        for sig, wait in ((signal.SIGINT, grace), (signal.SIGTERM, 2.0), (signal.SIGKILL, 2.0)):
            try:
                os.killpg(proc.pid, sig)
            except ProcessLookupError:
                break
            try:
                proc.wait(wait)
                break
            except subprocess.TimeoutExpired:
                continue
    # children that left the group's leader behind
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    for p in tree[1:]:  # pids of a finished tree may be reused soon, but not within these seconds
        try:
            os.kill(p, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
    _LIVE.discard(proc)


def _kill_all_live(*_):
    for p in list(_LIVE):
        _kill(p, grace=1.0)


atexit.register(_kill_all_live)


class Master:
    """One rosmaster on a free port and the processes run against it."""

    def __init__(self, name, log_dir, port=None):
        self.name = name
        self.port = port or free_port()
        self.uri = "http://127.0.0.1:%d" % self.port
        self.log_dir = log_dir
        self.procs = []

    def env(self, extra=None):
        e = dict(os.environ)
        e["ROS_MASTER_URI"] = self.uri
        e["ROS_IP"] = "127.0.0.1"
        e.pop("ROS_HOSTNAME", None)
        e["ROS_LOG_DIR"] = os.path.join(self.log_dir, "roslog-" + self.name)
        e["PATH"] = "/usr/bin:" + e.get("PATH", "")  # Debian's python3 with the ROS modules
        if extra:
            e.update(extra)
        return e

    def start(self, timeout=15.0):
        self._master = self.run(["rosmaster", "--core", "-p", str(self.port), "-w", "3"], name="rosmaster")
        deadline = time.time() + timeout
        while time.time() < deadline:
            if self.is_online():
                return self
            if self._master.poll() is not None:
                raise RuntimeError("rosmaster %s exited with %s (log: %s)" % (self.name, self._master.returncode,
                                                                             self.log_path("rosmaster")))
            time.sleep(0.05)
        raise RuntimeError("rosmaster %s on port %d did not come up in %.0f s" % (self.name, self.port, timeout))

    def is_online(self):
        import rosgraph
        return rosgraph.Master("/harness", master_uri=self.uri).is_online()

    def log_path(self, name):
        return os.path.join(self.log_dir, "%s-%s.log" % (self.name, name))

    def run(self, cmd, name, env=None):
        """Start cmd (a list) against this master; returns the Popen. Output goes to a log file."""
        log = open(self.log_path(name), "ab")
        p = subprocess.Popen(cmd, env=self.env(env), stdout=log, stderr=subprocess.STDOUT,
                             stdin=subprocess.DEVNULL, start_new_session=True)
        log.close()
        self.procs.append(p)
        _LIVE.add(p)
        return p

    def roslaunch(self, launch_file, args=(), name=None, env=None):
        # no --wait: the master is up already, and with --wait Debian's roslaunch hangs after connecting
        cmd = ["roslaunch", launch_file] + ["%s:=%s" % kv for kv in dict(args).items()]
        return self.run(cmd, name or os.path.basename(launch_file), env=env)

    def call(self, cmd, timeout=30.0, env=None):
        """Run a short command against this master; returns (returncode, output)."""
        r = subprocess.run(cmd, env=self.env(env), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout, stdin=subprocess.DEVNULL)
        return r.returncode, r.stdout.decode(errors="replace")

    def topics(self):
        import rosgraph
        return sorted(t for t, _ in rosgraph.Master("/harness", master_uri=self.uri).getPublishedTopics("/"))

    def wait_for_topic(self, topic, timeout=10.0):
        return wait_until(lambda: topic in self.topics(), timeout)

    def set_param(self, name, value):
        import rosgraph
        rosgraph.Master("/harness", master_uri=self.uri).setParam(name, value)

    def wait_for_param(self, name, timeout=60.0):
        """True once the parameter exists (e.g. /use_sim_time, set by a launch file), False after timeout."""
        import rosgraph
        m = rosgraph.Master("/harness", master_uri=self.uri)

        def has():
            try:
                return m.hasParam(name)
            except OSError:  # the master not up yet
                return False
        return bool(wait_until(has, timeout))

    def wait_for_message(self, topic, timeout=10.0):
        """First message on topic (dict, from rostopic echo), or raise TimeoutError."""
        try:
            rc, out = self.call(["rostopic", "echo", "-n", "1", "--noarr", topic], timeout=timeout)
        except subprocess.TimeoutExpired:
            raise TimeoutError("no message on %s of master %s within %.1f s" % (topic, self.name, timeout))
        if rc != 0:
            raise RuntimeError("rostopic echo %s failed on %s: %s" % (topic, self.name, out))
        return yaml.safe_load(out.split("\n---")[0])

    def publish(self, topic, msg_type, value, latch=True, name=None):
        """Publish one message (YAML/dict) with rostopic pub; latched by default. Returns the Popen."""
        cmd = ["rostopic", "pub"] + (["-l"] if latch else ["-1"]) + [topic, msg_type, yaml.safe_dump(value)]
        return self.run(cmd, name or "pub" + topic.replace("/", "_"))

    def stop(self):
        for p in reversed(self.procs):
            _kill(p)
        self.procs = []


class MasterSet:
    """Context manager: several masters by name; everything torn down on exit, failure or not."""

    def __init__(self, names=VEHICLES, log_dir=None, keep_logs_on_failure=True):
        self._own_dir = log_dir is None
        self.log_dir = log_dir or tempfile.mkdtemp(prefix="offshore_gnc_masters_")
        os.makedirs(self.log_dir, exist_ok=True)
        self.masters = {n: Master(n, self.log_dir) for n in names}
        self.keep_logs_on_failure = keep_logs_on_failure

    def __getitem__(self, name):
        return self.masters[name]

    def __enter__(self):
        try:
            for m in self.masters.values():
                m.start()
        except BaseException:
            self.close()
            raise
        return self

    def __exit__(self, exc_type, exc, tb):
        self.close()
        if exc_type is None and self._own_dir:
            shutil.rmtree(self.log_dir, ignore_errors=True)
        elif exc_type is not None:
            print("MasterSet logs kept in %s" % self.log_dir)
        return False

    def close(self):
        for m in self.masters.values():
            m.stop()
