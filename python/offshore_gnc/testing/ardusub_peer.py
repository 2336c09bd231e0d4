"""A MAVLink v2 peer on loopback UDP that behaves as ArduSub does for the messages the ArduSub bridge uses
(python/offshore_gnc/ardusub): it sends HEARTBEAT (type SUBMARINE, armed flag, custom mode), ATTITUDE and
SCALED_PRESSURE2, and acts on RC_CHANNELS_OVERRIDE (recorded), COMMAND_LONG ARM_DISARM (with COMMAND_ACK) and
SET_MODE. With `pilot_until` in the future it also forwards a pilot's MANUAL_CONTROL from the ground station
(system 255), as the companion's MAVLink router does. For tests; real bytes over a real socket."""
import os
import socket
import threading
import time

os.environ.setdefault("MAVLINK20", "1")
from pymavlink import mavutil  # noqa: E402


def free_udp_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class FakeArduSub:
    """System 1, component 1 (the autopilot), talking to the bridge's udpin port like a MAVLink router would."""

    def __init__(self, port):
        self.conn = mavutil.mavlink_connection("udpout:127.0.0.1:%d" % port, source_system=1, source_component=1,
                                               dialect="ardupilotmega")
        self.lock = threading.Lock()
        self.armed, self.mode = False, 0  # STABILIZE
        self.overrides, self.arm_commands, self.mode_commands = [], [], []
        self.heartbeats_on = True
        self.pilot_until = 0.0
        self.stop = False
        self.threads = [threading.Thread(target=f, daemon=True) for f in (self._send_loop, self._recv_loop)]
        for t in self.threads:
            t.start()

    def _send_loop(self):
        k = 0
        while not self.stop:
            with self.lock:
                armed, mode, hb, pilot = self.armed, self.mode, self.heartbeats_on, time.time() < self.pilot_until
            if hb and k % 10 == 0:
                self.conn.mav.heartbeat_send(mavutil.mavlink.MAV_TYPE_SUBMARINE, mavutil.mavlink.MAV_AUTOPILOT_ARDUPILOTMEGA,
                                             (128 if armed else 0) | 1, mode, mavutil.mavlink.MAV_STATE_ACTIVE)
            self.conn.mav.attitude_send(k * 100, 0.05, -0.02, 1.2, 0.0, 0.0, 0.1)
            if k % 2 == 0:
                self.conn.mav.scaled_pressure2_send(k * 100, 1300.0, 0.0, 1520)  # 1300 hPa: about 3 m of water
            if pilot:  # the pilot's gamepad, through the ground station (system 255) and the router
                self.conn.mav.srcSystem, self.conn.mav.srcComponent = 255, 190
                self.conn.mav.manual_control_send(1, 0, 0, 500, 300, 0)
                self.conn.mav.srcSystem, self.conn.mav.srcComponent = 1, 1
            k += 1
            time.sleep(0.1)

    def _recv_loop(self):
        while not self.stop:
            m = self.conn.recv_match(blocking=True, timeout=0.1)
            if m is None:
                continue
            t, now = m.get_type(), time.time()
            with self.lock:
                if t == "RC_CHANNELS_OVERRIDE" and m.target_system == 1:
                    self.overrides.append((now, [getattr(m, "chan%d_raw" % i) for i in range(1, 9)]))
                elif t == "COMMAND_LONG" and m.command == mavutil.mavlink.MAV_CMD_COMPONENT_ARM_DISARM:
                    self.armed = m.param1 == 1.0
                    self.arm_commands.append((now, self.armed))
                    self.conn.mav.command_ack_send(m.command, mavutil.mavlink.MAV_RESULT_ACCEPTED)
                elif t == "SET_MODE" and m.target_system == 1:
                    self.mode = m.custom_mode
                    self.mode_commands.append((now, m.custom_mode))

    def snapshot(self):
        with self.lock:
            return list(self.overrides), list(self.arm_commands), list(self.mode_commands), self.armed

    def close(self):
        self.stop = True
        for t in self.threads:
            t.join(2)
        self.conn.close()
