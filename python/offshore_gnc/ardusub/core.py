"""ArduSub bridge logic, ROS-free: what to send to the autopilot and what it reported, given the MAVLink
messages seen and a clock. The link itself is a pymavlink connection (mavutil); this module only decides.

- Our RC commands go out as RC_CHANNELS_OVERRIDE, one per command (the controller's rate and values), to the
  autopilot's system/component learned from its HEARTBEAT.
- Watchdog: when our commands stop for `watchdog_timeout`, every commanded channel goes to neutral (1500 us) and
  the vehicle is disarmed (MAV_CMD_COMPONENT_ARM_DISARM 0); neutral repeats at 1 Hz while the autopilot says armed.
- The pilot wins: a MANUAL_CONTROL or RC_CHANNELS_OVERRIDE from any other system (the pilot's gamepad through
  the ground station) suspends our overrides, arming and the watchdog's disarm for `pilot_timeout` after the last
  one; the channels are released to the pilot once (0 = release) when the override starts.
- Arm and mode: on request, or when commands flow (`arm_on_command`), COMMAND_LONG ARM_DISARM and SET_MODE with
  ArduSub's custom mode numbers; repeated at most once per `command_retry` until the HEARTBEAT shows it.
- In: HEARTBEAT (armed, mode, loss after `heartbeat_timeout`), ATTITUDE, SCALED_PRESSURE* (depth sensor).
"""
import math

NEUTRAL_US = 1500
# ArduSub's flight modes (custom_mode of its HEARTBEAT).
MODES = {"STABILIZE": 0, "ACRO": 1, "ALT_HOLD": 2, "DEPTH_HOLD": 2, "AUTO": 3, "GUIDED": 4, "CIRCLE": 7,
         "SURFACE": 9, "POSHOLD": 16, "MANUAL": 19, "MOTOR_DETECT": 20}
MODE_NAMES = {v: k for k, v in MODES.items() if k != "DEPTH_HOLD"}


class Settings:
    """One place for the bridge's parameters: defaults and ranges (validate() names the bad one)."""
    RANGES = {"watchdog_timeout": (0.1, 30.0), "heartbeat_timeout": (0.5, 60.0), "pilot_timeout": (0.1, 30.0),
              "heartbeat_period": (0.1, 10.0), "command_retry": (0.1, 10.0), "startup_timeout": (0.0, 600.0),
              "min_pulse": (800, 1500), "max_pulse": (1500, 2200), "max_channels": (1, 18)}

    def __init__(self, **kw):
        self.watchdog_timeout = 1.0     # [s] without our commands -> neutral + disarm
        self.heartbeat_timeout = 3.0    # [s] without the autopilot's HEARTBEAT -> link lost
        self.pilot_timeout = 1.0        # [s] the pilot's override holds this long after its last message
        self.heartbeat_period = 1.0     # [s] our own HEARTBEAT (onboard controller)
        self.command_retry = 1.0        # [s] between arm / mode attempts
        self.startup_timeout = 10.0     # [s] for the first HEARTBEAT, else the node fails naming the link
        self.arm_on_command = True
        self.mode = "MANUAL"            # flight mode while our commands drive (our PIDs close the loops)
        self.min_pulse, self.max_pulse = 1100, 1900
        self.max_channels = 8
        for k, v in kw.items():
            if not hasattr(self, k):
                raise ValueError("unknown ArduSub bridge parameter '%s'" % k)
            setattr(self, k, v)
        self.validate()

    def validate(self):
        for k, (lo, hi) in self.RANGES.items():
            v = getattr(self, k)
            if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v) or not lo <= v <= hi:
                raise ValueError("parameter '%s' = %r is out of range [%s, %s]" % (k, v, lo, hi))
        if self.mode.upper() not in MODES:
            raise ValueError("parameter 'mode' = %r is not one of %s" % (self.mode, ", ".join(sorted(MODES))))


class Bridge:
    """Decides. feed(msg, now) with every MAVLink message received; command(channels, now) with ours;
    tick(now) returns the messages to send, as (name, kwargs) for the caller's mav.<name>_send(**kwargs)."""

    def __init__(self, settings, own_system, own_component):
        self.s = settings
        self.own = (own_system, own_component)
        self.autopilot = None           # (system, component) from its HEARTBEAT
        self.last_heartbeat = None
        self.armed = False
        self.mode = None
        self.attitude = None            # (t, roll, pitch, yaw, p, q, r) NED/FRD [rad, rad/s]
        self.pressure = None            # (t, Pa, temperature degC)
        self.last_command = None
        self.channels = []
        self.pending = []               # overrides to send at the next tick
        self.pilot_until = -math.inf
        self.pilot_released = False
        self.watchdog_tripped = False
        self.want_armed = None          # explicit request (True / False) or None
        self.want_mode = None
        self.last_arm_try = self.last_mode_try = self.last_hb_sent = self.last_neutral = -math.inf
        self.counters = {}

    def _count(self, k, n=1):
        self.counters[k] = self.counters.get(k, 0) + n

    # -------------------------------------------------------------- in
    def feed(self, msg, now):
        t = msg.get_type()
        src = (msg.get_srcSystem(), msg.get_srcComponent())
        if t == "BAD_DATA":
            return self._count("bad_data")
        if src == self.own:
            return  # our own messages looped back by a router
        if t == "HEARTBEAT":
            # MAV_AUTOPILOT_INVALID (8) = not a flight controller (ground stations, cameras, ...)
            if msg.autopilot == 8:
                return
            if self.autopilot not in (None, src):
                return self._count("other_autopilots")
            self.autopilot = src
            self.last_heartbeat = now
            self.armed = bool(msg.base_mode & 128)  # MAV_MODE_FLAG_SAFETY_ARMED
            self.mode = msg.custom_mode
            self._count("heartbeats")
        elif src == self.autopilot:
            if t == "ATTITUDE":
                self.attitude = (now, msg.roll, msg.pitch, msg.yaw, msg.rollspeed, msg.pitchspeed, msg.yawspeed)
            elif t in ("SCALED_PRESSURE2", "SCALED_PRESSURE", "SCALED_PRESSURE3"):
                self.pressure = (now, t, msg.press_abs * 100.0, msg.temperature / 100.0)
        elif t in ("MANUAL_CONTROL", "RC_CHANNELS_OVERRIDE"):
            # Another system drives: the pilot (gamepad through the ground station) wins.
            if now >= self.pilot_until:
                self._count("pilot_overrides")
                self.pilot_released = False
            self.pilot_until = now + self.s.pilot_timeout

    def command(self, channels, now):
        """Our controller's RC channels (pulse widths, channel 1 first). Returns False (and counts) when refused."""
        chans = list(channels)
        if not chans or len(chans) > self.s.max_channels or any(
                not isinstance(c, int) or not self.s.min_pulse <= c <= self.s.max_pulse for c in chans):
            self._count("rejected_commands")
            return False
        self.last_command = now
        self.channels = chans
        self.watchdog_tripped = False
        self.pending.append(chans)
        return True

    def request_arm(self, armed):
        self.want_armed = bool(armed)

    def request_mode(self, mode):
        if str(mode).upper() not in MODES:
            self._count("rejected_modes")
            return False
        self.want_mode = MODES[str(mode).upper()]
        return True

    # -------------------------------------------------------------- state
    def heartbeat_age(self, now):
        return math.inf if self.last_heartbeat is None else now - self.last_heartbeat

    def link_ok(self, now):
        return self.heartbeat_age(now) <= self.s.heartbeat_timeout

    def pilot_active(self, now):
        return now < self.pilot_until

    def mode_name(self):
        return MODE_NAMES.get(self.mode, str(self.mode))

    # -------------------------------------------------------------- out
    def _override(self, chans):
        tgt = self.autopilot
        kw = {"target_system": tgt[0], "target_component": tgt[1]}
        for i in range(18):
            # channels 1..8: 0 releases to the radio; 9..18: 0 = ignore
            kw["chan%d_raw" % (i + 1)] = chans[i] if i < len(chans) else 0
        return ("rc_channels_override", kw)

    def _arm(self, arm):
        tgt = self.autopilot
        return ("command_long", {"target_system": tgt[0], "target_component": tgt[1], "command": 400,  # ARM_DISARM
                                 "confirmation": 0, "param1": 1.0 if arm else 0.0, "param2": 0.0, "param3": 0.0,
                                 "param4": 0.0, "param5": 0.0, "param6": 0.0, "param7": 0.0})

    def tick(self, now):
        out = []
        if now - self.last_hb_sent >= self.s.heartbeat_period:
            self.last_hb_sent = now
            # MAV_TYPE_ONBOARD_CONTROLLER (18), MAV_AUTOPILOT_INVALID (8), MAV_STATE_ACTIVE (4)
            out.append(("heartbeat", {"type": 18, "autopilot": 8, "base_mode": 0, "custom_mode": 0, "system_status": 4}))
        if self.autopilot is None:
            if self.pending:
                self._count("commands_without_autopilot", len(self.pending))
                self.pending = []
            return out
        pilot = self.pilot_active(now)
        if pilot:
            if not self.pilot_released:
                self.pilot_released = True
                out.append(self._override([0] * 8))  # hand every channel back to the pilot's radio / gamepad
            self._count("commands_while_pilot", len(self.pending))
            self.pending = []
            return out
        for chans in self.pending:
            out.append(self._override(chans))
            self._count("overrides_sent")
        self.pending = []
        commanding = self.last_command is not None and now - self.last_command <= self.s.watchdog_timeout
        if self.last_command is not None and not commanding and not self.watchdog_tripped:
            self.watchdog_tripped = True
            self._count("watchdog_trips")
            self.want_armed = None
            out.append(self._override([NEUTRAL_US] * len(self.channels)))
            out.append(self._arm(False))
            self.last_neutral = self.last_arm_try = now
        elif self.watchdog_tripped and self.armed and now - self.last_neutral >= 1.0:
            self.last_neutral = self.last_arm_try = now
            out.append(self._override([NEUTRAL_US] * len(self.channels)))
            out.append(self._arm(False))
        want_arm = self.want_armed
        if want_arm is None and commanding and self.s.arm_on_command:
            want_arm = True
        if self.watchdog_tripped and want_arm:
            want_arm = None
        if want_arm is not None and want_arm != self.armed and now - self.last_arm_try >= self.s.command_retry:
            self.last_arm_try = now
            out.append(self._arm(want_arm))
            self._count("arm_requests" if want_arm else "disarm_requests")
        want_mode = self.want_mode
        if want_mode is None and commanding and self.s.arm_on_command:
            want_mode = MODES[self.s.mode.upper()]
        if want_mode is not None and want_mode != self.mode and now - self.last_mode_try >= self.s.command_retry:
            self.last_mode_try = now
            # MAV_MODE_FLAG_CUSTOM_MODE_ENABLED (1), plus ARMED (128) so that the mode change does not disarm
            out.append(("set_mode", {"target_system": self.autopilot[0],
                                     "base_mode": 1 | (128 if self.armed else 0), "custom_mode": want_mode}))
            self._count("mode_requests")
        return out
