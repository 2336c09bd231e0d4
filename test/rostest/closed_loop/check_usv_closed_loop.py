#!/usr/bin/python3
"""rostest: the USV follows a 4-waypoint route around the scenario's buoy on the simulator, never inside the
safety box, ends in station keeping, and the joystick output is always finite."""
import math
import unittest

import rospy
import rostest
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry, Path
from offshore_gnc.msg import GuidanceStatus, JoystickCommand, SafetyBoxArray, Target, TargetArray
from offshore_gnc.testing import bounds


def inside(box, n, e):
    c, s = math.cos(box.path_angle), math.sin(box.path_angle)
    dn, de = n - box.center.x, e - box.center.y
    along, across = dn * c + de * s, -dn * s + de * c
    return abs(along) < box.length / 2 and abs(across) < box.width / 2


class UsvClosedLoop(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.status, cls.joy, cls.truth, cls.boxes = [], [], [], []
        cls.subs = [rospy.Subscriber("/usv/guidance/status", GuidanceStatus, cls.status.append),
                    rospy.Subscriber("/usv/joystick_cmd", JoystickCommand, cls.joy.append),
                    rospy.Subscriber("/usv/ground_truth/odom", Odometry, cls.truth.append),
                    rospy.Subscriber("/usv/guidance/safety_boxes", SafetyBoxArray, cls.boxes.append)]
        cls.path_pub = rospy.Publisher("/usv/guidance/path", Path, queue_size=1, latch=True)
        cls.obs_pub = rospy.Publisher("/usv/obstacles", TargetArray, queue_size=1)

    def test_route_around_buoy(self):
        deadline = rospy.get_time() + 30.0
        while not self.truth and rospy.get_time() < deadline and not rospy.is_shutdown():
            rospy.sleep(0.1)
        self.assertTrue(self.truth, "no simulator output")
        p = Path()
        p.header.frame_id = "map_ned"
        p.header.stamp = rospy.Time.now()
        for n in (0.0, 40.0, 80.0, 120.0):
            ps = PoseStamped()
            ps.header = p.header
            ps.pose.position.x = n
            ps.pose.orientation.w = 1.0
            p.poses.append(ps)
        t = Target()
        t.id = 1
        t.origin.x, t.origin.y = 25.0, 0.5  # config/scenarios/pyhajarvi.yaml buoy
        t.length = t.width = 1.2
        arr = TargetArray()
        arr.header.frame_id = "map_ned"
        arr.targets = [t]
        for _ in range(5):  # obstacles first, so the first plan already holds the detour
            self.obs_pub.publish(arr)
            rospy.sleep(0.2)
        self.path_pub.publish(p)
        deadline = rospy.get_time() + 240.0  # simulated seconds
        while rospy.get_time() < deadline and not rospy.is_shutdown():
            self.obs_pub.publish(arr)
            if self.status and self.status[-1].mode == GuidanceStatus.MODE_STATION_KEEPING:
                break
            rospy.sleep(0.5)
        self.assertTrue(self.status and self.status[-1].mode == GuidanceStatus.MODE_STATION_KEEPING,
                        "end of path not reached: %s" % (self.status[-1] if self.status else "no status"))
        self.assertTrue(self.boxes and any(b.cuts_path for b in self.boxes[-1].boxes), "no safety box")
        box = [b for b in self.boxes[-1].boxes if b.cuts_path][0]
        inside_n = sum(1 for o in self.truth if inside(box, o.pose.pose.position.y, o.pose.pose.position.x))
        clearance = min(math.hypot(o.pose.pose.position.y - 25.0, o.pose.pose.position.x - 0.5) - 0.6
                        for o in self.truth)
        rospy.loginfo("samples inside the safety box: %d, closest approach to the buoy %.2f m", inside_n, clearance)
        # Never inside the safety box, although the buoy is only 25 m ahead of a boat at rest (detour corners are
        # reached within los/detour_radius, not cut by the 16 m circle; the side chosen is kept while drifting).
        self.assertEqual(inside_n, 0)
        bounds.record("rostest_usv_closed_loop", "buoy_clearance_ref_m", clearance)
        self.assertGreaterEqual(clearance, bounds.lower("rostest_usv_closed_loop", "buoy_clearance_ref_m"))
        for j in self.joy:
            self.assertTrue(all(math.isfinite(v) for v in (j.surge, j.sway, j.yaw)))
        xte = [s.cross_track_error for s in self.status if s.mode == GuidanceStatus.MODE_FOLLOW_PATH]
        rmse = math.sqrt(sum(e * e for e in xte) / len(xte))
        rospy.loginfo("closed loop on the simulator: %d samples, cross-track RMSE %.2f m", len(xte), rmse)
        # Bounds: test/bounds.yaml, from the runs in test/bounds_measured.yaml. The straight-line goal is measured by
        # the bench (bench tracking).
        bounds.record("rostest_usv_closed_loop", "usv_xte_est_rmse_m", rmse)
        self.assertLessEqual(rmse, bounds.upper("rostest_usv_closed_loop", "usv_xte_est_rmse_m"))


if __name__ == "__main__":
    rospy.init_node("check_usv_closed_loop")
    rostest.rosrun("offshore_gnc", "usv_sim_closed_loop", UsvClosedLoop)
