#!/usr/bin/python3
"""One vehicle's master, seen from the main job: mission status as JSON lines, the co-simulation clock, and
topics carried between the masters by the simulated acoustic channel.

    status_monitor.py VEHICLE [--step-topic /usv_sim/sim/step] [--pace TOPIC ...] [--echo TOPIC ...]
                              [--echo-rate HZ] [--publish TOPIC ...]

Prints one JSON line per mission-status change and a heartbeat every wall second (phase, distance to go,
simulated time). With --step-topic the vehicle's simulator runs in lockstep and this process is its clock
hand: each line read on stdin is a simulated time to reach; it publishes the steps (the simulator spreads
them at its rate) and, once /clock got there, prints a line with "reached". The job drives both vehicles'
monitors to the same times, so the two masters share one time base although each has its own simulator and
/clock (rospy binds a process to one master).

--pace TOPIC (repeatable; stamped messages: the vehicle's navigation output and its controller's command) holds a
target back until those topics' stamps got there too (class Pace), so the stack, not only its simulator, keeps up
with the shared clock.

--echo TOPIC (repeatable) subscribes the topic on this master, whatever its type, and prints each message as one
JSON line {"echo": TOPIC, "type": "pkg/Type", "msg": {field: value, ...}} (times as {"secs", "nsecs"}, exact), at
most --echo-rate per topic (default 10 Hz, counted in the messages' header stamps, i.e. simulated time).
--publish TOPIC[:TYPE] (repeatable) takes such lines on stdin (next to the clock's target times) and publishes them
on this master, typed by their "type" tag, field for field (the header stamp unchanged). With a TYPE
("pkg/Type") the publisher is there from the start, so that subscribers (the relay) are connected before the
first line; without, it appears with the first line. A line that is neither a
time nor a line for one of these topics, or whose message does not fit its type, is counted ("bad_lines" in the
status lines) and ignored.
"""
import argparse
import collections
import functools
import json
import struct
import sys
import threading
import time

import genpy
import roslib.message
import rospy
from offshore_gnc.msg import MissionStatus
from std_msgs.msg import UInt32

_out_lock = threading.Lock()


def emit(d):
    with _out_lock:
        print(json.dumps(d), flush=True)


def wait_for_sim_time_param(timeout=60.0):
    # rospy reads /use_sim_time once, at init: wait until the vehicle's launch file has set it
    import rosgraph
    params = rosgraph.Master("/mission_monitor")
    deadline = time.time() + timeout
    while time.time() < deadline:
        try:
            if params.hasParam("/use_sim_time"):
                return
        except OSError:
            pass
        time.sleep(0.2)


def to_plain(v):
    """A message (or field value) as JSON values: messages as {field: value}, times as {"secs", "nsecs"} (exact,
    genpy.message.fill_message_args reads them back), uint8[] as a list of ints."""
    if isinstance(v, genpy.TVal):
        return {"secs": v.secs, "nsecs": v.nsecs}
    if isinstance(v, genpy.Message):
        return {f: to_plain(getattr(v, f)) for f in v.__slots__}
    if isinstance(v, (list, tuple)):
        return [to_plain(x) for x in v]
    if isinstance(v, bytes):
        return list(v)
    return v


def from_plain(msg_type, fields):
    """The message of type "pkg/Type" with these fields (to_plain's output); ValueError when it does not fit."""
    cls = roslib.message.get_message_class(msg_type)
    if cls is None:
        raise ValueError("unknown message type %r" % msg_type)
    m = cls()
    try:
        genpy.message.fill_message_args(m, [fields])
        m._check_types()
    except (genpy.MessageException, genpy.SerializationError, TypeError, AttributeError) as e:
        raise ValueError(str(e))
    return m


class Echo:
    """Prints each message of one topic on this master as a JSON line, at most `rate` per second of its stamps."""

    def __init__(self, topic, rate):
        self.topic, self.period, self.last = topic, 1.0 / rate, None
        self.classes = {}
        self.sub = rospy.Subscriber(topic, rospy.AnyMsg, self.on_msg, queue_size=50)

    def on_msg(self, raw):
        msg_type = raw._connection_header["type"]
        if msg_type not in self.classes:
            self.classes[msg_type] = roslib.message.get_message_class(msg_type)
        cls = self.classes[msg_type]
        if cls is None:
            return
        m = cls().deserialize(raw._buff)
        stamp = getattr(getattr(m, "header", None), "stamp", None)
        t = stamp.to_sec() if isinstance(stamp, genpy.Time) else rospy.get_time()
        if self.last is not None and self.last <= t < self.last + self.period - 1e-6:
            return  # within the period (a stamp going backwards, a restarted clock, starts again)
        self.last = t
        with _out_lock:
            print(json.dumps({"echo": self.topic, "type": msg_type, "msg": to_plain(m)}, separators=(",", ":")),
                  flush=True)


class Republisher:
    """Publishes the echo lines of the named topics on this master; counts the lines it cannot use."""

    def __init__(self, topics):
        self.topics, self.pubs, self.lock = set(), {}, threading.Lock()
        self.published = self.bad_lines = 0
        for spec in topics:
            topic, _, msg_type = spec.partition(":")
            self.topics.add(topic)
            if msg_type:
                cls = roslib.message.get_message_class(msg_type)
                if cls is None:
                    raise SystemExit("--publish %s: unknown message type %r" % (spec, msg_type))
                self.pubs[topic] = rospy.Publisher(topic, cls, queue_size=20, latch=True)

    def line(self, d):
        try:
            topic, msg_type = d["echo"], d["type"]
            if topic not in self.topics:
                raise ValueError("topic %r is not republished here" % topic)
            m = from_plain(msg_type, d["msg"])
            pub = self.pubs.get(topic)
            if pub is None or pub.type != msg_type:
                # latched: a subscriber that connects only once the publisher appears (the relay) still gets it
                pub = self.pubs[topic] = rospy.Publisher(topic, type(m), queue_size=20, latch=True)
            pub.publish(m)
            self.published += 1
        except (KeyError, TypeError, ValueError, rospy.ROSException):
            self.bad()

    def bad(self):
        with self.lock:
            self.bad_lines += 1


class Pace:
    """Lockstep for the stack, not only its simulator. A target time counts as reached once each paced topic's
    latest stamp is within LAG of it: at the job's speed-up a callback a few hundred wall milliseconds late
    (the CPU shared by both stacks) was seconds of simulated time, long enough for the navigation to count as
    stale and the AUV's supervisor to surface it, and for the USV's DP to act on old feedback and circle. A topic
    silent for SILENT simulated seconds is not waited for (a fault or a dead node stopped it, it is not late) until
    it publishes again, and no target is held longer than WAIT wall seconds (counted in `waits`)."""
    LAG, SILENT, WAIT = 0.3, 2.0, 0.3

    def __init__(self, topics):
        self.stamps = {t: None for t in topics}  # None: not published yet, nothing to wait for
        self.waits = 0
        self.subs = [rospy.Subscriber(t, rospy.AnyMsg, functools.partial(self.on_msg, t), queue_size=10)
                     for t in topics]

    def on_msg(self, topic, raw):
        try:  # std_msgs/Header is the first field of every paced type: seq, stamp.secs, stamp.nsecs
            _, secs, nsecs = struct.unpack_from("<3I", raw._buff)
        except struct.error:
            return
        self.stamps[topic] = secs + nsecs * 1e-9

    def caught_up(self, target, now):
        return all(s is None or s >= target - self.LAG or now - s > self.SILENT for s in self.stamps.values())


def read_stdin(on_time, republisher):
    """The job's lines: a number is a simulated time for the clock hand, a JSON object an echo line to publish."""
    for line in sys.stdin:
        line = line.strip()
        if not line:
            continue
        if line.startswith("{"):
            try:
                d = json.loads(line)
            except ValueError:
                d = None
            if republisher and isinstance(d, dict):
                republisher.line(d)
            elif republisher:
                republisher.bad()
            continue
        try:
            target = float(line)
        except ValueError:
            if republisher:
                republisher.bad()
            continue
        if on_time:
            on_time(target)


def clock_hand(step_topic, snapshot, pace):
    """Publishes the simulator steps for each target time at once (the job keeps up to two rounds granted, so the
    simulator never idles between them); reports each target once /clock got there. Returns the function that
    takes a target time (read_stdin calls it). `pace` (a Pace or None) holds a report back until the stack has
    caught up."""
    dt = float(rospy.get_param(step_topic.rsplit("/sim/step", 1)[0] + "/dt", 0.01))
    pub = rospy.Publisher(step_topic, UInt32, queue_size=100)
    while pub.get_num_connections() == 0 and not rospy.is_shutdown():  # the first steps must not be lost
        time.sleep(0.01)
    granted = collections.deque()
    lock = threading.Lock()

    held = [None]  # wall time since which the first granted target waits for the stack

    def report():
        while not rospy.is_shutdown():
            with lock:
                done = []
                while granted and rospy.get_time() >= granted[0][1] - dt / 2:
                    if pace and not pace.caught_up(granted[0][1], rospy.get_time()):
                        held[0] = held[0] or time.monotonic()
                        if time.monotonic() - held[0] < Pace.WAIT:
                            break
                        pace.waits += 1
                    held[0] = None
                    done.append(granted.popleft()[0])
            for target in done:
                emit(dict(snapshot(), reached=target))
            time.sleep(0.001)

    threading.Thread(target=report, daemon=True).start()
    requested = [rospy.get_time()]

    def on_time(target):
        steps = int(round((target - requested[0]) / dt))
        if steps > 0:
            pub.publish(UInt32(steps))
            requested[0] += steps * dt
        with lock:
            granted.append((target, requested[0]))
    return on_time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("vehicle")
    ap.add_argument("--step-topic", default=None)
    ap.add_argument("--pace", action="append", default=[], metavar="TOPIC",
                    help="with --step-topic: a target is reached once this stamped topic got there too (repeatable)")
    ap.add_argument("--echo", action="append", default=[], metavar="TOPIC",
                    help="print this topic's messages as JSON lines (repeatable)")
    ap.add_argument("--echo-rate", type=float, default=10.0, help="at most this many lines per echoed topic [Hz]")
    ap.add_argument("--publish", action="append", default=[], metavar="TOPIC[:TYPE]",
                    help="publish the echo lines of this topic read on stdin (repeatable); with its type, from the "
                         "start")
    a = ap.parse_args()
    if not 0.0 < a.echo_rate <= 10.0:
        ap.error("--echo-rate: 0 < HZ <= 10")
    wait_for_sim_time_param()
    rospy.init_node("mission_monitor_" + a.vehicle, anonymous=True, disable_signals=True)
    last = {}

    republisher = Republisher(a.publish) if a.publish else None
    pace = Pace(a.pace) if a.step_topic and a.pace else None

    def snapshot():
        out = dict(last) if last else {"vehicle": a.vehicle, "phase": "STARTING"}
        out["sim_time"] = rospy.get_time()
        if republisher:
            out.update(republished=republisher.published, bad_lines=republisher.bad_lines)
        if pace:
            out["pace_waits"] = pace.waits
        return out

    def on_status(m):
        changed = m.phase != last.get("phase")
        last.update(vehicle=m.vehicle or a.vehicle, phase=m.phase, distance_to_go=m.distance_to_go,
                    finished=m.finished, success=m.success, detail=m.detail, stamp=m.header.stamp.to_sec(),
                    on_station_since=m.on_station_since if m.on_station_since == m.on_station_since else None)
        if changed:
            emit(snapshot())

    rospy.Subscriber("/%s/mission/status" % a.vehicle, MissionStatus, on_status, queue_size=10)
    echoes = [Echo(topic, a.echo_rate) for topic in a.echo]  # noqa: F841 (kept: their subscribers)

    def stdin_loop():
        on_time = clock_hand(a.step_topic, snapshot, pace) if a.step_topic else None
        read_stdin(on_time, republisher)

    if a.step_topic or republisher:
        threading.Thread(target=stdin_loop, daemon=True).start()
    while not rospy.is_shutdown():
        emit(snapshot())
        time.sleep(1.0)


if __name__ == "__main__":
    main()
