#!/usr/bin/python3
"""Gateway + emulator nodelets over a real vcan0: positions, heading, status and per-jet commands cross the bus."""
import math
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import QuaternionStamped
from nav_msgs.msg import Odometry
from offshore_gnc.msg import JoystickCommand, WaterjetAnswering, WaterjetSetpoints, WaterjetStatus
from sensor_msgs.msg import NavSatFix


class VcanE2E(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("can_vcan_e2e")
        cls.got = {"gps": [], "heading": [], "status": [], "applied": [], "answering": []}
        cls.subs = [
            rospy.Subscriber("/usv_gps", NavSatFix, lambda m: cls.got["gps"].append(m)),
            rospy.Subscriber("/usv_heading", QuaternionStamped, lambda m: cls.got["heading"].append(m)),
            rospy.Subscriber("/usv/waterjet/status", WaterjetStatus, lambda m: cls.got["status"].append(m)),
            rospy.Subscriber("/usv/waterjet/applied_setpoints", WaterjetSetpoints, lambda m: cls.got["applied"].append(m)),
            rospy.Subscriber("/usv/waterjet/answering", WaterjetAnswering, lambda m: cls.got["answering"].append(m)),
        ]
        cls.odom = rospy.Publisher("/usv/ground_truth/odom", Odometry, queue_size=10)
        cls.cmd = rospy.Publisher("/usv/joystick_cmd", JoystickCommand, queue_size=10)

    def test_round_trip_over_vcan(self):
        o = Odometry()
        o.header.frame_id = "map"
        o.pose.pose.position.x = 100.0  # 100 m east of the origin
        yaw = math.radians(30.0)        # ENU yaw 30 deg = heading 60 deg
        o.pose.pose.orientation.z = math.sin(yaw / 2)
        o.pose.pose.orientation.w = math.cos(yaw / 2)
        end = time.time() + 60.0
        while time.time() < end and not rospy.is_shutdown():
            self.odom.publish(o)
            self.cmd.publish(JoystickCommand(surge=0.8, yaw=-0.25))
            if (len(self.got["gps"]) > 3 and len(self.got["heading"]) > 3 and
                    any(m.source[0] == JoystickCommand.SOURCE_AUTONOMY and m.rpm[0] > 1000 for m in self.got["applied"]) and
                    any(s.rpm > 1000 for s in self.got["status"])):
                break
            time.sleep(0.05)
        self.assertGreater(len(self.got["gps"]), 3, "no /usv_gps from the emulated GPS-compass")
        fix = self.got["gps"][-1]
        self.assertAlmostEqual(fix.latitude, 61.4507, places=4)
        self.assertGreater(fix.longitude, 23.7270)  # east of the origin
        q = self.got["heading"][-1].quaternion
        self.assertAlmostEqual(2 * math.atan2(q.z, q.w), yaw, places=3)
        # The gateway allocated (0.8, 0, -0.25) onto the jets: both engines well above idle, buckets ahead, the
        # nozzles turned to port (P > 0: eq. 3.25's sign); the units act on it (source autonomy).
        applied = self.got["applied"][-1]
        self.assertEqual(list(applied.source), [JoystickCommand.SOURCE_AUTONOMY] * 2)
        for i in (0, 1):
            self.assertGreater(applied.rpm[i], 1000.0)
            self.assertGreater(applied.bucket[i], 0.5)
            self.assertGreater(applied.nozzle[i], 0.0)
        self.assertTrue(any(s.rpm > 1000 for s in self.got["status"]), "jets never spun up")
        self.assertEqual({s.jet for s in self.got["status"]}, {0, 1})
        self.assertTrue(self.got["answering"], "no /usv/waterjet/answering from the gateway")
        self.assertEqual(list(self.got["answering"][-1].answering), [True, True])


if __name__ == "__main__":
    rostest.rosrun("offshore_gnc", "can_vcan_e2e", VcanE2E)
