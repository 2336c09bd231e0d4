"""`auv.launch sim:=false` per vehicle, as a user starts it on the vehicle: every hardware node comes up when its
device is there, and the launch stops with a message naming the device when one is absent. The devices are
stand-ins: a pseudo-terminal for the Micron's serial line (the driver opens it; nothing answers, which is not
fatal), the ArduSub-like MAVLink peer on loopback UDP for the aColor's Pixhawk, and a COLA2 navigator stand-in
(cola2_msgs/NavSts by COLA2's type name) for the Girona500."""
import os
import pty
import subprocess
import time

import pytest

from offshore_gnc.testing import MasterSet, wait_until
from offshore_gnc.testing.ardusub_peer import FakeArduSub, free_udp_port

STARTUP = 4.0  # [s] startup_timeout for the autopilot / COLA2
REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture
def sonar_tty(tmp_path):
    """A serial device for the Micron driver: the slave side of a pseudo-terminal, behind a symlink."""
    master, slave = pty.openpty()
    link = str(tmp_path / "micron_tty")
    os.symlink(os.ttyname(slave), link)
    yield link
    os.close(master)
    os.close(slave)


def launch(ms, name, **args):
    args.setdefault("relay", "false")
    args.setdefault("site", os.path.join(REPO, "config", "sites", "pyhajarvi.yaml"))  # a team's site file
    args = {k: v for k, v in args.items() if v is not None}
    return ms["auv"].run(["roslaunch", "offshore_gnc", "auv.launch", "sim:=false"] +
                         ["%s:=%s" % kv for kv in args.items()], name=name)


def log(ms, name):
    with open(ms["auv"].log_path(name), errors="replace") as f:
        return f.read()


def nodes(ms):
    rc, out = ms["auv"].call(["rosnode", "list"], timeout=30)
    return set(out.split())


def assert_fails_naming(ms, proc, name, *needles):
    try:
        proc.wait(120)
    except subprocess.TimeoutExpired:
        pytest.fail("roslaunch did not stop although a device is missing:\n" + log(ms, name)[-3000:])
    text = log(ms, name)
    for n in needles:
        assert n in text, "%r not in the launch output (%d chars):\n%s" % (n, len(text), text[-6000:])


@pytest.fixture
def ms():
    with MasterSet(["auv"]) as m:
        yield m


def test_acolor_starts_every_hardware_node(ms, sonar_tty):
    port = free_udp_port()
    peer = FakeArduSub(port)
    try:
        p = launch(ms, "acolor_ok", vehicle_model="acolor", sonar_port=sonar_tty,
                   mavlink_url="udpin:127.0.0.1:%d" % port, startup_timeout=STARTUP)
        want = {"/auv/micron", "/auv/ardusub_bridge", "/usbl", "/auv/sonar_targets", "/auv/mission"}
        assert wait_until(lambda: want <= nodes(ms), 90, step=0.2), (nodes(ms), log(ms, "acolor_ok")[-3000:])
        time.sleep(STARTUP + 2.0)  # past the autopilot's startup timeout: still running
        assert p.poll() is None, log(ms, "acolor_ok")[-3000:]
        assert want <= nodes(ms)
    finally:
        peer.close()


def test_acolor_without_the_sonar_fails_naming_it(ms):
    port = free_udp_port()
    peer = FakeArduSub(port)
    try:
        # the autopilot's startup timeout well past the sonar's device_wait: on a loaded machine the bridge must not
        # be the first to stop the launch (a CI run saw the launch end without the Micron's message)
        p = launch(ms, "acolor_nosonar", vehicle_model="acolor", sonar_port="/dev/ttyNO_MICRON",
                   mavlink_url="udpin:127.0.0.1:%d" % port, startup_timeout=60.0)
        assert_fails_naming(ms, p, "acolor_nosonar", "cannot open serial device '/dev/ttyNO_MICRON'",
                            "REQUIRED process [auv/micron")
    finally:
        peer.close()


def test_acolor_without_the_autopilot_fails_naming_it(ms, sonar_tty):
    port = free_udp_port()  # nothing sends there
    p = launch(ms, "acolor_nopix", vehicle_model="acolor", sonar_port=sonar_tty,
               mavlink_url="udpin:127.0.0.1:%d" % port, startup_timeout=STARTUP)
    assert_fails_naming(ms, p, "acolor_nopix", "no HEARTBEAT from the autopilot on 'udpin:127.0.0.1:%d'" % port,
                        "REQUIRED process [auv/ardusub_bridge")


def test_girona500_starts_every_hardware_node(ms, sonar_tty):
    nav = ms["auv"].run(["rostopic", "pub", "-r", "10", "/girona500/navigator/navigation", "offshore_gnc/Cola2NavSts",
                         "{origin: {latitude: 61.4507, longitude: 23.727}, position: {north: 1.0, east: 2.0, depth: 3.0}}"],
                        name="fake_cola2")
    p = launch(ms, "g500_ok", vehicle_model="girona500", sonar_port=sonar_tty, startup_timeout=STARTUP)
    want = {"/auv/micron", "/auv/cola2_bridge", "/usbl", "/auv/sonar_targets", "/auv/mission"}
    assert wait_until(lambda: want <= nodes(ms), 90, step=0.2), (nodes(ms), log(ms, "g500_ok")[-3000:])
    time.sleep(STARTUP + 2.0)
    assert p.poll() is None, log(ms, "g500_ok")[-3000:]
    assert want <= nodes(ms)
    odom = ms["auv"].wait_for_message("/auv/odom", timeout=20)
    assert abs(odom["pose"]["pose"]["position"]["x"] - 2.0) < 1e-6  # COLA2's east is our map x
    nav.kill()


def test_girona500_without_cola2_fails_naming_it(ms, sonar_tty):
    p = launch(ms, "g500_nocola2", vehicle_model="girona500", sonar_port=sonar_tty, startup_timeout=STARTUP)
    assert_fails_naming(ms, p, "g500_nocola2", "no COLA2 navigation on /girona500/navigator/navigation",
                        "REQUIRED process [auv/cola2_bridge")


def test_without_a_site_nothing_starts_and_the_launch_says_how_to_set_one(ms, sonar_tty):
    """On hardware the origin comes from the operation (site:=FILE or origin:=LAT,LON[,ALT]), never from a default
    that would put the vehicle in Finland."""
    p = launch(ms, "g500_nosite", vehicle_model="girona500", sonar_port=sonar_tty, startup_timeout=STARTUP, site=None)
    assert_fails_naming(ms, p, "g500_nosite", "no site origin", "origin:=LAT,LON[,ALT]", "REQUIRED process [")


def test_girona500_without_the_sonar_fails_naming_it(ms):
    p = launch(ms, "g500_nosonar", vehicle_model="girona500", sonar_port="/dev/ttyNO_MICRON", startup_timeout=STARTUP)
    assert_fails_naming(ms, p, "g500_nosonar", "cannot open serial device '/dev/ttyNO_MICRON'",
                        "REQUIRED process [auv/micron")
