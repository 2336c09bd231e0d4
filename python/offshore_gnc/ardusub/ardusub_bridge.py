#!/usr/bin/python3
"""ardusub_bridge: the aColor AUV's Pixhawk (ArduSub) over MAVLink v2, UDP or serial (pymavlink).

    /auv/rc_channels (offshore_gnc/RcChannels)  -> RC_CHANNELS_OVERRIDE (our controller's rate and values)
    /auv/autopilot/arm (std_msgs/Bool), /auv/autopilot/mode (std_msgs/String)  -> ARM_DISARM, SET_MODE
    ATTITUDE -> /auv/imu (sensor_msgs/Imu, ENU/FLU like the rest of the stack)
    SCALED_PRESSURE2 (the external depth sensor; `pressure_message`) -> /auv/pressure (sensor_msgs/FluidPressure)
    HEARTBEAT -> diagnostics (armed, mode, heartbeat age: ERROR when lost), counters

Parameters (private): url (pymavlink connection string, e.g. udpin:0.0.0.0:14550, /dev/ttyACM0), baud,
source_system, source_component, frame_id, pressure_message, and every core.Settings field. The logic lives in
core.Bridge; this file only moves messages. A link that cannot be opened, or no HEARTBEAT within
startup_timeout, ends the node with a FATAL naming the link.
"""
import math
import os
import sys
import threading
import time

os.environ.setdefault("MAVLINK20", "1")  # MAVLink v2 framing (pymavlink reads this at import)
from pymavlink import mavutil  # noqa: E402

import rospy  # noqa: E402
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue  # noqa: E402
from sensor_msgs.msg import FluidPressure, Imu  # noqa: E402
from std_msgs.msg import Bool, String  # noqa: E402

from offshore_gnc.ardusub.core import Bridge, Settings  # noqa: E402
from offshore_gnc.msg import RcChannels  # noqa: E402


def enu_quaternion(roll, pitch, yaw_ned):
    """FLU body in ENU from NED/FRD Euler angles (the simulator's convention, sim_ros::enuQuaternion)."""
    r, p, y = roll, -pitch, math.pi / 2 - yaw_ned
    cr, sr, cp, sp, cy, sy = (math.cos(r / 2), math.sin(r / 2), math.cos(p / 2), math.sin(p / 2),
                              math.cos(y / 2), math.sin(y / 2))
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


class Node:
    def __init__(self):
        g = rospy.get_param
        self.url = g("~url", "udpin:0.0.0.0:14550")
        self.baud = int(g("~baud", 115200))
        self.frame_id = g("~frame_id", "auv/base_link")
        self.pressure_message = g("~pressure_message", "SCALED_PRESSURE2")
        sysid, compid = int(g("~source_system", 1)), int(g("~source_component", 191))  # MAV_COMP_ID_ONBOARD_COMPUTER
        fields = {k: g("~" + k) for k in vars(Settings()) if rospy.has_param("~" + k)}
        self.settings = Settings(**fields)
        self.bridge = Bridge(self.settings, sysid, compid)
        self.lock = threading.Lock()
        self.conn = mavutil.mavlink_connection(self.url, baud=self.baud, source_system=sysid,
                                               source_component=compid, autoreconnect=True, dialect="ardupilotmega")
        self.imu_pub = rospy.Publisher("/auv/imu", Imu, queue_size=20)
        self.pressure_pub = rospy.Publisher("/auv/pressure", FluidPressure, queue_size=10)
        self.diag_pub = rospy.Publisher("/diagnostics", DiagnosticArray, queue_size=5)
        rospy.Subscriber("/auv/rc_channels", RcChannels, self.on_rc, queue_size=20)
        rospy.Subscriber("/auv/autopilot/arm", Bool, lambda m: self._locked(self.bridge.request_arm, m.data))
        rospy.Subscriber("/auv/autopilot/mode", String, lambda m: self._locked(self.bridge.request_mode, m.data))
        self.last_att = self.last_press = None

    def _locked(self, f, *a):
        with self.lock:
            return f(*a)

    def on_rc(self, m):
        with self.lock:
            if not self.bridge.command(list(m.channels), time.monotonic()):
                rospy.logwarn_throttle(5.0, "ardusub: refused RC channels %s (1..%d channels of %d..%d us)" % (
                    list(m.channels), self.settings.max_channels, self.settings.min_pulse, self.settings.max_pulse))
            self._send(self.bridge.tick(time.monotonic()))  # forward at once: the controller sets the rate

    def _send(self, out):
        for name, kw in out:
            try:
                getattr(self.conn.mav, name + "_send")(**kw)
            except (OSError, ValueError) as e:
                self.bridge._count("send_errors")
                rospy.logwarn_throttle(5.0, "ardusub: sending %s failed: %s" % (name, e))

    def receive_loop(self):
        while not rospy.is_shutdown():
            try:
                msg = self.conn.recv_match(blocking=True, timeout=0.05)
            except (OSError, ValueError) as e:
                with self.lock:
                    self.bridge._count("link_errors")
                rospy.logwarn_throttle(5.0, "ardusub: link %s: %s" % (self.url, e))
                time.sleep(0.5)
                continue
            if msg is None:
                continue
            with self.lock:
                self.bridge.feed(msg, time.monotonic())
                att, press = self.bridge.attitude, self.bridge.pressure
            if att is not None and att is not self.last_att:
                self.last_att = att
                self.publish_imu(att)
            if press is not None and press is not self.last_press and press[1] == self.pressure_message:
                self.last_press = press
                fp = FluidPressure()
                fp.header.stamp = rospy.Time.now()
                fp.header.frame_id = self.frame_id
                fp.fluid_pressure = press[2]
                self.pressure_pub.publish(fp)

    def publish_imu(self, att):
        _, roll, pitch, yaw, p, q, r = att
        m = Imu()
        m.header.stamp = rospy.Time.now()
        m.header.frame_id = self.frame_id
        m.orientation.x, m.orientation.y, m.orientation.z, m.orientation.w = enu_quaternion(roll, pitch, yaw)
        m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z = p, -q, -r  # FRD -> FLU
        m.linear_acceleration_covariance[0] = -1.0  # not provided (REP-145)
        self.imu_pub.publish(m)

    def diagnostics(self):
        now = time.monotonic()
        with self.lock:
            b = self.bridge
            st = DiagnosticStatus(name=rospy.get_name() + ": ardusub", hardware_id="ardusub:" + self.url)
            if not b.link_ok(now):
                st.level, st.message = DiagnosticStatus.ERROR, "no HEARTBEAT from the autopilot for %.1f s" % b.heartbeat_age(now)
            elif b.pilot_active(now):
                st.level, st.message = DiagnosticStatus.WARN, "pilot override (gamepad / ground station)"
            elif b.watchdog_tripped:
                st.level, st.message = DiagnosticStatus.WARN, "no commands: neutral and disarmed by the watchdog"
            else:
                st.level, st.message = DiagnosticStatus.OK, "armed" if b.armed else "disarmed"
            values = {"armed": b.armed, "mode": b.mode_name(), "heartbeat_age_s": round(b.heartbeat_age(now), 2),
                      "autopilot": b.autopilot, "pilot_override": b.pilot_active(now),
                      "watchdog_tripped": b.watchdog_tripped}
            values.update(b.counters)
            out = self.bridge.tick(now)
        st.values = [KeyValue(key=str(k), value=str(v)) for k, v in values.items()]
        a = DiagnosticArray(status=[st])
        a.header.stamp = rospy.Time.now()
        self.diag_pub.publish(a)
        return out

    def wait_for_autopilot(self):
        deadline = time.monotonic() + self.settings.startup_timeout
        while time.monotonic() < deadline and not rospy.is_shutdown():
            with self.lock:
                if self.bridge.autopilot is not None:
                    return True
            with self.lock:
                out = self.bridge.tick(time.monotonic())  # our HEARTBEAT lets a udpout autopilot find us
            self._send(out)
            time.sleep(0.05)
        return False

    def spin(self):
        threading.Thread(target=self.receive_loop, daemon=True).start()
        if not self.wait_for_autopilot():
            rospy.logfatal("ArduSub bridge: no HEARTBEAT from the autopilot on '%s' within %.0f s; is the Pixhawk "
                           "powered and the companion's MAVLink router forwarding to this port?" %
                           (self.url, self.settings.startup_timeout))
            return 1
        rospy.loginfo("ArduSub bridge: autopilot %s on %s" % (self.bridge.autopilot, self.url))
        last_diag = 0.0
        while not rospy.is_shutdown():
            now = time.monotonic()
            with self.lock:
                out = self.bridge.tick(now)
            self._send(out)
            if now - last_diag >= 1.0:
                last_diag = now
                self._send(self.diagnostics())
            time.sleep(0.02)
        return 0


def main():
    rospy.init_node("ardusub_bridge")
    try:
        node = Node()
    except (ValueError, OSError) as e:
        # A missing serial device, a port in use, or a parameter out of range: say which, and stop.
        rospy.logfatal("ArduSub bridge: cannot start on '%s': %s" % (rospy.get_param("~url", "udpin:0.0.0.0:14550"), e))
        return 1
    return node.spin()


if __name__ == "__main__":
    sys.exit(main())
