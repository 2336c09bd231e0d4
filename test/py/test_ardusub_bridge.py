"""The ArduSub bridge (python/offshore_gnc/ardusub) against a MAVLink v2 peer on loopback UDP that behaves as
ArduSub does for the messages the bridge uses: HEARTBEAT (type SUBMARINE, armed flag, custom mode), ATTITUDE,
SCALED_PRESSURE2, and it acts on RC_CHANNELS_OVERRIDE, COMMAND_LONG ARM_DISARM (with COMMAND_ACK) and SET_MODE.
Real bytes over a real UDP socket, a real rosmaster, the bridge as a real process."""
import os
import threading
import time

import pytest

from offshore_gnc.testing import MasterSet, wait_until  # noqa: E402
from offshore_gnc.testing.ardusub_peer import FakeArduSub, free_udp_port  # noqa: E402

WATCHDOG = 1.0
HEARTBEAT_TIMEOUT = 2.0


def wait(pred, timeout):
    return wait_until(pred, timeout, step=0.05)


@pytest.fixture(scope="module")
def rig():
    with MasterSet(["auv"]) as ms:
        port = free_udp_port()
        ms["auv"].run(["rosrun", "offshore_gnc", "ardusub_bridge.py", "_url:=udpin:127.0.0.1:%d" % port,
                       "_watchdog_timeout:=%s" % WATCHDOG, "_heartbeat_timeout:=%s" % HEARTBEAT_TIMEOUT,
                       "_pilot_timeout:=0.5", "_startup_timeout:=30.0"], name="bridge")
        peer = FakeArduSub(port)
        os.environ["ROS_MASTER_URI"] = ms["auv"].uri
        os.environ["ROS_IP"] = "127.0.0.1"
        import rospy
        from diagnostic_msgs.msg import DiagnosticArray
        from sensor_msgs.msg import FluidPressure, Imu

        from offshore_gnc.msg import RcChannels
        rospy.init_node("test_ardusub", anonymous=True, disable_signals=True)
        got = {"diag": [], "imu": [], "pressure": []}
        lock = threading.Lock()

        def store(k):
            def cb(m):
                with lock:
                    got[k].append((time.time(), m))
            return cb
        subs = [rospy.Subscriber("/diagnostics", DiagnosticArray, store("diag")),
                rospy.Subscriber("/auv/imu", Imu, store("imu")),
                rospy.Subscriber("/auv/pressure", FluidPressure, store("pressure"))]
        pub = rospy.Publisher("/auv/rc_channels", RcChannels, queue_size=50)
        assert wait(lambda: pub.get_num_connections() > 0, 30), open(ms["auv"].log_path("bridge")).read()
        # The bridge publishes diagnostics once it has found the autopilot (before that it drops commands).
        assert wait(lambda: got["diag"], 30), open(ms["auv"].log_path("bridge")).read()
        try:
            yield {"peer": peer, "pub": pub, "got": got, "lock": lock, "RcChannels": RcChannels, "ms": ms}
        finally:
            for s in subs:
                s.unregister()
            peer.close()


def command(rig, values, rate=10.0):
    """Publish RC channel commands at `rate`, one per value list; returns the time of the last one."""
    for v in values:
        m = rig["RcChannels"]()
        m.channels = v
        rig["pub"].publish(m)
        last = time.time()
        time.sleep(1.0 / rate)
    return last


def test_overrides_mirror_our_commands_then_watchdog_neutral_and_disarm(rig):
    peer = rig["peer"]
    n0 = len(peer.snapshot()[0])
    values = [[1500, 1500, 1500 + i, 1450, 1600 + 5 * i, 1500, 1500, 1500] for i in range(30)]
    last = command(rig, values)
    assert wait(lambda: len(peer.snapshot()[0]) >= n0 + 30, 5)
    overrides, arms, modes, armed = peer.snapshot()
    ours = [o for o in overrides[n0:] if o[1] in values]
    # Every command arrives once, in order, with its values: the override stream runs at the controller's rate.
    assert [o[1] for o in ours] == values
    gaps = [b[0] - a[0] for a, b in zip(ours, ours[1:])]
    assert 0.05 < sum(gaps) / len(gaps) < 0.2, gaps
    # Commands flowing: the bridge armed the vehicle and asked for MANUAL (19) mode.
    assert any(a[1] for a in arms) and armed
    assert any(m[1] == 19 for m in modes)
    # Commands stop: within the watchdog time every channel goes neutral and the vehicle is disarmed.
    assert wait(lambda: not peer.snapshot()[3], WATCHDOG + 3.0)
    overrides, arms, _, armed = peer.snapshot()
    disarm_t = [a[0] for a in arms if not a[1] and a[0] > last][0]
    neutral = [o for o in overrides if o[0] > last and o[1] == [1500] * 8]
    assert neutral, overrides[-3:]
    assert WATCHDOG - 0.3 <= disarm_t - last <= WATCHDOG + 1.0, disarm_t - last
    assert neutral[0][0] - last <= WATCHDOG + 1.0
    assert not armed


def test_attitude_and_pressure_come_in_as_imu_and_fluid_pressure(rig):
    got, lock = rig["got"], rig["lock"]
    assert wait(lambda: len(got["imu"]) > 5 and len(got["pressure"]) > 2, 10)
    with lock:
        imu = got["imu"][-1][1]
        p = got["pressure"][-1][1]
    assert imu.header.frame_id == "auv/base_link"
    assert abs(p.fluid_pressure - 130000.0) < 1e-6
    # yaw 1.2 rad NED -> ENU yaw pi/2 - 1.2; the quaternion is a unit one
    q = imu.orientation
    assert abs(q.x ** 2 + q.y ** 2 + q.z ** 2 + q.w ** 2 - 1.0) < 1e-9
    import math
    yaw_enu = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2))
    assert abs(yaw_enu - (math.pi / 2 - 1.2)) < 0.01
    assert abs(imu.angular_velocity.z + 0.1) < 1e-6  # FRD r -> FLU -r


def test_the_pilots_gamepad_wins(rig):
    peer = rig["peer"]
    command(rig, [[1500, 1500, 1550, 1500, 1650, 1500, 1500, 1500]] * 10)
    with peer.lock:
        peer.pilot_until = time.time() + 3.0
    t0 = time.time()
    assert wait(lambda: any(o[0] > t0 and o[1] == [0] * 8 for o in peer.snapshot()[0]), 3), "no release"
    released = [o[0] for o in peer.snapshot()[0] if o[0] > t0 and o[1] == [0] * 8][0]
    command(rig, [[1500, 1500, 1560, 1500, 1660, 1500, 1500, 1500]] * 10)  # we keep commanding
    overrides = peer.snapshot()[0]
    assert not [o for o in overrides if o[0] > released + 0.3 and o[1][2] == 1560], "our override fought the pilot"
    # The pilot lets go: ours flow again.
    assert wait(lambda: time.time() > peer.pilot_until + 1.0, 6)
    t1 = time.time()
    command(rig, [[1500, 1500, 1570, 1500, 1670, 1500, 1500, 1500]] * 5)
    assert wait(lambda: any(o[0] > t1 and o[1][2] == 1570 for o in peer.snapshot()[0]), 3)


def test_heartbeat_loss_is_reported_in_diagnostics(rig):
    peer, got, lock = rig["peer"], rig["got"], rig["lock"]
    with peer.lock:
        peer.heartbeats_on = False
    t0 = time.time()

    def lost():
        with lock:
            return any(t > t0 and s.level == 2 and "HEARTBEAT" in s.message
                       for t, a in got["diag"] for s in a.status if s.name.endswith("ardusub"))
    assert wait(lost, HEARTBEAT_TIMEOUT + 4.0)
    with peer.lock:
        peer.heartbeats_on = True

    def back():
        with lock:
            return any(t > time.time() - 1.5 and s.level != 2 for t, a in got["diag"] for s in a.status
                       if s.name.endswith("ardusub"))
    assert wait(back, 6.0)


def test_a_missing_link_fails_naming_it():
    with MasterSet(["auv"]) as ms:
        port = free_udp_port()
        silent = ms["auv"].run(["rosrun", "offshore_gnc", "ardusub_bridge.py", "_url:=udpin:127.0.0.1:%d" % port,
                                "_startup_timeout:=2.0", "__name:=silent_bridge"], name="silent")
        serial = ms["auv"].run(["rosrun", "offshore_gnc", "ardusub_bridge.py", "_url:=/dev/ttyNO_PIXHAWK",
                                "__name:=serial_bridge"], name="serial")
        assert silent.wait(30) != 0 and serial.wait(30) != 0
        log = open(ms["auv"].log_path("silent")).read()
        assert "no HEARTBEAT from the autopilot on 'udpin:127.0.0.1:%d'" % port in log, log
        log = open(ms["auv"].log_path("serial")).read()
        assert "cannot start on '/dev/ttyNO_PIXHAWK'" in log, log
