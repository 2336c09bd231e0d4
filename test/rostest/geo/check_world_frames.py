#!/usr/bin/python3
"""rostest: /origin is latched with the site's origin (/site/origin); map_ned is the NED view of map; diagnostics
give the origin in its own UTM zone."""
import unittest

import rospy
import rostest
import tf2_ros
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import PointStamped
from sensor_msgs.msg import NavSatFix
import tf2_geometry_msgs  # noqa: F401  (registers PointStamped with tf2)

from offshore_gnc.testing.poll import wait_until


class WorldFrames(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # one listener for the whole test: a listener dropped mid-test leaves rospy's other subscriptions dead
        cls.origin, cls.diags = [], []
        cls.origin_sub = rospy.Subscriber("/origin", NavSatFix, cls.origin.append)
        cls.diag_sub = rospy.Subscriber("/diagnostics", DiagnosticArray, cls.diags.append)
        cls.buf = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.buf)

    def test_origin_latched(self):
        self.assertTrue(wait_until(lambda: self.origin, 60, step=0.05), "no message on /origin")
        msg = self.origin[0]
        lat, lon, alt = (float(v) for v in rospy.get_param("/site/origin").split(","))
        self.assertAlmostEqual(msg.latitude, lat)
        self.assertAlmostEqual(msg.longitude, lon)
        self.assertAlmostEqual(msg.altitude, alt)
        self.assertEqual(msg.header.frame_id, "map_ned")

    def test_grid_is_the_sites_own_zone(self):
        def grid():
            kvs = ({v.key: v.value for v in st.values} for arr in list(self.diags) for st in arr.status)
            return next((kv for kv in kvs if "grid" in kv), None)
        kv = wait_until(grid, 60)
        self.assertTrue(kv, "no origin diagnostics with a grid")
        # Hobart: UTM zone 55 south, about 528 km E, 5252 km N
        self.assertEqual(kv["grid"], "UTM 55S")
        self.assertAlmostEqual(float(kv["grid_easting_m"]) / 1000, 528.7, delta=1.0)
        self.assertAlmostEqual(float(kv["grid_northing_m"]) / 1000, 5252.0, delta=2.0)
        self.assertNotIn("tm35fin_easting_m", kv)

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
