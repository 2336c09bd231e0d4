#!/usr/bin/python3
"""Prints one JSON line per mission-status change (and a heartbeat every wall second) of one vehicle's master.

The main job runs one monitor per master (rospy binds a process to one master), reads the lines and shows
progress: phase, simulated time, distance to go.
"""
import json
import sys
import time

import rospy
from offshore_gnc.msg import MissionStatus


def main():
    vehicle = sys.argv[1]
    # rospy reads /use_sim_time once, at init: wait until the vehicle's launch file has set it
    import rosgraph
    params = rosgraph.Master("/mission_monitor")
    deadline = time.time() + 60
    while time.time() < deadline:
        try:
            if params.hasParam("/use_sim_time"):
                break
        except OSError:
            pass
        time.sleep(0.2)
    rospy.init_node("mission_monitor_" + vehicle, anonymous=True, disable_signals=True)
    last = {}

    def on_status(m):
        last.update(vehicle=m.vehicle or vehicle, phase=m.phase, distance_to_go=m.distance_to_go,
                    finished=m.finished, success=m.success, detail=m.detail, stamp=m.header.stamp.to_sec())

    rospy.Subscriber("/%s/mission/status" % vehicle, MissionStatus, on_status, queue_size=10)
    while not rospy.is_shutdown():
        out = dict(last) if last else {"vehicle": vehicle, "phase": "STARTING"}
        out["sim_time"] = rospy.get_time()
        print(json.dumps(out), flush=True)
        time.sleep(1.0)


if __name__ == "__main__":
    main()
