#!/usr/bin/python3
"""Stand-in for COLA2: publishes cola2_msgs/NavSts and subscribes to cola2_msgs/Setpoints by COLA2's type names
(our field-for-field definitions: the md5sums must be COLA2's), and checks what the Cola2Bridge makes of them."""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from nav_msgs.msg import Odometry

from offshore_gnc.msg import Cola2NavSts, Cola2Setpoints, ThrusterSetpoints
from offshore_gnc.testing.poll import wait_until

# COLA2's published md5sum of cola2_msgs/NavSts (from its generated message code).
COLA2_NAVSTS_MD5 = "0ba23d6197aed7a9fab08613fe8fc381"


class NavSts(Cola2NavSts):
    _type = "cola2_msgs/NavSts"


class Setpoints(Cola2Setpoints):
    _type = "cola2_msgs/Setpoints"


class Cola2BridgeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("fake_cola2")
        cls.lock = threading.Lock()
        cls.setpoints, cls.odom = [], []
        rospy.Subscriber("/girona500/controller/thruster_setpoints", Setpoints, cls._store(cls.setpoints))
        rospy.Subscriber("/auv/odom", Odometry, cls._store(cls.odom))
        cls.nav = rospy.Publisher("/girona500/navigator/navigation", NavSts, queue_size=5)
        cls.ours = rospy.Publisher("/auv/thruster_setpoints", ThrusterSetpoints, queue_size=5)
        deadline = time.time() + 30
        while time.time() < deadline and (cls.nav.get_num_connections() == 0 or cls.ours.get_num_connections() == 0):
            time.sleep(0.1)

    @classmethod
    def _store(cls, where):
        def cb(m):
            with cls.lock:
                where.append((time.time(), m))
        return cb

    def _wait(self, pred, timeout):
        return wait_until(pred, timeout, step=0.05, lock=self.lock)

    def test_0_messages_match_cola2(self):
        self.assertEqual(Cola2NavSts._md5sum, COLA2_NAVSTS_MD5)

    def test_1_setpoints_in_cola2_order_then_watchdog_zeros(self):
        sent = [0.1, 0.2, -0.3, 0.4, -0.5]
        for _ in range(5):
            self.ours.publish(ThrusterSetpoints(setpoint=sent, thrust=[0.0] * 5))
            time.sleep(0.1)
        last = time.time()
        self.assertTrue(self._wait(lambda: any(abs(m.setpoints[0] - 0.2) < 1e-12 for _, m in self.setpoints), 5))
        with self.lock:
            got = [m for _, m in self.setpoints if abs(m.setpoints[0] - 0.2) < 1e-12][-1]
        self.assertEqual(list(got.setpoints), [0.2, -0.1, -0.3, 0.4, -0.5])
        self.assertEqual(got._connection_header["type"], "cola2_msgs/Setpoints")
        # Our setpoints stop: zeros within the watchdog time (1 s), a few of them, then silence.
        self.assertTrue(self._wait(lambda: any(t > last and all(v == 0.0 for v in m.setpoints)
                                               for t, m in self.setpoints), 3))
        with self.lock:
            zeros = [t for t, m in self.setpoints if t > last and all(v == 0.0 for v in m.setpoints)]
        self.assertLess(zeros[0] - last, 2.0)
        time.sleep(1.5)
        with self.lock:
            after = [t for t, m in self.setpoints if t > last and all(v == 0.0 for v in m.setpoints)]
        self.assertEqual(len(after), 5)
        # NaN never reaches a thruster
        n = len(self.setpoints)
        self.ours.publish(ThrusterSetpoints(setpoint=[float("nan")] * 5, thrust=[0.0] * 5))
        time.sleep(0.5)
        with self.lock:
            self.assertFalse(any(any(math.isnan(v) for v in m.setpoints) for _, m in self.setpoints[n:]))

    def test_2_navigation_becomes_odometry_in_our_frame(self):
        m = NavSts()
        m.header.stamp = rospy.Time.now()
        m.origin.latitude, m.origin.longitude = 61.4507, 23.7270  # the same origin as ours
        m.position.north, m.position.east, m.position.depth = 20.0, -4.0, 3.5
        m.orientation.yaw = math.radians(30.0)
        m.body_velocity.x = 0.6
        for _ in range(10):
            self.nav.publish(m)
            time.sleep(0.05)
        self.assertTrue(self._wait(lambda: self.odom, 5))
        with self.lock:
            o = self.odom[-1][1]
        self.assertEqual((o.header.frame_id, o.child_frame_id), ("map", "auv/base_link"))
        p = o.pose.pose.position
        self.assertAlmostEqual(p.x, -4.0, delta=1e-6)   # ENU: x east
        self.assertAlmostEqual(p.y, 20.0, delta=1e-6)   # y north
        self.assertAlmostEqual(p.z, -3.5, delta=1e-6)   # z up
        q = o.pose.pose.orientation
        yaw_enu = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2))
        self.assertAlmostEqual(yaw_enu, math.radians(60.0), delta=1e-4)
        self.assertAlmostEqual(o.twist.twist.linear.x, 0.6, delta=1e-6)


if __name__ == "__main__":
    rostest.rosrun("offshore_gnc", "cola2_bridge", Cola2BridgeTest, sys.argv)
