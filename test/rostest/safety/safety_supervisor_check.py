#!/usr/bin/python3
"""rostest: the AUV's SafetySupervisor on synthetic heartbeats (safety_supervisor.test sets the short timeouts).

Every AUV input at 10 Hz -> no action; /auv/odom stops -> navigation_timeout active with the preset's surface
within the timeout + 0.3 s (judged on the messages' stamps, waited for with generous deadlines, all in ROS time,
which is wall time here), and a transition published; odometry 60 m deep -> max_depth, surface; diagnostics
OK then ERROR. The command heartbeat switches from /auv/thruster_setpoints to /auv/rc_channels half-way: both
must count."""
import threading
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from nav_msgs.msg import Odometry
from sensor_msgs.msg import FluidPressure

from offshore_gnc.msg import LinkStatus, RcChannels, SafetyState, SonarBeam, ThrusterSetpoints, UsblFix
from offshore_gnc.testing.poll import wait_until

NAVIGATION_TIMEOUT = 0.5  # safety_supervisor.test
NAVIGATION_RELEASE = 0.5
MAX_DEPTH_DETECTION = 1.0  # the AUV preset's
SLACK = 0.3  # the supervisor updates at 10 Hz


class SafetySupervisorCheck(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lock = threading.Lock()
        cls.states, cls.transitions, cls.diags = [], [], []  # (ROS time received, message)
        cls.odom_on, cls.odom_z, cls.last_odom, cls.use_rc = True, -5.0, None, False
        cls.subs = [rospy.Subscriber("/auv/safety/state", SafetyState, cls._store(cls.states)),
                    rospy.Subscriber("/auv/safety/transitions", SafetyState, cls._store(cls.transitions)),
                    rospy.Subscriber("/diagnostics", DiagnosticArray, cls._on_diag)]
        cls.pubs = {
            "odom": rospy.Publisher("/auv/odom", Odometry, queue_size=10),
            "sonar": rospy.Publisher("/auv/sonar/beam", SonarBeam, queue_size=10),
            "usbl": rospy.Publisher("/auv/usbl/fix", UsblFix, queue_size=10),
            "pressure": rospy.Publisher("/auv/pressure", FluidPressure, queue_size=10),
            "link": rospy.Publisher("/relay/link_status", LinkStatus, queue_size=10),
            "thrusters": rospy.Publisher("/auv/thruster_setpoints", ThrusterSetpoints, queue_size=10),
            "rc": rospy.Publisher("/auv/rc_channels", RcChannels, queue_size=10),
        }
        wait_until(lambda: all(p.get_num_connections() for p in cls.pubs.values()), 30.0, step=0.05)
        cls.unconnected = [n for n, p in cls.pubs.items() if p.get_num_connections() == 0]
        cls.heartbeat_start = rospy.Time.now()
        cls.clear_since = cls.rc_since = cls.heartbeat_start + rospy.Duration(2.0)  # test_1 and test_2 set them
        cls.timer = rospy.Timer(rospy.Duration(0.1), cls._heartbeat)

    @classmethod
    def _store(cls, where):
        def cb(m):
            with cls.lock:
                where.append((rospy.Time.now(), m))
        return cb

    @classmethod
    def _on_diag(cls, msg):
        now = rospy.Time.now()
        with cls.lock:
            cls.diags.extend((now, s) for s in msg.status if s.name.endswith("safety supervisor"))

    @classmethod
    def _heartbeat(cls, _event):
        with cls.lock:  # held while publishing: once odom_on is cleared, no odometry follows last_odom
            now = rospy.Time.now()
            if cls.odom_on:
                o = Odometry()
                o.header.stamp, o.header.frame_id, o.child_frame_id = now, "map", "auv/base_link"
                o.pose.pose.position.x, o.pose.pose.position.y, o.pose.pose.position.z = 10.0, 20.0, cls.odom_z
                o.pose.pose.orientation.w = 1.0
                cls.pubs["odom"].publish(o)
                cls.last_odom = now
            beam = SonarBeam(head_status=SonarBeam.STATUS_HEAD_READY | SonarBeam.STATUS_MOTOR_ON,
                             intensities=[0] * 10)
            beam.header.stamp = now
            cls.pubs["sonar"].publish(beam)
            fix = UsblFix(quality=UsblFix.QUALITY_OK)
            fix.header.stamp = now
            cls.pubs["usbl"].publish(fix)
            p = FluidPressure(fluid_pressure=150000.0)
            p.header.stamp = now
            cls.pubs["pressure"].publish(p)
            link = LinkStatus(local_name="auv", peer_name="usv", up=True)
            link.header.stamp = now
            cls.pubs["link"].publish(link)
            if cls.use_rc:
                rc = RcChannels(channels=[1500] * 8)
                rc.header.stamp = now
                cls.pubs["rc"].publish(rc)
            else:
                t = ThrusterSetpoints(thrust=[0.0] * 5, setpoint=[0.0] * 5)
                t.header.stamp = now
                cls.pubs["thrusters"].publish(t)

    def wait_for(self, what, where, pred, timeout):
        """The first (received, message) of `where` for which pred(received, message), waiting at most `timeout`
        s (wall time, which is ROS time here)."""
        item = wait_until(lambda: next((i for i in where if pred(*i)), None), timeout, step=0.02, lock=self.lock)
        if item:
            return item
        with self.lock:
            last = where[-1][1] if where else None
        self.fail("timed out after %.1f s waiting for %s; last: %s" % (timeout, what, last))

    def sleep_until(self, t):
        while not rospy.is_shutdown() and rospy.Time.now() < t:
            rospy.sleep(0.02)

    def test_1_every_input_heard_no_action(self):
        self.assertEqual(self.unconnected, [], "the supervisor did not subscribe to these inputs")
        after = self.heartbeat_start + rospy.Duration(2.0)  # 2 s of heartbeats at 10 Hz
        got, s = self.wait_for("no action after 2 s of heartbeats", self.states,
                               lambda _, m: m.header.stamp >= after and m.action == SafetyState.ACTION_NONE and
                               not m.active_rules, 20.0)
        type(self).clear_since = s.header.stamp
        self.assertEqual(s.vehicle, "auv")
        self.assertEqual(s.action_name, "none")
        self.assertEqual(s.active_rule, "")
        self.assertFalse(s.manual)
        _, d = self.wait_for("diagnostics OK", self.diags,
                             lambda t, st: t >= got and st.level == DiagnosticStatus.OK and
                             {kv.key: kv.value for kv in st.values}.get("action") == "none", 10.0)
        values = {kv.key: kv.value for kv in d.values}
        self.assertEqual(values["bad_input"], "0")
        self.assertIn("transitions", values)
        self.assertEqual(values["vehicle"], "auv")
        self.assertEqual(values["active_rules"], "")

    def test_2_navigation_lost_surfaces_within_the_timeout(self):
        with self.lock:
            type(self).use_rc = True  # the command stream goes on as RC channels (aColor)
            type(self).rc_since = rospy.Time.now()
            type(self).odom_on = False
            t_last = self.last_odom
        self.assertIsNotNone(t_last)
        limit = NAVIGATION_TIMEOUT + SLACK

        def navigation_surface(_, m):
            return m.header.stamp > t_last and m.action == SafetyState.ACTION_SURFACE and \
                m.active_rule == "navigation_timeout" and "navigation_timeout" in m.active_rules

        # the supervisor's own stamps say when it decided; the deadlines only bound the wait for delivery
        _, s = self.wait_for("state: navigation_timeout, surface", self.states, navigation_surface, limit + 5.0)
        dt = (s.header.stamp - t_last).to_sec()
        self.assertLessEqual(dt, limit, "surface %.2f s after the last odometry (timeout %.1f s)" % (dt, NAVIGATION_TIMEOUT))
        self.assertGreaterEqual(dt, NAVIGATION_TIMEOUT - 1e-3, "raised before the timeout")
        self.assertEqual(s.action_name, "surface")
        self.assertIn("navigation", s.reason)
        self.assertFalse(s.manual)

        got, tr = self.wait_for("transition: navigation_timeout active", self.transitions, navigation_surface, 5.0)
        dt = (tr.header.stamp - t_last).to_sec()
        self.assertLessEqual(dt, limit)
        self.assertGreaterEqual(dt, NAVIGATION_TIMEOUT - 1e-3)
        self.assertEqual(tr.vehicle, "auv")
        self.assertIn("silent", tr.reason)

        self.wait_for("diagnostics ERROR (surface, navigation_timeout)", self.diags,
                      lambda t, st: t >= got and st.level == DiagnosticStatus.ERROR and "surface" in st.message and
                      "navigation_timeout" in st.message, 10.0)

    def test_3_beyond_max_depth_surfaces(self):
        with self.lock:  # no odometry is published before t_resume
            type(self).odom_z = -60.0  # 60 m deep; the preset's max_depth is 50 m
            type(self).odom_on = True
            t_resume = rospy.Time.now()

        # navigation is back: released after its release time, as a transition too (action none, not listed)
        _, rel = self.wait_for("transition: navigation_timeout released", self.transitions,
                               lambda _, m: m.header.stamp > t_resume and m.active_rule == "navigation_timeout" and
                               m.action == SafetyState.ACTION_NONE and "navigation_timeout" not in m.active_rules,
                               NAVIGATION_RELEASE + 5.0)
        self.assertGreaterEqual((rel.header.stamp - t_resume).to_sec(), NAVIGATION_RELEASE - 1e-3)
        self.assertIn("released", rel.reason)

        def max_depth(_, m):
            return m.header.stamp > t_resume and m.action == SafetyState.ACTION_SURFACE and \
                m.active_rule == "max_depth" and "max_depth" in m.active_rules

        got, tr = self.wait_for("transition: max_depth active", self.transitions, max_depth,
                                MAX_DEPTH_DETECTION + 5.0)
        self.assertGreaterEqual((tr.header.stamp - t_resume).to_sec(), MAX_DEPTH_DETECTION - 1e-3)
        self.assertIn("depth 60", tr.reason)
        _, s = self.wait_for("state: max_depth, surface", self.states, max_depth, 5.0)
        self.assertEqual(s.action_name, "surface")
        self.assertEqual(list(s.active_rules), ["max_depth"])
        self.wait_for("diagnostics ERROR (max_depth)", self.diags,
                      lambda t, st: t >= got and st.level == DiagnosticStatus.ERROR and "max_depth" in st.message, 10.0)

        # RC channels count as the command stream: no command_timeout (2 s) since the switch, nor any other rule
        self.sleep_until(self.rc_since + rospy.Duration(2.5))
        with self.lock:
            later = [m for _, m in self.states + self.transitions if m.header.stamp > self.clear_since]
        others = [m for m in later if set(m.active_rules) - {"navigation_timeout", "max_depth"}]
        self.assertEqual(others[:1], [], "a rule other than navigation_timeout / max_depth was raised")
        with self.lock:
            self.assertIn("max_depth", self.states[-1][1].active_rules)


if __name__ == "__main__":
    rospy.init_node("safety_supervisor_check")
    rostest.rosrun("offshore_gnc", "safety_supervisor", SafetySupervisorCheck)
