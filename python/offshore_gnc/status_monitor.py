#!/usr/bin/python3
"""One vehicle's master, seen from the main job: mission status as JSON lines, and the co-simulation clock.

    status_monitor.py VEHICLE [--step-topic /usv_sim/sim/step]

Prints one JSON line per mission-status change and a heartbeat every wall second (phase, distance to go,
simulated time). With --step-topic the vehicle's simulator runs in lockstep and this process is its clock
hand: each line read on stdin is a simulated time to reach; it publishes the steps (the simulator spreads
them at its rate) and, once /clock got there, prints a line with "reached". The job drives both vehicles' monitors to the same times, so the two masters
share one time base although each has its own simulator and /clock (rospy binds a process to one master).
"""
import argparse
import collections
import json
import sys
import threading
import time

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


def clock_hand(step_topic, snapshot):
    """Reads target times on stdin and publishes the simulator steps at once (the job keeps up to two rounds
    granted, so the simulator never idles between them); reports each target once /clock got there."""
    dt = float(rospy.get_param(step_topic.rsplit("/sim/step", 1)[0] + "/dt", 0.01))
    pub = rospy.Publisher(step_topic, UInt32, queue_size=100)
    while pub.get_num_connections() == 0 and not rospy.is_shutdown():  # the first steps must not be lost
        time.sleep(0.01)
    granted = collections.deque()
    lock = threading.Lock()

    def report():
        while not rospy.is_shutdown():
            with lock:
                done = []
                while granted and rospy.get_time() >= granted[0][1] - dt / 2:
                    done.append(granted.popleft()[0])
            for target in done:
                emit(dict(snapshot(), reached=target))
            time.sleep(0.001)

    threading.Thread(target=report, daemon=True).start()
    requested = rospy.get_time()
    for line in sys.stdin:
        try:
            target = float(line)
        except ValueError:
            continue
        steps = int(round((target - requested) / dt))
        if steps > 0:
            pub.publish(UInt32(steps))
            requested += steps * dt
        with lock:
            granted.append((target, requested))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("vehicle")
    ap.add_argument("--step-topic", default=None)
    a = ap.parse_args()
    wait_for_sim_time_param()
    rospy.init_node("mission_monitor_" + a.vehicle, anonymous=True, disable_signals=True)
    last = {}

    def snapshot():
        out = dict(last) if last else {"vehicle": a.vehicle, "phase": "STARTING"}
        out["sim_time"] = rospy.get_time()
        return out

    def on_status(m):
        changed = m.phase != last.get("phase")
        last.update(vehicle=m.vehicle or a.vehicle, phase=m.phase, distance_to_go=m.distance_to_go,
                    finished=m.finished, success=m.success, detail=m.detail, stamp=m.header.stamp.to_sec())
        if changed:
            emit(snapshot())

    rospy.Subscriber("/%s/mission/status" % a.vehicle, MissionStatus, on_status, queue_size=10)
    if a.step_topic:
        threading.Thread(target=clock_hand, args=(a.step_topic, snapshot), daemon=True).start()
    while not rospy.is_shutdown():
        emit(snapshot())
        time.sleep(1.0)


if __name__ == "__main__":
    main()
