#!/usr/bin/python3
"""Micron emulator -> driver -> sonar targets: the scenario's target must come out of SonarTargets at its
position (horizontal error within the target radius plus the simulated navigation error), from beams that the
driver decoded (90 degree forward sector, 1.8 degree step, head ready), with the driver's diagnostics OK."""
import math
import sys
import threading
import unittest

import rospy
import rostest
import yaml
from diagnostic_msgs.msg import DiagnosticArray

from offshore_gnc.msg import SonarBeam, TargetArray
from offshore_gnc.testing.poll import wait_until

SCENARIO = yaml.safe_load(open(sys.argv[1]))


class MicronE2e(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("check_micron_e2e")
        cls.lock = threading.Lock()
        cls.targets, cls.beams, cls.diag = [], [], {}
        rospy.Subscriber("/auv/sonar/targets", TargetArray, cls._store(cls.targets))
        rospy.Subscriber("/auv/sonar/beam", SonarBeam, cls._store(cls.beams))
        rospy.Subscriber("/diagnostics", DiagnosticArray, cls._on_diag)

    @classmethod
    def _store(cls, where):
        def cb(m):
            with cls.lock:
                where.append(m)
        return cb

    @classmethod
    def _on_diag(cls, m):
        with cls.lock:
            for s in m.status:
                cls.diag[s.name] = s

    def _wait(self, pred, timeout):
        return wait_until(pred, timeout, step=0.1, lock=self.lock)

    def test_target_found_at_the_scenario_position(self):
        tg = SCENARIO["targets"][0]

        def err(t):
            return math.hypot(t.nearest.x - tg["north"], t.nearest.y - tg["east"])

        def found():
            return any(err(t) < tg["radius"] + 0.8 for a in self.targets for t in a.targets)
        ok = self._wait(found, 90)
        # The target can show up within the first pass: take two full passes of the sector for the scan checks.
        self._wait(lambda: len(self.beams) > 110, 60)
        with self.lock:
            seen = [(round(t.nearest.x, 2), round(t.nearest.y, 2)) for a in self.targets for t in a.targets]
            beams = list(self.beams)
        self.assertTrue(ok, "target at (%.1f, %.1f) not found; targets seen: %s; %d beams" %
                        (tg["north"], tg["east"], seen[:10], len(beams)))
        self.assertGreater(len(beams), 110)
        bearings = [math.degrees(math.atan2(math.sin(b.bearing), math.cos(b.bearing))) for b in beams]
        self.assertLess(max(bearings), 45.5)
        self.assertGreater(min(bearings), -45.5)
        self.assertGreater(max(bearings), 40.0)
        self.assertLess(min(bearings), -40.0)
        steps = [abs(math.degrees(math.atan2(math.sin(a.bearing - b.bearing), math.cos(a.bearing - b.bearing))))
                 for a, b in zip(beams[1:], beams[:-1])]
        self.assertAlmostEqual(sorted(steps)[len(steps) // 2], 1.8, delta=0.01)
        for b in beams:
            self.assertEqual(b.header.frame_id, "auv/sonar")
            self.assertEqual(len(b.intensities), 200)
            self.assertTrue(b.head_status & SonarBeam.STATUS_HEAD_READY)
        t = [t for a in self.targets for t in a.targets if err(t) < tg["radius"] + 0.8][0]
        self.assertAlmostEqual(t.depth, tg["depth"], delta=1.5)  # the head sees no elevation: its own depth

    def test_driver_diagnostics_report_scanning(self):
        def scanning():
            return any(n.endswith("micron") and s.level == 0 and s.message == "scanning" for n, s in self.diag.items())
        self.assertTrue(self._wait(scanning, 60), "driver diagnostics: %s" %
                        {n: s.message for n, s in self.diag.items()})
        with self.lock:
            s = [s for n, s in self.diag.items() if n.endswith("micron")][0]
        values = {kv.key: kv.value for kv in s.values}
        self.assertEqual(values.get("garbage_bytes", "0"), "0")


if __name__ == "__main__":
    rostest.rosrun("offshore_gnc", "micron_e2e", MicronE2e, sys.argv)
