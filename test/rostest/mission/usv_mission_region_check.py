#!/usr/bin/python3
"""rostest: targets outside the USV's operating region are refused by its mission nodelet, saying why
(usv_mission_region.test)."""
import threading
import unittest

import rospy
import rostest
from nav_msgs.msg import Odometry

from offshore_gnc.msg import MissionStatus, Target
from offshore_gnc.testing.poll import wait_until


class UsvMissionRegionCheck(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lock = threading.Lock()
        cls.statuses = []
        cls.sub = rospy.Subscriber("/usv/mission/status", MissionStatus, cls._on_status)
        cls.odom = rospy.Publisher("/usv/odom", Odometry, queue_size=10)
        cls.target = rospy.Publisher("/target", Target, queue_size=10, latch=True)
        wait_until(lambda: cls.odom.get_num_connections() and cls.target.get_num_connections(), 30.0, step=0.05)
        cls.timer = rospy.Timer(rospy.Duration(0.1), cls._pose)

    @classmethod
    def _on_status(cls, m):
        with cls.lock:
            cls.statuses.append(m)

    @classmethod
    def _pose(cls, _):
        o = Odometry()
        o.header.stamp = rospy.Time.now()
        o.header.frame_id = "map"
        o.pose.pose.orientation.w = 1.0  # at the origin
        cls.odom.publish(o)

    def send_and_wait(self, north, east, want, timeout=10.0):
        t = Target()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id = "map_ned"
        t.origin.x, t.origin.y = north, east
        with self.lock:
            del self.statuses[:]
        self.target.publish(t)
        hit = wait_until(lambda: next((s for s in reversed(self.statuses) if want(s)), None), timeout, step=0.05,
                         lock=self.lock)
        if hit:
            return hit
        with self.lock:
            self.fail("no status as wanted after N %g E %g; last: %s" % (
                north, east, self.statuses[-1] if self.statuses else "none"))

    def test_1_far_targets_are_refused_and_a_near_one_is_used(self):
        rospy.sleep(1.0)  # a few poses first: the mission needs one before any target
        s = self.send_and_wait(2520.0e3, 0.0, lambda s: "2520.0 km" in s.detail)
        self.assertEqual(s.phase, "STATION_KEEPING", s)
        self.assertIn("refused a target", s.detail)
        s = self.send_and_wait(500.0, 0.0, lambda s: "refused a target" in s.detail and "500.0 m" in s.detail)
        self.assertEqual(s.phase, "STATION_KEEPING", s)
        s = self.send_and_wait(60.0, 20.0, lambda s: s.phase == "TRANSIT")
        self.assertIn("transit", s.detail)


if __name__ == "__main__":
    rospy.init_node("usv_mission_region_check")
    rostest.rosrun("offshore_gnc", "usv_mission_region", UsvMissionRegionCheck)
