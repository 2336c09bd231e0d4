#!/usr/bin/python3
"""Plays the USV and the AUV (analytic trajectories) and checks the USBL node's fixes against the AUV's ground
truth at each fix's time stamp: position in map_ned within 2.0 m per fix (sim noise 0.05 m range, 0.5 deg
angles at 30-70 m range: about 0.6 m 1-sigma across track), mean error within 0.8 m, WGS84 consistent with
NED, PING_ERROR timeouts from the simulated dropouts counted in diagnostics."""
import math
import threading
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import QuaternionStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import FluidPressure, NavSatFix, NavSatStatus
from nodelet.srv import NodeletLoad, NodeletUnload
from std_msgs.msg import UInt8MultiArray

from offshore_gnc.msg import UsblFix

LAT0, LON0 = 61.4507, 23.7270
A, E2 = 6378137.0, 6.69437999014e-3


def ned_to_wgs84(n, e):
    """Local tangent plane -> WGS84 with the meridian/prime-vertical radii at the origin (mm-level at 100 m)."""
    s = math.sin(math.radians(LAT0))
    rn = A / math.sqrt(1 - E2 * s * s)
    rm = rn * (1 - E2) / (1 - E2 * s * s)
    return LAT0 + math.degrees(n / rm), LON0 + math.degrees(e / (rn * math.cos(math.radians(LAT0))))


def usv_enu(t):
    """USV on a 20 m circle at 0.05 rad/s, heading along the track (ENU yaw)."""
    w = 0.05
    return (20 * math.cos(w * t), 20 * math.sin(w * t), 0.0), w * t + math.pi / 2


def auv_enu(t):
    return (40 + 0.5 * t, 30.0, -15.0)


class UsblSimTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("check_usbl_sim")
        cls.lock = threading.Lock()
        cls.fixes = []
        cls.diag = {}
        rospy.Subscriber("/auv/usbl/fix", UsblFix, cls.on_fix)
        rospy.Subscriber("/diagnostics", DiagnosticArray, cls.on_diag)
        cls.data_in = []
        rospy.Subscriber("/auv/usbl/data_in", UInt8MultiArray, lambda m: cls.data_in.append(bytes(m.data)))
        cls.data_out = rospy.Publisher("/auv/usbl/data_out", UInt8MultiArray, queue_size=10)
        cls.remote_queue = rospy.Publisher("/auv/usbl/sim_remote_queue", UInt8MultiArray, queue_size=1, latch=True)
        cls.pubs = dict(
            usv_gt=rospy.Publisher("/usv/ground_truth/odom", Odometry, queue_size=10),
            auv_gt=rospy.Publisher("/auv/ground_truth/odom", Odometry, queue_size=10),
            gps=rospy.Publisher("/usv_gps", NavSatFix, queue_size=10),
            heading=rospy.Publisher("/usv_heading", QuaternionStamped, queue_size=10),
            pressure=rospy.Publisher("/auv/pressure", FluidPressure, queue_size=10))
        cls.t0 = rospy.get_time()
        cls.timer = rospy.Timer(rospy.Duration(0.05), cls.publish)

    @classmethod
    def on_fix(cls, m):
        with cls.lock:
            cls.fixes.append(m)

    @classmethod
    def on_diag(cls, m):
        for s in m.status:
            if "usbl" in s.name and "sim" not in s.name:
                with cls.lock:
                    cls.diag = {kv.key: kv.value for kv in s.values}

    @classmethod
    def publish(cls, _):
        now = rospy.Time.now()
        t = now.to_sec() - cls.t0
        (x, y, z), yaw = usv_enu(t)
        q = (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
        for name, pos, quat in (("usv", (x, y, z), q), ("auv", auv_enu(t), (0.0, 0.0, 0.0, 1.0))):
            o = Odometry()
            o.header.stamp, o.header.frame_id, o.child_frame_id = now, "map", name + "/base_link"
            o.pose.pose.position.x, o.pose.pose.position.y, o.pose.pose.position.z = pos
            o.pose.pose.orientation.x, o.pose.pose.orientation.y, o.pose.pose.orientation.z, o.pose.pose.orientation.w = quat
            cls.pubs[name + "_gt"].publish(o)
        g = NavSatFix()
        g.header.stamp, g.header.frame_id = now, "usv/gps"
        g.status.status = NavSatStatus.STATUS_FIX
        g.latitude, g.longitude = ned_to_wgs84(y, x)
        g.altitude = z
        cls.pubs["gps"].publish(g)
        h = QuaternionStamped()
        h.header.stamp, h.header.frame_id = now, "map"
        h.quaternion.x, h.quaternion.y, h.quaternion.z, h.quaternion.w = q
        cls.pubs["heading"].publish(h)
        p = FluidPressure()
        p.header.stamp = now
        p.fluid_pressure = 101325.0 + 1000.0 * 9.80665 * -auv_enu(t)[2]
        cls.pubs["pressure"].publish(p)

    def test_fixes_match_ground_truth(self):
        deadline = rospy.get_time() + 60
        while rospy.get_time() < deadline and not rospy.is_shutdown():
            with self.lock:
                ok = [f for f in self.fixes if f.quality == UsblFix.QUALITY_OK]
                diag = dict(self.diag)
            if len(ok) >= 25 and int(diag.get("ping_timeouts", "0")) >= 1:
                break
            rospy.sleep(0.2)
        self.assertGreaterEqual(len(ok), 25, "accepted fixes: %d of %d, diag %s" % (len(ok), len(self.fixes), diag))
        errors = []
        for f in ok:
            ax, ay, az = auv_enu(f.header.stamp.to_sec() - self.t0)
            truth_ned = (ay, ax, -az)
            p = f.position_ned
            err = math.sqrt((p.x - truth_ned[0]) ** 2 + (p.y - truth_ned[1]) ** 2 + (p.z - truth_ned[2]) ** 2)
            errors.append(err)
            self.assertLess(err, 2.0, "fix %s vs truth %s" % ((p.x, p.y, p.z), truth_ned))
            lat, lon = ned_to_wgs84(p.x, p.y)
            self.assertAlmostEqual(f.latitude, lat, delta=1e-6)
            self.assertAlmostEqual(f.longitude, lon, delta=2e-6)
            self.assertTrue(30 < f.range < 90, f.range)
            self.assertEqual(f.header.frame_id, "usv/usbl")
            self.assertEqual(f.remote_beacon_id, 2)
        mean = sum(errors) / len(errors)
        rospy.loginfo("USBL: %d fixes, mean error %.2f m, max %.2f m", len(errors), mean, max(errors))
        self.assertLess(mean, 0.8)
        # Simulated dropouts reach the node as PING_ERROR (XCVR_RESP_TIMEOUT) and are counted.
        self.assertGreaterEqual(int(diag.get("ping_timeouts", "0")), 1, diag)
        self.assertGreaterEqual(int(diag.get("frames_ok", "0")), len(ok))
        self.assertEqual(int(diag.get("bad_crc", "0")), 0)

    def test_acoustic_data_channel(self):
        """A small packet (a target position) requested from the AUV's beacon crosses without the tether."""
        packet = bytes([0x54, 0x47]) + (1234).to_bytes(2, "little") + (-567 & 0xFFFF).to_bytes(2, "little")
        self.remote_queue.publish(UInt8MultiArray(data=list(packet)))
        # A request that reaches the beacon before its (latched) queue does is answered empty: wait for data.
        received = lambda: [d for d in self.data_in if d]  # noqa: E731
        deadline = rospy.get_time() + 30
        while rospy.get_time() < deadline and not received():
            self.data_out.publish(UInt8MultiArray(data=[1, 2, 3]))  # REQ: the remote answers with its queue
            rospy.sleep(1.0)
        self.assertTrue(received(), "no DAT_RECEIVE with data within 30 s: %s" % self.data_in)
        self.assertEqual(received()[0], packet)

    def test_serial_device_replugged(self):
        """The simulator (the serial device) disappears and comes back: the node reopens the port and fixes resume."""
        rospy.wait_for_service("/usbl_manager/unload_nodelet", 10)
        rospy.ServiceProxy("/usbl_manager/unload_nodelet", NodeletUnload)(name="/usbl_sim")
        deadline = rospy.get_time() + 15
        while rospy.get_time() < deadline:
            with self.lock:
                diag = dict(self.diag)
            if int(diag.get("hangups", "0")) + int(diag.get("io_errors", "0")) >= 1:
                break
            rospy.sleep(0.2)
        self.assertGreaterEqual(int(diag.get("hangups", "0")) + int(diag.get("io_errors", "0")), 1, diag)
        opens_before = int(diag.get("opens", "0"))
        with self.lock:
            n_before = len(self.fixes)
        res = rospy.ServiceProxy("/usbl_manager/load_nodelet", NodeletLoad)(
            name="/usbl_sim", type="offshore_gnc/UsblSim", remap_source_args=[], remap_target_args=[], my_argv=[],
            bond_id="")
        self.assertTrue(res.success)
        deadline = rospy.get_time() + 30
        while rospy.get_time() < deadline:
            with self.lock:
                diag = dict(self.diag)
                n_after = len([f for f in self.fixes[n_before:] if f.quality == UsblFix.QUALITY_OK])
            if n_after >= 3 and int(diag.get("opens", "0")) > opens_before:
                break
            rospy.sleep(0.2)
        self.assertGreaterEqual(n_after, 3, diag)
        self.assertGreater(int(diag.get("opens", "0")), opens_before, diag)


if __name__ == "__main__":
    rostest.rosrun("offshore_gnc", "usbl_sim", UsblSimTest)
