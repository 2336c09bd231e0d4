#!/usr/bin/python3
"""rostest: the AUV simulator in lockstep. /clock advances exactly by the requested steps; AHRS, depth, sonar and
navigation estimate come at their rates in simulated time with the right frames and values; NaN setpoints are
rejected and counted."""
import math
import time
import unittest

import rospy
import rostest
import tf2_ros
from diagnostic_msgs.msg import DiagnosticArray
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import FluidPressure, Imu
from std_msgs.msg import UInt32

from offshore_gnc.msg import SonarBeam, ThrusterSetpoints
from offshore_gnc.testing.poll import wait_until

DT = 0.01


def rate(msgs, t0, t1):
    return len([m for m in msgs if t0 <= m.header.stamp.to_sec() < t1]) / (t1 - t0)


class AuvSim(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        c = cls.got = {k: [] for k in ("clock", "imu", "pressure", "sonar", "odom", "truth", "diag")}
        cls.subs = [
            rospy.Subscriber("/clock", Clock, lambda m: c["clock"].append(m.clock.to_sec())),
            rospy.Subscriber("/auv/imu", Imu, c["imu"].append),
            rospy.Subscriber("/auv/pressure", FluidPressure, c["pressure"].append),
            rospy.Subscriber("/auv/sonar/beam", SonarBeam, c["sonar"].append),
            rospy.Subscriber("/auv/odom", Odometry, c["odom"].append),
            rospy.Subscriber("/auv/ground_truth/odom", Odometry, c["truth"].append),
            rospy.Subscriber("/diagnostics", DiagnosticArray, c["diag"].append),
        ]
        cls.buf = tf2_ros.Buffer()
        cls.listener = tf2_ros.TransformListener(cls.buf)
        step = rospy.Publisher("/auv_sim/sim/step", UInt32, queue_size=10)
        cls.setpoints = rospy.Publisher("/auv/thruster_setpoints", ThrusterSetpoints, queue_size=10)
        wait_until(lambda: step.get_num_connections() and c["clock"] and cls.setpoints.get_num_connections(), 30,
                   step=0.05)
        time.sleep(0.5)  # let every subscription connect
        cls.clock_before = c["clock"][-1] if c["clock"] else None
        cls.run_steps(step, 500)
        cls.setpoints.publish(ThrusterSetpoints(setpoint=[0.0, 0.0, float("nan"), 0.0, 0.0]))
        cls.setpoints.publish(ThrusterSetpoints(setpoint=[-1.0, -1.0, 0.0, 0.0, 0.0]))  # full ahead (eq. 3.18 signs)
        time.sleep(0.3)
        cls.run_steps(step, 500)
        time.sleep(1.0)  # nothing may move without steps
        cls.clock_idle = c["clock"][-1]
        time.sleep(1.0)  # one more diagnostics period

    @classmethod
    def run_steps(cls, pub, n, chunk=10):
        """Steps in small chunks, each acknowledged on /clock, so that no publisher queue overflows."""
        target = round(cls.got["clock"][-1] / DT)
        for _ in range(n // chunk):
            target += chunk
            pub.publish(UInt32(chunk))
            wait_until(lambda: round(cls.got["clock"][-1] / DT) >= target, 10, step=0.002)

    def test_lockstep_clock(self):
        self.assertAlmostEqual(self.clock_before, 0.0)
        self.assertAlmostEqual(self.got["clock"][-1], 10.0, places=6)
        self.assertAlmostEqual(self.clock_idle, 10.0, places=6)

    def test_rates(self):
        self.assertAlmostEqual(rate(self.got["imu"], 1.0, 9.0), 50.0, delta=2.0)
        self.assertAlmostEqual(rate(self.got["pressure"], 1.0, 9.0), 10.0, delta=0.5)
        self.assertAlmostEqual(rate(self.got["sonar"], 1.0, 9.0), 20.0, delta=1.0)
        self.assertAlmostEqual(rate(self.got["odom"], 1.0, 9.0), 20.0, delta=1.0)

    def test_imu_and_pressure(self):
        m = self.got["imu"][-1]
        self.assertEqual(m.header.frame_id, "auv/base_link")
        self.assertAlmostEqual(m.linear_acceleration.z, 9.81, delta=0.3)  # FLU: gravity reaction is up
        # the pressure gives the true depth (fresh water), within its noise
        for p in self.got["pressure"][-20:]:
            depth = (p.fluid_pressure - 101325.0) / (1000.0 * 9.80665)
            t = min(self.got["truth"], key=lambda m: abs((m.header.stamp - p.header.stamp).to_sec()))
            self.assertLess(abs((t.header.stamp - p.header.stamp).to_sec()), 0.03)
            self.assertAlmostEqual(depth, max(0.0, -t.pose.pose.position.z), delta=0.02)

    def test_sonar_beams(self):
        beams = self.got["sonar"]
        self.assertGreater(len(beams), 150)
        self.assertEqual(beams[-1].header.frame_id, "auv/sonar")
        for b in beams:
            self.assertEqual(len(b.intensities), 200)
            self.assertAlmostEqual(b.range_resolution * 200, 10.0)
            off = min(b.bearing, 2 * math.pi - b.bearing)
            self.assertLessEqual(off, math.radians(45.0) + 1e-6)
            self.assertTrue(b.head_status & SonarBeam.STATUS_HEAD_READY and b.head_status & SonarBeam.STATUS_MOTOR_ON)
        self.assertTrue(any(b.head_status & SonarBeam.STATUS_SECTOR_REVERSE for b in beams))
        self.assertTrue(any(b.head_status & SonarBeam.STATUS_SCAN_CW for b in beams))
        self.assertTrue(any(not b.head_status & SonarBeam.STATUS_SCAN_CW for b in beams))
        # near-field clutter: the first 1.5 m are brighter than the mid range on average
        near = sum(sum(bytearray(b.intensities[:20])) for b in beams) / (20.0 * len(beams))
        mid = sum(sum(bytearray(b.intensities[60:140])) for b in beams) / (80.0 * len(beams))
        self.assertGreater(near, 2 * mid)

    def test_navigation_estimate(self):
        o = self.got["odom"][-1]
        self.assertEqual((o.header.frame_id, o.child_frame_id), ("map", "auv/base_link"))
        t = min(self.got["truth"], key=lambda m: abs((m.header.stamp - o.header.stamp).to_sec()))
        err = math.hypot(o.pose.pose.position.x - t.pose.pose.position.x, o.pose.pose.position.y - t.pose.pose.position.y)
        self.assertLess(err, 1.0)
        self.assertGreater(t.pose.pose.position.y, 5.8)  # moved north (ENU y) after the setpoints
        self.buf.lookup_transform("map", "auv/base_link", rospy.Time(0), rospy.Duration(5))
        s = self.buf.lookup_transform("auv/base_link", "auv/sonar", rospy.Time(0), rospy.Duration(5))
        # the sonar frame is FRD (180 deg about x from the FLU body), its head tilted 15 deg down (sim::SonarConfig
        # tilt): 180 deg about x composed with 15 deg about y, q = (cos 7.5 deg, 0, +-sin 7.5 deg, 0) in (x, y, z, w)
        q = s.transform.rotation
        self.assertAlmostEqual(abs(q.x), math.cos(math.radians(7.5)), places=6)
        self.assertAlmostEqual(q.y, 0.0, places=6)
        self.assertAlmostEqual(abs(q.z), math.sin(math.radians(7.5)), places=6)
        self.assertAlmostEqual(q.w, 0.0, places=6)

    def test_nan_setpoints_counted(self):
        values, names = {}, set()
        for arr in self.got["diag"]:
            for st in arr.status:
                names.add(st.name)
                if "auv_sim" in st.name:
                    values.update({kv.key: kv.value for kv in st.values})
        self.assertGreaterEqual(int(values.get("rejected_commands", 0)), 1, (values, names))


if __name__ == "__main__":
    rospy.init_node("check_auv_sim")
    rostest.rosrun("offshore_gnc", "check_auv_sim", AuvSim)
