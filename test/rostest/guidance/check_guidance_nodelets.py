#!/usr/bin/python3
"""rostest: the USV Guidance and Control nodelets on synthetic input (odometry in map/ENU, path in map_ned)."""
import math
import unittest

import rospy
import rostest
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry, Path
from offshore_gnc.msg import (GuidanceStatus, JoystickCommand, SafetyBox, SafetyBoxArray, Target, TargetArray, Track,
                              TrackArray)
from offshore_gnc.testing.poll import wait_until


def odom(north, east, yaw_ned=0.0):
    o = Odometry()
    o.header.stamp = rospy.Time.now()
    o.header.frame_id = "map"
    o.child_frame_id = "usv/base_link"
    o.pose.pose.position.x, o.pose.pose.position.y = east, north  # ENU
    yaw_enu = math.pi / 2 - yaw_ned
    o.pose.pose.orientation.z, o.pose.pose.orientation.w = math.sin(yaw_enu / 2), math.cos(yaw_enu / 2)
    return o


def path(points):
    p = Path()
    p.header.stamp = rospy.Time.now()
    p.header.frame_id = "map_ned"
    for n, e in points:
        ps = PoseStamped()
        ps.header = p.header
        ps.pose.position.x, ps.pose.position.y = n, e
        ps.pose.orientation.w = 1.0
        p.poses.append(ps)
    return p


class GuidanceNodelets(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.status, cls.boxes, cls.planned, cls.joy = [], [], [], []
        cls.subs = [rospy.Subscriber("/usv/guidance/status", GuidanceStatus, cls.status.append),
                    rospy.Subscriber("/usv/guidance/safety_boxes", SafetyBoxArray, cls.boxes.append),
                    rospy.Subscriber("/usv/guidance/planned_path", Path, cls.planned.append),
                    rospy.Subscriber("/usv/joystick_cmd", JoystickCommand, cls.joy.append)]
        cls.odom_pub = rospy.Publisher("/usv/odom", Odometry, queue_size=10)
        cls.path_pub = rospy.Publisher("/usv/guidance/path", Path, queue_size=1, latch=True)
        cls.obs_pub = rospy.Publisher("/usv/obstacles", TargetArray, queue_size=1)
        cls.tracks_pub = rospy.Publisher("/usv/tracks", TrackArray, queue_size=1)
        cls.pose = (0.0, 3.0)
        cls.timer = rospy.Timer(rospy.Duration(0.05), lambda _: cls.odom_pub.publish(odom(*cls.pose)))

    def wait(self, what, cond, timeout=20.0):
        if not wait_until(cond, timeout, step=0.05):
            self.fail("timed out waiting for " + what)

    def latest_status(self):
        return self.status[-1] if self.status else None

    def test_1_follow_avoid_and_bad_input(self):
        type(self).pose = (0.0, 3.0)
        self.path_pub.publish(path([(0, 0), (40, 0), (80, 0)]))
        self.wait("path following", lambda: self.latest_status() and
                  self.latest_status().mode == GuidanceStatus.MODE_FOLLOW_PATH)
        s = self.latest_status()
        self.assertAlmostEqual(s.cross_track_error, 3.0, places=2)  # 3 m east of a north leg = starboard
        self.assertLess(s.desired_heading, 0.0)                     # steer to port
        self.assertEqual(s.header.frame_id, "map_ned")
        self.assertEqual(s.desired_depth, 0.0)  # the surface
        # the reference control follows travels in the status: the projection of the boat on the leg
        self.assertEqual(s.reference_mode, GuidanceStatus.REFERENCE_FOLLOW)
        self.assertAlmostEqual(s.reference_point.x, 0.0, delta=0.5)
        self.assertAlmostEqual(s.reference_point.y, 0.0, places=2)
        # control may still send a neutral command or two from before the status arrived: wait for the first
        # command computed from path following, which must steer to port with thrust ahead
        self.wait("a steering joystick command", lambda: any(j.yaw < 0.0 and j.surge > 0.0 for j in self.joy))
        j = next(j for j in self.joy if j.yaw < 0.0 and j.surge > 0.0)
        self.assertEqual(j.source, JoystickCommand.SOURCE_AUTONOMY)
        self.assertTrue(all(j.yaw <= 0.0 for j in self.joy[-3:]), "later commands stopped steering to port")

        # a buoy on the route: safety box, detour inserted into the planned path
        t = Target()
        t.id = 42
        t.origin.x, t.origin.y = 40.0, 0.5
        t.length = t.width = 1.2
        arr = TargetArray()
        arr.header.frame_id = "map_ned"
        arr.targets = [t]
        n0 = len(self.planned)
        self.wait("safety box", lambda: (self.obs_pub.publish(arr) or True) and self.boxes and
                  any(b.cuts_path for b in self.boxes[-1].boxes))
        box = [b for b in self.boxes[-1].boxes if b.cuts_path][0]
        self.assertEqual(list(box.obstacle_ids), [42])
        self.assertIn(box.side, (SafetyBox.SIDE_PORT, SafetyBox.SIDE_STARBOARD))
        self.wait("planned path with detour", lambda: len(self.planned) > n0 and len(self.planned[-1].poses) > 3)

        # one-point path: hold with a clear status, finite neutral-ish command
        self.path_pub.publish(path([(10, 10)]))
        self.wait("hold fault", lambda: self.latest_status().mode == GuidanceStatus.MODE_HOLD_FAULT)
        self.assertIn("single waypoint", self.latest_status().status_text)
        self.assertEqual(self.latest_status().desired_surge, 0.0)

        # NaN pose: hold, never NaN on the outputs
        self.path_pub.publish(path([(0, 0), (40, 0)]))
        self.wait("following again", lambda: self.latest_status().mode == GuidanceStatus.MODE_FOLLOW_PATH)
        type(self).pose = (float("nan"), 0.0)
        self.wait("hold on NaN pose", lambda: self.latest_status().mode == GuidanceStatus.MODE_HOLD_FAULT)
        n = len(self.joy)
        self.wait("joystick during fault", lambda: len(self.joy) > n + 5)
        for j in self.joy[n:]:
            self.assertTrue(all(math.isfinite(v) for v in (j.surge, j.sway, j.yaw)))
        s = self.latest_status()
        for v in (s.desired_heading, s.desired_surge, s.cross_track_error, s.crab_angle):
            self.assertTrue(math.isfinite(v))

    def test_2_end_of_path_station_keeping(self):
        type(self).pose = (0.0, 0.0)
        self.path_pub.publish(path([(-20, 0), (0, 0)]))
        self.wait("station keeping", lambda: self.latest_status() and
                  self.latest_status().mode == GuidanceStatus.MODE_STATION_KEEPING)
        self.assertEqual(self.latest_status().desired_surge, 0.0)
        self.assertIn("end of path", self.latest_status().status_text)
        # station keeping holds the end of the path
        self.assertEqual(self.latest_status().reference_mode, GuidanceStatus.REFERENCE_HOLD)
        self.assertAlmostEqual(self.latest_status().reference_point.x, 0.0, places=3)
        self.assertAlmostEqual(self.latest_status().reference_point.y, 0.0, places=3)

    def test_3_gives_way_to_a_track_from_starboard(self):
        """A confirmed track 50 m off on our starboard bow, coming straight at us at 1.5 m/s: a crossing from
        starboard, so guidance alters to starboard and says so; a NaN track beside it is counted, not used."""
        type(self).pose = (5.0, 0.0)
        self.path_pub.publish(path([(0, 0), (200, 0)]))
        self.wait("path following", lambda: self.latest_status().mode == GuidanceStatus.MODE_FOLLOW_PATH)

        def tracks():
            a = TrackArray()
            a.header.stamp = rospy.Time.now()
            a.header.frame_id = "map_ned"
            good, bad = Track(), Track()
            good.id, bad.id = 7, 8
            good.status = bad.status = Track.CONFIRMED
            good.position.x, good.position.y = 45.0, 30.0
            good.velocity.x, good.velocity.y = -1.2, -0.9
            bad.position.x, bad.position.y = 60.0, -10.0
            bad.velocity.x, bad.velocity.y = float("nan"), 1.0
            for t in (good, bad):
                t.header = a.header
                t.covariance = [0.01 if i % 5 == 0 else 0.0 for i in range(16)]
                t.length, t.width = 8.0, 3.0
            a.tracks = [good, bad]
            return a
        self.wait("an encounter", lambda: (self.tracks_pub.publish(tracks()) or True) and
                  self.latest_status().encounter != GuidanceStatus.ENCOUNTER_NONE)
        s = self.latest_status()
        self.assertEqual(s.encounter, GuidanceStatus.ENCOUNTER_CROSSING_GIVE_WAY)
        self.assertEqual(s.encounter_contact, 7)
        self.assertEqual(s.encounter_action, GuidanceStatus.ACTION_STARBOARD)
        self.assertGreater(s.desired_heading, math.radians(30.0))  # the leg is north: a large turn to starboard
        self.assertIn("crossing from starboard", s.status_text)


if __name__ == "__main__":
    rospy.init_node("check_guidance_nodelets")
    rostest.rosrun("offshore_gnc", "guidance_nodelets", GuidanceNodelets)
