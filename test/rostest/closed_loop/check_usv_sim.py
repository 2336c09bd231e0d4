#!/usr/bin/python3
"""rostest: the USV simulator's topics (rates in simulated time, frames, ranges, NaN for no return), the map
grid, manual priority inputs, NaN commands rejected and counted, and GPS navigation's /usv/odom + TF."""
import math
import time
import unittest

import rospy
import rostest
import tf2_ros
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import QuaternionStamped
from nav_msgs.msg import OccupancyGrid, Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs import point_cloud2
from sensor_msgs.msg import NavSatFix, PointCloud2

from offshore_gnc.msg import JoystickCommand, WaterjetStatus
from offshore_gnc.testing.poll import wait_until

SIM_SECONDS = 8.0
MANUAL_FROM = 4.5  # simulated time at which the manual joystick takes over


def rate(stamps, t0, t1):
    s = [t for t in stamps if t0 <= t < t1]
    return len(s) / (t1 - t0)


class UsvSim(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        c = cls.got = {k: [] for k in ("clock", "gps", "heading", "odom", "truth", "map", "diag", "jets")}
        cls.lidar_stamps, cls.lidar_last = [], [None]
        subs = [
            rospy.Subscriber("/clock", Clock, lambda m: c["clock"].append(m.clock.to_sec())),
            rospy.Subscriber("/usv_gps", NavSatFix, c["gps"].append),
            rospy.Subscriber("/usv_heading", QuaternionStamped, c["heading"].append),
            rospy.Subscriber("/usv/odom", Odometry, c["odom"].append),
            rospy.Subscriber("/usv/ground_truth/odom", Odometry, c["truth"].append),
            rospy.Subscriber("/usv/map", OccupancyGrid, c["map"].append),
            rospy.Subscriber("/diagnostics", DiagnosticArray, c["diag"].append),
            rospy.Subscriber("/usv/waterjet/status", WaterjetStatus, c["jets"].append),
            rospy.Subscriber("/usv/lidar/points", PointCloud2, cls.on_lidar, queue_size=2),
        ]
        cls.subs = subs
        cls.buf = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.buf)
        auto = rospy.Publisher("/usv/joystick_cmd", JoystickCommand, queue_size=10)
        manual = rospy.Publisher("/usv/manual_cmd", JoystickCommand, queue_size=10)
        wait_until(lambda: auto.get_num_connections() and manual.get_num_connections(), 30, step=0.05)
        cls.wall0 = time.time()
        t_start = c["clock"][-1] if c["clock"] else 0.0
        deadline = cls.wall0 + 60
        sent_nan = False
        while time.time() < deadline and (not c["clock"] or c["clock"][-1] < SIM_SECONDS):
            if not sent_nan:
                auto.publish(JoystickCommand(surge=float("nan")))
                manual.publish(JoystickCommand(surge=0.2, yaw=float("inf")))
                sent_nan = True
            auto.publish(JoystickCommand(surge=0.3, yaw=0.0))
            if c["clock"] and c["clock"][-1] > MANUAL_FROM:  # the operator takes over and turns to starboard
                manual.publish(JoystickCommand(surge=0.3, yaw=0.8, source=JoystickCommand.SOURCE_JOYSTICK,
                                               priority=JoystickCommand.PRIORITY_MANUAL))
            time.sleep(0.05)
        cls.wall = time.time() - cls.wall0
        cls.t_start = t_start
        time.sleep(1.5)  # one more diagnostics period

    @classmethod
    def on_lidar(cls, m):
        cls.lidar_stamps.append(m.header.stamp.to_sec())
        if m.header.stamp.to_sec() < MANUAL_FROM:  # keep a frame from before the turn
            cls.lidar_last[0] = m

    def test_clock_runs_faster_than_real_time(self):
        clk = self.got["clock"]
        self.assertTrue(clk and clk[-1] >= SIM_SECONDS, "clock stopped at %s" % (clk[-1:],))
        self.assertTrue(all(b >= a for a, b in zip(clk, clk[1:])), "clock went backwards")
        self.assertGreater((clk[-1] - self.t_start) / self.wall, 1.2)  # rate 2

    def test_gps_compass(self):
        g = self.got["gps"]
        self.assertAlmostEqual(rate([m.header.stamp.to_sec() for m in g], 2.0, 7.0), 10.0, delta=1.0)
        self.assertEqual(g[-1].header.frame_id, "usv/gps")
        self.assertAlmostEqual(g[-1].latitude, 61.4507, delta=0.001)
        self.assertAlmostEqual(g[-1].longitude, 23.7270, delta=0.002)
        h = [m for m in self.got["heading"] if m.header.stamp.to_sec() < MANUAL_FROM][-1]
        self.assertEqual(h.header.frame_id, "map")
        q = h.quaternion
        yaw_enu = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
        self.assertAlmostEqual(yaw_enu, math.pi / 2, delta=0.05)  # heading north, no yaw command

    def test_lidar(self):
        self.assertAlmostEqual(rate(self.lidar_stamps, 2.0, 7.0), 12.5, delta=1.3)
        m = self.lidar_last[0]
        self.assertEqual(m.header.frame_id, "usv/lidar")
        self.assertEqual((m.height, m.width), (4, 1101))
        self.assertFalse(m.is_dense)
        pts = list(point_cloud2.read_points(m, field_names=("x", "y", "z", "ring")))
        ranges = [math.sqrt(x * x + y * y + z * z) for x, y, z, _ in pts]
        finite = [r for r in ranges if not math.isnan(r)]
        self.assertGreater(len(finite), 10)
        self.assertGreater(len(ranges) - len(finite), 100, "expected NaN for beams with no return")
        self.assertTrue(all(0.2 <= r <= 64.5 for r in finite), (min(finite), max(finite)))
        # the buoy 25 m north of the start is ahead (within 10 deg of the bow) and nearer than the shore
        ahead = [math.hypot(x, y) for x, y, z, _ in pts if not math.isnan(x) and abs(math.atan2(y, x)) < 0.17]
        self.assertTrue(ahead and min(ahead) < 25.0, ahead[:5])

    def test_map_grid(self):
        self.assertTrue(self.got["map"], "no latched /usv/map")
        g = self.got["map"][-1]
        self.assertEqual(g.header.frame_id, "map")
        self.assertEqual((g.info.width, g.info.height), (200, 160))
        self.assertAlmostEqual(g.info.origin.position.x, -100.0)
        self.assertAlmostEqual(g.info.origin.position.y, -60.0)
        self.assertEqual(g.data[0], 100)            # south-west corner: land
        self.assertEqual(g.data[60 * 200 + 100], 0)  # the origin: water

    def test_navigation_follows_truth(self):
        odom, truth = self.got["odom"], self.got["truth"]
        self.assertTrue(odom and truth)
        self.assertEqual((odom[-1].header.frame_id, odom[-1].child_frame_id), ("map", "usv/base_link"))
        self.assertEqual(truth[-1].child_frame_id, "usv/base_link")
        o = odom[-1]
        t = min(truth, key=lambda m: abs((m.header.stamp - o.header.stamp).to_sec()))
        dx = o.pose.pose.position.x - t.pose.pose.position.x
        dy = o.pose.pose.position.y - t.pose.pose.position.y
        self.assertLess(math.hypot(dx, dy), 2.0)
        self.assertGreater(t.pose.pose.position.y, 2.0)  # moved north under the joystick command
        tf = self.buf.lookup_transform("map", "usv/base_link", rospy.Time(0), rospy.Duration(5))
        self.assertAlmostEqual(tf.transform.translation.y, o.pose.pose.position.y, delta=2.0)
        lidar = self.buf.lookup_transform("usv/base_link", "usv/lidar", rospy.Time(0), rospy.Duration(5))
        self.assertAlmostEqual(lidar.transform.translation.x, 1.5)
        self.assertAlmostEqual(lidar.transform.translation.z, 1.0)

    def test_manual_takes_priority_and_jets_report(self):
        truth = self.got["truth"]
        before = [m for m in truth if m.header.stamp.to_sec() < MANUAL_FROM][-1]
        self.assertAlmostEqual(before.twist.twist.angular.z, 0.0, delta=0.02)
        # starboard turn: NED yaw rate > 0, i.e. FLU angular z < 0
        self.assertLess(truth[-1].twist.twist.angular.z, -0.02)
        jets = self.got["jets"]
        self.assertEqual({j.jet for j in jets}, {0, 1})
        self.assertGreater(jets[-1].rpm, 600.0)
        self.assertGreater(jets[-1].nozzle_position, 0.1)  # nozzles to starboard
        self.assertTrue(all(-1.0 <= j.nozzle_position <= 1.0 and -1.0 <= j.bucket_position <= 1.0 for j in jets))

    def test_bad_commands_counted(self):
        values, names = {}, set()
        for arr in self.got["diag"]:
            for st in arr.status:
                names.add(st.name)
                if "usv_sim" in st.name:
                    values.update({kv.key: kv.value for kv in st.values})
        self.assertIn("rejected_commands", values, (values, names))
        self.assertGreaterEqual(int(values["rejected_commands"]), 2)
        self.assertGreater(int(values.get("autonomy_overridden_by_manual", 0)), 0, values)


if __name__ == "__main__":
    rospy.init_node("check_usv_sim")
    rostest.rosrun("offshore_gnc", "check_usv_sim", UsvSim)
