#!/usr/bin/python3
"""The main job: the co-operative mission in simulation, each vehicle in its own ROS master, and its report.

Starts two real masters, the USV and AUV stacks (simulators, perception, guidance, control, mission, relay,
rosbag recording) from launch/usv.launch and launch/auv.launch, follows both missions' progress (phase,
simulated time, distance to go) until the USV holds position at the target (success), the AUV ends its
search without a target, a stack dies, or the simulated-time limit passes; then writes the report folder
(metrics.json, summary.md, map.png, cross_track.png, the rosbags, logs) and prints where it is.
Exit status 0 only if the mission ended as the scenario expects.
"""
import argparse
import datetime
import json
import os
import select
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from offshore_gnc import report, scenario_check  # noqa: E402
from offshore_gnc.testing import MasterSet  # noqa: E402

REPO = os.path.abspath(os.path.join(HERE, "..", ".."))


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", default=os.path.join(REPO, "config", "scenarios", "pyhajarvi.yaml"))
    ap.add_argument("--rviz", action="store_true", help="open rviz on the USV master to watch live")
    ap.add_argument("--out", default=None, help="report folder (default: reports/<scenario>-<time>)")
    ap.add_argument("--rate", type=float, default=20.0, help="simulated seconds per wall second (default 20)")
    ap.add_argument("--max-sim-time", type=float, default=None, help="give up after this simulated time [s]")
    ap.add_argument("--auv-model", default="girona500", choices=["girona500", "acolor"])
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    return ap.parse_args(argv)


class Monitor:
    """Reads the JSON status lines of one vehicle's status_monitor.py."""

    def __init__(self, master, vehicle):
        self.vehicle = vehicle
        self.proc = subprocess.Popen([sys.executable, os.path.join(HERE, "status_monitor.py"), vehicle],
                                     env=master.env(), stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                     start_new_session=True, text=True, bufsize=1)
        master.procs.append(self.proc)
        self.last = {"phase": "STARTING", "sim_time": 0.0}

    def poll(self):
        while select.select([self.proc.stdout], [], [], 0)[0]:
            line = self.proc.stdout.readline()
            if not line:
                break
            try:
                self.last = json.loads(line)
            except ValueError:
                pass
        return self.last


def fmt_progress(u, a):
    def one(s):
        d = s.get("distance_to_go")
        dist = " %.1f m to go" % d if isinstance(d, (int, float)) and d == d and d >= 0 else ""
        return "%s%s" % (s.get("phase", "?"), dist)
    return "[sim %7.1f s] AUV %-14s | USV %s" % (max(u.get("sim_time", 0), a.get("sim_time", 0)), one(a), one(u))


def run(a):
    sc = scenario_check.load(a.scenario)  # refuses a bad scenario before anything starts
    ms_cfg = sc.get("mission", {}) or {}
    expect = ms_cfg.get("expect", "target_reached")
    max_sim = a.max_sim_time or float(ms_cfg.get("max_sim_time", 900.0))
    name = sc.get("name", os.path.splitext(os.path.basename(a.scenario))[0])
    out = os.path.abspath(a.out or os.path.join(REPO, "reports", "%s-%s" % (
        name, datetime.datetime.now().strftime("%Y%m%d-%H%M%S"))))
    os.makedirs(out, exist_ok=True)
    t0 = time.time()
    outcome = {"success": False, "reason": "not started"}
    with MasterSet(["usv", "auv"], log_dir=os.path.join(out, "logs")) as ms:
        common = {"sim": "true", "scenario": os.path.abspath(a.scenario), "rate": str(a.rate), "record": "true"}
        launches = {
            "usv": ms["usv"].roslaunch(os.path.join(REPO, "launch", "usv.launch"), dict(
                common, bag=os.path.join(out, "usv.bag"), rviz=str(a.rviz).lower())),
            "auv": ms["auv"].roslaunch(os.path.join(REPO, "launch", "auv.launch"), dict(
                common, bag=os.path.join(out, "auv.bag"), vehicle_model=a.auv_model)),
        }
        mons = {v: Monitor(ms[v], v) for v in ("usv", "auv")}
        print("[mission] scenario %s, report folder %s" % (a.scenario, out), flush=True)
        last_print = 0.0
        while True:
            time.sleep(0.2)
            u, av = mons["usv"].poll(), mons["auv"].poll()
            dead = [v for v, p in launches.items() if p.poll() is not None]
            sim_t = max(u.get("sim_time", 0.0), av.get("sim_time", 0.0))
            if not a.quiet and time.time() - last_print >= 2.0:
                print(fmt_progress(u, av), flush=True)
                last_print = time.time()
            if dead:
                outcome = {"success": False, "reason": "the %s stack died (exit %s); see logs/" % (
                    ",".join(dead), ",".join(str(launches[v].returncode) for v in dead))}
                if "auv" in dead and "usv" not in dead:
                    outcome["reason"] += "; the USV kept station keeping (%s)" % u.get("phase")
                break
            if expect == "target_reached" and u.get("finished") and u.get("success"):
                outcome = {"success": True, "reason": "USV holds position at the target: " + u.get("detail", "")}
                break
            if av.get("phase") == "NO_TARGET":
                outcome = {"success": expect == "no_target",
                           "reason": "AUV finished its coverage without a detection; USV %s" % u.get("phase")}
                break
            if sim_t > max_sim:
                outcome = {"success": False, "reason": "simulated time limit %.0f s reached (AUV %s, USV %s)" % (
                    max_sim, av.get("phase"), u.get("phase"))}
                break
            if time.time() - t0 > 30 and sim_t == 0.0:
                outcome = {"success": False, "reason": "no simulated time after 30 s: simulators not running"}
                break
        outcome["sim_time_s"] = round(sim_t, 1)
        print(fmt_progress(u, av), flush=True)
        # MasterSet's exit stops roslaunch with SIGINT: rosbag closes its bags cleanly.
    wall = time.time() - t0
    m = report.build(os.path.join(out, "usv.bag"), os.path.join(out, "auv.bag"), a.scenario, out,
                     wall_time_s=round(wall, 2), outcome=outcome)
    print("[mission] %s: %s" % ("SUCCESS" if m["success"] else "FAILED", outcome["reason"]))
    print("[mission] metrics: " + ", ".join("%s=%s" % (k, m[k]) for k in (
        "usv_rmse_m", "auv_rmse_m", "target_error_m", "min_clearance_m", "sim_time_s", "wall_time_s")))
    print("[mission] report: %s" % out)
    return 0 if m["success"] else 1


def main(argv=None):
    a = parse_args(argv)
    try:
        return run(a)
    except scenario_check.ScenarioError as e:
        print("[mission] refused: %s" % e, file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
