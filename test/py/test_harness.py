"""Demonstrates and checks the multi-master harness with real masters and the WorldFrames nodelet."""
import os
import socket
import time

import pytest

from offshore_gnc import VEHICLES
from offshore_gnc.testing import MasterSet, wait_until


def _port_free(port):
    with socket.socket() as s:
        try:
            s.bind(("127.0.0.1", port))
            return True
        except OSError:
            return False


def _frames(master, lat, lon):
    master.set_param("/site/origin", "%f,%f" % (lat, lon))
    return master.run(["rosrun", "nodelet", "nodelet", "standalone", "offshore_gnc/WorldFrames"], name="frames")


def test_two_masters_are_isolated():
    with MasterSet(VEHICLES) as ms:
        assert ms["usv"].port != ms["auv"].port
        _frames(ms["usv"], 61.45, 23.72)
        _frames(ms["auv"], 60.10, 24.90)
        usv = ms["usv"].wait_for_message("/origin", timeout=20)
        auv = ms["auv"].wait_for_message("/origin", timeout=20)
        assert usv["latitude"] == pytest.approx(61.45)
        assert auv["latitude"] == pytest.approx(60.10)
        # the AUV's master knows nothing of the USV's publishers and vice versa
        assert "/origin" in ms["usv"].topics() and "/origin" in ms["auv"].topics()
        rc, out = ms["usv"].call(["rosnode", "list"])
        assert rc == 0 and out.count("/") >= 1
        pub = ms["usv"].publish("/only_on_usv", "std_msgs/String", {"data": "hello"})
        assert ms["usv"].wait_for_topic("/only_on_usv", timeout=10)
        assert "/only_on_usv" not in ms["auv"].topics()
        assert pub.poll() is None


def test_teardown_even_when_the_body_fails():
    procs, ports = [], []
    with pytest.raises(RuntimeError, match="deliberate"):
        with MasterSet(["a", "b"]) as ms:
            ports = [ms["a"].port, ms["b"].port]
            procs = [ms["a"].run(["sleep", "600"], name="sleeper"), ms["b"].run(["sleep", "600"], name="sleeper")]
            raise RuntimeError("deliberate failure inside the test body")
    for p in procs:
        assert p.poll() is not None, "process survived teardown"
    assert wait_until(lambda: all(_port_free(p) for p in ports), 5), "a master still holds its port"


def test_invalid_parameter_stops_the_nodelet_with_its_name():
    with MasterSet(["usv"]) as ms:
        p = _frames(ms["usv"], 123.0, 23.0)  # latitude out of range
        assert p.wait(30) != 0
        log = open(ms["usv"].log_path("frames")).read()
        assert "origin/latitude" in log and "out of range" in log


def test_four_masters():
    names = ["usv", "auv1", "auv2", "station"]
    with MasterSet(names) as ms:
        assert len({ms[n].port for n in names}) == 4
        for n in names:
            assert ms[n].is_online()
    for n in names:
        assert not ms[n].is_online()


def _live_members(pgid):
    """Processes of a group that are still running (zombies reparented to a non-reaping init don't count)."""
    live = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            fields = open("/proc/%s/stat" % pid).read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":
            live.append(int(pid))
    return live


def test_child_process_group_is_killed():
    # a launcher whose child ignores SIGINT still dies: SIGTERM / SIGKILL follow within the grace period
    with MasterSet(["usv"]) as ms:
        p = ms["usv"].run(["bash", "-c", "trap '' INT; sleep 600 & wait"], name="stubborn")
        time.sleep(0.3)
        pgid = os.getpgid(p.pid)
        assert len(_live_members(pgid)) == 2
    assert _live_members(pgid) == []
