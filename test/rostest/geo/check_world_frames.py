#!/usr/bin/python3
"""rostest: /origin is latched with the configured origin; map_ned is the NED view of map."""
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import PointStamped
from sensor_msgs.msg import NavSatFix
import tf2_geometry_msgs  # noqa: F401  (registers PointStamped with tf2)


class WorldFrames(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # one listener for the whole test: a listener dropped mid-test leaves rospy's other subscriptions dead
        cls.origin = []
        cls.origin_sub = rospy.Subscriber("/origin", NavSatFix, cls.origin.append)
        cls.buf = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.buf)

    def test_origin_latched(self):
        deadline = rospy.Time.now() + rospy.Duration(60)
        while not self.origin and rospy.Time.now() < deadline:
            rospy.sleep(0.05)
        self.assertTrue(self.origin, "no message on /origin")
        msg = self.origin[0]
        self.assertAlmostEqual(msg.latitude, 61.5)
        self.assertAlmostEqual(msg.longitude, 23.75)
        self.assertEqual(msg.header.frame_id, "map_ned")

    def test_ned_is_enu_swapped(self):
        p = PointStamped()
        p.header.frame_id = "map_ned"
        p.point.x, p.point.y, p.point.z = 10.0, 3.0, 2.0  # 10 m north, 3 m east, 2 m down
        q = self.buf.transform(p, "map", rospy.Duration(60))
        self.assertAlmostEqual(q.point.x, 3.0, places=6)   # east
        self.assertAlmostEqual(q.point.y, 10.0, places=6)  # north
        self.assertAlmostEqual(q.point.z, -2.0, places=6)  # up


if __name__ == "__main__":
    rospy.init_node("check_world_frames")
    rostest.rosrun("offshore_gnc", "check_world_frames", WorldFrames)
