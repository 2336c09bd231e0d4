#!/usr/bin/python3
"""rostest: the Girona500 follows a lawnmower coverage pattern on the simulator and ends in station keeping."""
import math
import unittest

import rospy
import rostest
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry, Path
from offshore_gnc.msg import GuidanceStatus, ThrusterSetpoints
from offshore_gnc.testing import bounds


class AuvCoverage(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.status, cls.thr, cls.truth = [], [], []
        cls.subs = [rospy.Subscriber("/auv/guidance/status", GuidanceStatus, cls.status.append),
                    rospy.Subscriber("/auv/thruster_setpoints", ThrusterSetpoints, cls.thr.append),
                    rospy.Subscriber("/auv/ground_truth/odom", Odometry, cls.truth.append)]
        cls.path_pub = rospy.Publisher("/auv/guidance/path", Path, queue_size=1, latch=True)

    def test_coverage(self):
        deadline = rospy.get_time() + 30.0
        while not self.truth and rospy.get_time() < deadline and not rospy.is_shutdown():
            rospy.sleep(0.1)
        self.assertTrue(self.truth, "no simulator output")
        p = Path()
        p.header.frame_id = "map_ned"
        p.header.stamp = rospy.Time.now()
        # scenario start (5, 5, 2): two 10 m tracks 3 m apart at 3 m depth
        for n, e in ((5, 5), (15, 5), (15, 8), (5, 8)):
            ps = PoseStamped()
            ps.header = p.header
            ps.pose.position.x, ps.pose.position.y, ps.pose.position.z = n, e, 3.0
            ps.pose.orientation.w = 1.0
            p.poses.append(ps)
        self.path_pub.publish(p)
        deadline = rospy.get_time() + 300.0
        while rospy.get_time() < deadline and not rospy.is_shutdown():
            if self.status and self.status[-1].mode == GuidanceStatus.MODE_STATION_KEEPING:
                break
            rospy.sleep(0.5)
        self.assertTrue(self.status and self.status[-1].mode == GuidanceStatus.MODE_STATION_KEEPING,
                        "coverage not finished: %s" % (self.status[-1] if self.status else "no status"))
        self.assertTrue(self.thr)
        for m in self.thr:
            self.assertEqual(len(m.setpoint), 5)
            self.assertTrue(all(math.isfinite(v) and abs(v) <= 1.0 for v in m.setpoint))
        xte = [s.cross_track_error for s in self.status if s.mode == GuidanceStatus.MODE_FOLLOW_PATH]
        rmse = math.sqrt(sum(e * e for e in xte) / len(xte))
        rospy.loginfo("Girona500 coverage on the simulator: %d samples, cross-track RMSE %.3f m", len(xte), rmse)
        bounds.record("rostest_auv_coverage", "auv_xte_est_rmse_m", rmse)
        self.assertLessEqual(rmse, bounds.upper("rostest_auv_coverage", "auv_xte_est_rmse_m"))  # test/bounds.yaml
        depth = self.truth[-1].pose.pose.position.z  # ENU up
        self.assertAlmostEqual(-depth, 3.0, delta=0.5)


if __name__ == "__main__":
    rospy.init_node("check_auv_coverage")
    rostest.rosrun("offshore_gnc", "auv_sim_coverage", AuvCoverage)
