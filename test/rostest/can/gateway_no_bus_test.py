#!/usr/bin/python3
"""CanGateway without its interface: diagnostics and the latched bus state say the bus is down, bad commands are
counted, the jets (never heard) are reported not answering, no crash."""
import math
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from offshore_gnc.msg import CanBusState, JoystickCommand, WaterjetAnswering
from offshore_gnc.testing.poll import wait_until


class GatewayNoBus(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("gateway_no_bus_test")
        cls.statuses = []
        cls.answering = []
        cls.sub = rospy.Subscriber("/diagnostics", DiagnosticArray, cls.on_diag)
        cls.answering_sub = rospy.Subscriber("/usv/waterjet/answering", WaterjetAnswering,
                                             lambda m: cls.answering.append(list(m.answering)))
        cls.bus_states = []
        cls.bus_sub = rospy.Subscriber("/usv/can/bus_state", CanBusState,
                                       lambda m: cls.bus_states.append((m.state, m.state_name)))
        cls.pub = rospy.Publisher("/usv/joystick_cmd", JoystickCommand, queue_size=10)

    @classmethod
    def on_diag(cls, msg):
        cls.statuses.extend(s for s in msg.status if "can gateway" in s.name)

    def wait_for(self, pred, timeout=20.0):
        """The first gateway status for which pred(status), or None."""
        return wait_until(lambda: next((s for s in list(self.statuses) if pred(s)), None), timeout)

    def test_down_bus_reported_and_bad_commands_counted(self):
        s = self.wait_for(lambda s: True)
        self.assertIsNotNone(s, "no diagnostics from the gateway")
        self.assertEqual(s.level, DiagnosticStatus.ERROR)
        self.assertIn("down", s.message)
        wait_until(lambda: self.pub.get_num_connections() > 0, 5.0, step=0.05)
        for v in (math.nan, 2.0, -math.inf):
            self.pub.publish(JoystickCommand(surge=v))
        self.pub.publish(JoystickCommand(surge=0.3))
        s = self.wait_for(lambda s: any(kv.key == "autonomy_out_of_range" and int(kv.value) == 3 for kv in s.values))
        self.assertIsNotNone(s, "bad commands not counted: %s" % (self.statuses[-1].values if self.statuses else None))
        values = {kv.key: kv.value for kv in s.values}
        self.assertEqual(values["bus_state"], "down")
        self.assertIn(values["mode"], ("autonomy", "watchdog", "jet_silent"))
        # No status frame can arrive: after jet_timeout (0.5 s) both jets are reported not answering.
        s = self.wait_for(lambda s: any(kv.key == "starboard_jet" and kv.value == "not answering" for kv in s.values))
        self.assertIsNotNone(s, "silent jets not in the diagnostics")
        values = {kv.key: kv.value for kv in s.values}
        self.assertEqual(values["port_jet"], "not answering")
        self.assertGreaterEqual(int(values["port_jet_timeouts"]), 1)
        wait_until(lambda: [False, False] in self.answering, 5.0, step=0.05)
        self.assertIn([False, False], self.answering, "latched /usv/waterjet/answering: %s" % self.answering)
        # the safety supervisor's bus_off rule takes a bus that is down as off
        wait_until(lambda: self.bus_states, 5.0, step=0.05)
        self.assertEqual(self.bus_states[:1], [(CanBusState.STATE_DOWN, "down")], "latched /usv/can/bus_state")


if __name__ == "__main__":
    rostest.rosrun("offshore_gnc", "gateway_no_bus", GatewayNoBus)
