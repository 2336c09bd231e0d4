#!/usr/bin/python3
"""The main job: the co-operative mission in simulation, each vehicle in its own ROS master, and its report.

Starts two real masters, the USV and AUV stacks (simulators, perception, guidance, control, mission, relay,
rosbag recording) from launch/usv.launch and launch/auv.launch, follows both missions' progress (phase,
simulated time, distance to go) until the USV reports the AUV recovered (RECOVERED: after the find the AUV came up
and the USV holds beside it, both stationary; docs/mission.md), a stack dies, or the simulated-time limit passes;
then writes the report folder
(metrics.json, summary.md, map.png, cross_track.png, the rosbags, logs, rviz_usv.png with --screenshot) and
prints where it is. Exit status 0 only if the mission ended as the scenario expects.

When one vehicle's stack dies (or is killed with --kill, to test exactly that), the job keeps watching the other
one for --after-kill simulated seconds (or until it finishes) so that the report says what it did meanwhile.

--auv-navigation usbl (the default) navigates the AUV on USBL fixes (auv.launch navigation:=usbl: the USBL node,
the beacon simulator and the AuvNavigation filter on fixes, depth, AHRS and DVL publish /auv/odom); ins keeps the
simulator's INS-like estimate. With usbl the job is the simulated acoustic channel: the beacon simulator on the
AUV master needs the USV's true pose, so the USV's monitor echoes /usv/ground_truth/odom (10 Hz of simulated time)
and the job hands each line to the AUV's monitor, which republishes it there with its header stamp (both masters
run on the one lockstep clock). Simulation only: on the vehicles the acoustic link itself carries the signal.

The relays talk through the simulated radio (python/offshore_gnc/radio.py: latency, rate and losses of a WiFi link
over water, config/relay/radio.yaml or --radio FILE), which the `link` fault takes down. --seed S draws every
simulated sensor's noise and field effects, and the radio's, anew (S = 1: the launch files' seeds, as
mission_rosfree --seed).
"""
import argparse
import datetime
import json
import os
import select
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from offshore_gnc import VEHICLES, report, scenario_check  # noqa: E402
from offshore_gnc import radio as radio_link  # noqa: E402
from offshore_gnc import vehicles  # noqa: E402
from offshore_gnc.testing import MasterSet  # noqa: E402
from offshore_gnc.testing.masters import free_port, kill_tree  # noqa: E402

REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
# The geofence fault's target (common/faults.h kGeofenceTargetNorth: 5 km north of the origin, NED [m]), outside the USV's
# operating region (safety::usvDefaults(): a 2 km square about the origin)
PHANTOM_TARGET_NED = (5000.0, 0.0, 5.0)


def relay_configs(folder, speedup):
    """config/relay/{usv,auv}.yaml with the link on a free port instead of the fixed 11411 (two missions on one
    machine would otherwise share a link, both holding the same simulation key), and each topic's rate limit
    (the relay counts in wall seconds) times the simulation's speed-up, so that /usv_gps still reaches the AUV
    at its rate in simulated time (0: as fast as possible, unlimited). The AUV's relay dials the simulated radio
    (radio.RADIO_HOST at the USV relay's port) and listens on a port of its own, where its UDP socket is bound
    (the radio forwards the USV's datagrams there). Returns (vehicle -> file, the USV relay's port, the AUV's)."""
    import yaml
    files = {}
    port, auv_port = free_port(), free_port()
    for v in VEHICLES:
        with open(os.path.join(REPO, "config", "relay", v + ".yaml")) as f:
            c = yaml.safe_load(f)
        if c.get("listen_port"):
            c["listen_port"] = port
        if v == "auv":
            c["listen_host"], c["listen_port"] = "127.0.0.1", auv_port
        for p in c.get("peers", []):
            if p.get("address"):
                p["address"] = "%s:%d" % (radio_link.RADIO_HOST, port)
        for t in c.get("topics", []):
            if t.get("rate_hz"):
                t["rate_hz"] = float(t["rate_hz"]) * speedup if speedup > 0 else 0.0
        files[v] = os.path.join(folder, "relay-%s.yaml" % v)
        with open(files[v], "w") as f:
            yaml.safe_dump(c, f)
    return files, port, auv_port


def vehicle_configs(auv_model):
    """The vehicles' configs the stacks get (the launch files' defaults). They describe the vehicles only: the
    site's origin is the scenario's, which the launch files give every node (launch/site.launch). Returns
    vehicle -> file."""
    return {"usv": vehicles.vehicle_config("usv"), "auv": vehicles.vehicle_config("auv", auv_model)}


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", default=os.path.join(REPO, "config", "scenarios", "pyhajarvi.yaml"))
    ap.add_argument("--rviz", action="store_true", help="open rviz on the USV master to watch live")
    ap.add_argument("--out", default=None, help="report folder (default: reports/<scenario>-<time>)")
    ap.add_argument("--rate", type=float, default=20.0,
                    help="at most this many simulated seconds per wall second (default 20; 0 = as fast as possible)")
    ap.add_argument("--free-running", action="store_true",
                    help="each simulator keeps its own clock at --rate (no shared lockstep time)")
    ap.add_argument("--max-sim-time", type=float, default=None, help="give up after this simulated time [s]")
    ap.add_argument("--auv-model", default=vehicles.auv_models()[0], choices=vehicles.auv_models())
    ap.add_argument("--auv-navigation", default="usbl", choices=["usbl", "ins"],
                    help="usbl (default): the AUV navigates on USBL fixes, depth, AHRS and DVL (the job carries the "
                         "USV's true pose to the AUV master's beacon simulator); ins: the simulator's INS-like "
                         "estimate")
    ap.add_argument("--usv-params", default="", metavar="FILE",
                    help="the simulated USV's model parameter file (config/models/ schema, e.g. from model_fit)")
    ap.add_argument("--seed", type=int, default=1,
                    help="the run's seed S >= 1: every simulated sensor's noise and field effects and the radio's "
                         "losses (USV simulator 2S-1, AUV 2S, USBL pair 2S-1, as mission_rosfree --seed; default 1)")
    ap.add_argument("--radio", default=os.path.join(REPO, "config", "relay", "radio.yaml"), metavar="FILE",
                    help="the simulated radio between the relays (sim::RadioParams keys over the defaults)")
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    ap.add_argument("--screenshot", action="store_true",
                    help="rviz (USV configuration) under Xvfb during the mission: rviz_usv.png in the report")
    ap.add_argument("--kill", metavar="VEHICLE@SIM_S", default=None,
                    help="fault injection: SIGKILL one vehicle's whole stack at this simulated time, e.g. auv@120, "
                         "or this long after the AUV reports its find, e.g. usv@found+12 (the find's time depends on "
                         "the sea and the search)")
    ap.add_argument("--fault", action="append", default=[], metavar="NAME@START_S[+DURATION_S]",
                    help="fault injection (repeatable), e.g. usbl@150+60 (no USBL reply for 60 s from sim 150 s); "
                         "NAME is a kind of docs/safety.md's table (offshore_gnc::faultKinds(); an unknown one is "
                         "refused with the list); without a duration it lasts to the end. The report lists each fault "
                         "and the safety supervisor's response")
    ap.add_argument("--after-kill", type=float, default=60.0,
                    help="simulated seconds to keep watching the surviving vehicle after a stack died (default 60)")
    a = ap.parse_args(argv)
    if a.seed < 1:
        ap.error("--seed: 1 or more")
    if a.usv_params and not os.path.isfile(a.usv_params):
        ap.error("--usv-params: no file %s" % a.usv_params)
    if a.kill:
        v, _, t = a.kill.partition("@")
        try:  # (vehicle, simulated time or None, seconds after the find or None)
            a.kill = (v, None, float(t[len("found+"):])) if t.startswith("found+") else (v, float(t), None)
        except ValueError:
            ap.error("--kill wants VEHICLE@SIM_S or VEHICLE@found+S, e.g. auv@120, usv@found+12")
        if v not in VEHICLES:
            ap.error("--kill: the vehicle is one of " + ", ".join(VEHICLES))
    return a


class Monitor:
    """One vehicle's status_monitor.py: its JSON status lines, its simulator's clock in lockstep, and the topics
    it echoes (`echo`, printed as lines kept in `echoed` for the job to forward) or republishes (`publish`)."""

    def __init__(self, master, vehicle, lockstep, echo=(), publish=()):
        self.vehicle = vehicle
        cmd = [sys.executable, os.path.join(HERE, "status_monitor.py"), vehicle]
        if lockstep:
            cmd += ["--step-topic", "/%s_sim/sim/step" % vehicle]
            for t in STACK_PACE[vehicle]:
                cmd += ["--pace", t]
        for t in echo:
            cmd += ["--echo", t]
        for t in publish:
            cmd += ["--publish", t]
        self.proc = subprocess.Popen(cmd, env=master.env(), stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL, start_new_session=True, text=True, bufsize=1)
        master.procs.append(self.proc)
        self.last = {"phase": "STARTING", "sim_time": 0.0}
        self.reached = 0.0
        self.echoed = []  # (topic, raw line) of echo lines since the last take_echoed()
        self.bad_lines = 0

    def poll(self):
        while select.select([self.proc.stdout], [], [], 0)[0]:
            line = self.proc.stdout.readline()
            if not line:
                break
            try:
                d = json.loads(line)
            except ValueError:
                self.bad_lines += 1
                continue
            if not isinstance(d, dict):
                self.bad_lines += 1
            elif "echo" in d:
                self.echoed.append((d["echo"], line))
            else:
                self.last = d
                self.reached = self.last.get("reached", self.reached)
        return self.last

    def take_echoed(self):
        out, self.echoed = self.echoed, []
        return out

    def send(self, line):
        """Hands an echo line to this monitor without ever blocking the job: False (the line dropped) when the
        monitor is dead or its stdin pipe is full (not reading yet, or behind)."""
        try:
            if self.proc.poll() is not None or not select.select([], [self.proc.stdin], [], 0)[1]:
                return False
            self.proc.stdin.write(line if line.endswith("\n") else line + "\n")
            return True
        except (BrokenPipeError, ValueError, OSError):
            return False

    def advance(self, t):
        """Let the simulator run up to simulated time t (lockstep)."""
        try:
            self.proc.stdin.write("%.3f\n" % t)
        except (BrokenPipeError, ValueError):
            pass


class AcousticChannel:
    """The simulated acoustic channel (simulation only): the echo lines of TOPICS from one vehicle's monitor go to
    the other's, which republishes them on its master. Counts what it forwarded and what it had to drop."""
    TOPICS = ("/usv/ground_truth/odom",)  # the beacon simulator on the AUV master answers from the USV's truth

    def __init__(self, source, sink):
        self.source, self.sink = source, sink
        self.forwarded = self.dropped = 0

    def pump(self):
        for topic, line in self.source.take_echoed():
            if topic not in self.TOPICS:
                continue
            if self.sink.send(line):
                self.forwarded += 1
            else:
                self.dropped += 1

    def summary(self):
        return "%d forwarded, %d dropped, %d unparsable from the %s monitor, %s republished, %s refused by the %s's" % (
            self.forwarded, self.dropped, self.source.bad_lines, self.source.vehicle,
            self.sink.last.get("republished", "?"), self.sink.last.get("bad_lines", "?"), self.sink.vehicle)


# What each vehicle's stack advertises once its nodelets are loaded: navigation, guidance, control, the mission.
STACK_TOPICS = {"usv": ["/usv/odom", "/usv/guidance/status", "/usv/joystick_cmd", "/usv/mission/status"],
                "auv": ["/auv/guidance/status", "/auv/mission/status"]}
STACK_READY_S = 60.0
# In lockstep the clock also waits for these (stamped) outputs of each stack: its navigation and its controller's
# command (status_monitor.Pace). Those of another vehicle model never publish and are not waited for.
STACK_PACE = {"usv": ["/usv/odom", "/usv/joystick_cmd"],
              "auv": ["/auv/odom", "/auv/thruster_setpoints", "/auv/rc_channels"]}


class SharedClock:
    """Co-simulation time: both simulators run in lockstep to the same simulated times, granted in rounds of
    CHUNK seconds with at most two rounds outstanding, so neither gets more than 2 CHUNK ahead of the other.
    Each simulator spreads its steps at --rate; the slower one sets the pace (the USV's LiDAR costs more CPU
    than the AUV's sonar: free-running, their clocks drifted apart by minutes over one mission)."""
    CHUNK = 0.5

    def __init__(self, monitors):
        self.monitors, self.target = monitors, 0.0

    def tick(self, alive):
        live = [self.monitors[v] for v in alive]
        while live and all(m.reached >= self.target - self.CHUNK - 1e-6 for m in live):
            self.target += self.CHUNK
            for m in live:
                m.advance(self.target)


class Screenshots:
    """rviz with the USV configuration under Xvfb, shot every few wall seconds once the USV is under way; keeps
    the shot where the planned path, the target from the AUV and the safety boxes are all drawn (the last such).
    A shot only starts the `import` process and never waits for it: the job's loop drives the shared lockstep
    clock, and shots taken and scored in the loop (seconds each on a loaded machine) stalled the simulation until
    the default mission ran out of its time. The shots are scored when the run ends."""
    # config/rviz/usv.rviz path colour, the mission's target marker, the guidance's box outlines (red when the
    # box cuts the path, olive when it does not)
    COLOURS = {"planned_path": [(25, 255, 0)], "target": [(255, 0, 255)], "safety_box": [(255, 0, 0), (128, 128, 0)]}
    MIN_PIXELS = 30
    INTERVAL_S = 2.0  # wall seconds between the end of one shot and the start of the next
    KEEP = 30         # newest shots kept for scoring

    def __init__(self, master, out):
        from offshore_gnc.testing.screenshot import RvizScreen
        self.out, self.last_t, self.proc, self.shots, self.taken = out, 0.0, None, [], 0
        self.dir = os.path.join(out, "rviz_shots")
        os.makedirs(self.dir, exist_ok=True)
        master.wait_for_param("/use_sim_time", 60.0)  # rviz reads it once: without it, it shows wall time
        self.screen = RvizScreen(master, os.path.join(REPO, "config", "rviz", "usv.rviz")).__enter__()

    def _reap(self, wait=False):
        """The running shot, if it has ended: kept when its PNG was written."""
        if self.proc is None:
            return True
        try:
            rc = self.proc.wait(timeout=30) if wait else self.proc.poll()
        except subprocess.TimeoutExpired:
            self.proc.kill()
            rc = self.proc.wait()
        if rc is None:
            return False
        if rc == 0 and os.path.exists(self.pending):
            self.shots.append(self.pending)
            for old in self.shots[:-self.KEEP]:
                os.remove(old)
            self.shots = self.shots[-self.KEEP:]
        else:
            print("[mission] screenshot failed (import exit %s)" % rc, flush=True)
        self.proc, self.last_t = None, time.time()
        return True

    def maybe_shoot(self, usv_phase, force=False):
        if (usv_phase not in ("TRANSIT", "ARRIVED") and not force) or not self._reap():
            return
        if time.time() - self.last_t < self.INTERVAL_S and not force:
            return
        self.taken += 1
        self.pending = os.path.join(self.dir, "shot_%04d.png" % self.taken)
        try:
            self.proc = self.screen.shot_async(self.pending)
        except (RuntimeError, OSError) as e:
            print("[mission] screenshot failed: %s" % e, flush=True)
            self.last_t = time.time()

    def close(self, usv_phase=None):
        """Scores the shots from the newest back and keeps the newest with every colour drawn (else the one with
        the most of them) as rviz_usv.png; a run quicker than the shot interval gets one shot here, at its end."""
        from offshore_gnc.testing.screenshot import count_colour
        self._reap(wait=True)
        for _ in range(3):  # none kept (every shot failed, or the run ended in another phase): at the end, in any phase
            if self.shots:
                break
            self.maybe_shoot(usv_phase, force=True)
            self._reap(wait=True)
        best, best_score = None, -1
        for path in reversed(self.shots):
            px = {k: sum(count_colour(path, rgb) for rgb in rgbs) for k, rgbs in self.COLOURS.items()}
            score = sum(min(v, 500) for v in px.values())
            if min(px.values()) >= self.MIN_PIXELS:
                best = (path, px)
                break
            if score > best_score:
                best, best_score = (path, px), score
        self.screen.__exit__(None, None, None)
        if best:
            os.replace(best[0], os.path.join(self.out, "rviz_usv.png"))
        shutil.rmtree(self.dir, ignore_errors=True)
        return best[1] if best else None


def phantom_target(sim_t):
    """The geofence fault: a /target line for the AUV's monitor to publish on the AUV master, stamped at sim_t,
    as the AUV mission publishes a detection (map_ned, from the sonar) but outside the USV's operating region.
    No geodetic position (NaN): the USV mission takes the local one."""
    n, e, d = PHANTOM_TARGET_NED
    secs = int(sim_t)
    point = {"x": n, "y": e, "z": d}
    return json.dumps({"echo": "/target", "type": "offshore_gnc/Target", "msg": {
        "header": {"stamp": {"secs": secs, "nsecs": int(round((sim_t - secs) * 1e9)) % 1000000000},
                   "frame_id": "map_ned"},
        "source": 2, "origin": point, "centroid": point, "nearest": point, "confidence": 1.0,
        "latitude": float("nan"), "longitude": float("nan"), "depth": d}})


def fmt_progress(u, a):
    def one(s):
        d = s.get("distance_to_go")
        dist = " %.1f m to go" % d if isinstance(d, (int, float)) and d == d and d >= 0 else ""
        return "%s%s" % (s.get("phase", "?"), dist)
    return "[sim %7.1f s] AUV %-14s | USV %s" % (max(u.get("sim_time", 0), a.get("sim_time", 0)), one(a), one(u))


def after_death(died, launches, status, watch_s):
    """The outcome once a stack has died, or None while the survivor is still being watched."""
    gone = ", ".join("the %s stack died at sim %.1f s (exit %s)" % (v, t, launches[v].returncode)
                     for v, t in sorted(died.items()))
    survivors = [v for v in VEHICLES if v not in died]
    if not survivors:
        return {"reason": gone, "died": died}
    s = status[survivors[0]]
    if not s.get("finished") and s.get("sim_time", 0.0) - min(died.values()) < watch_s:
        return None
    return {"died": died,
            "reason": "%s; the %s went on: phase %s (%s)" % (gone, survivors[0].upper(), s.get("phase"),
                                                             s.get("detail", ""))}


def run(a):
    sc = scenario_check.load(a.scenario)  # refuses a bad scenario before anything starts
    judged = scenario_check.mission(a.scenario)  # how the run is judged (the scenario's mission section)
    max_sim = a.max_sim_time or judged["max_sim_time"]
    name = sc.get("name", os.path.splitext(os.path.basename(a.scenario))[0])
    out = os.path.abspath(a.out or os.path.join(REPO, "reports", "%s-%s" % (
        name, datetime.datetime.now().strftime("%Y%m%d-%H%M%S"))))
    os.makedirs(out, exist_ok=True)
    configs = vehicle_configs(a.auv_model)
    fault_plan = " ".join(a.fault)
    planned = scenario_check.faults(a.scenario, fault_plan)  # refused before start when it does not parse
    try:
        radio_params = radio_link.load_params(a.radio)  # refused before start when it does not validate
    except ValueError as e:
        raise scenario_check.ScenarioError(str(e))
    t0 = time.time()
    outcome = {"reason": "not started"}
    with MasterSet(VEHICLES, log_dir=os.path.join(out, "logs")) as ms:
        lockstep = not a.free_running
        common = {"sim": "true", "scenario": os.path.abspath(a.scenario), "rate": str(a.rate), "record": "true",
                  "lockstep": str(lockstep).lower(), "faults": fault_plan, "seed": str(a.seed)}
        # the radio between the relays, always in their path; the link fault takes it down
        link_faults = [f for f in planned if f["name"] == "link"]
        relay, usv_relay_port, auv_relay_port = relay_configs(os.path.join(out, "logs"), a.rate)  # missions never meet
        radio = radio_link.Radio(usv_relay_port, auv_relay_port, radio_params, a.rate, seed=a.seed)
        launches = {
            "usv": ms["usv"].roslaunch(os.path.join(REPO, "launch", "usv.launch"), dict(
                common, bag=os.path.join(out, "usv.bag"), rviz=str(a.rviz).lower(), relay_config=relay["usv"],
                config=configs["usv"],
                usv_params=os.path.abspath(a.usv_params) if a.usv_params else "")),
            "auv": ms["auv"].roslaunch(os.path.join(REPO, "launch", "auv.launch"), dict(
                common, bag=os.path.join(out, "auv.bag"), vehicle_model=a.auv_model, relay_config=relay["auv"],
                config=configs["auv"], navigation=a.auv_navigation,
                usbl_port=os.path.join(out, "logs", "seatrac"))),  # missions side by side: one line each
        }
        # The simulators' clocks wait for the stacks: at --rate 20 a stack whose nodelets took a second of wall time
        # to load was 20 s late, the USV drifting in the current meanwhile (its wait drift: 2.5 m of 2.5 m).
        for v, topics in STACK_TOPICS.items():
            missing = [t for t in topics if not ms[v].wait_for_topic(t, timeout=STACK_READY_S)]
            if missing:
                print("[mission] the %s stack has not advertised %s after %.0f s; starting anyway" % (
                    v, ", ".join(missing), STACK_READY_S), flush=True)
        clock_t0 = time.time()
        usbl = a.auv_navigation == "usbl"
        # the phantom target of a geofence fault goes out on the AUV master, where the relay picks it up
        geofence = [f for f in planned if f["name"] == "geofence"]
        mons = {"usv": Monitor(ms["usv"], "usv", lockstep, echo=AcousticChannel.TOPICS if usbl else ()),
                "auv": Monitor(ms["auv"], "auv", lockstep, publish=(AcousticChannel.TOPICS if usbl else ()) +
                               (("/target:offshore_gnc/Target",) if geofence else ()))}
        channel = AcousticChannel(mons["usv"], mons["auv"]) if usbl else None
        clock = SharedClock(mons) if lockstep else None
        shots = Screenshots(ms["usv"], out) if a.screenshot else None
        print("[mission] scenario %s, report folder %s" % (a.scenario, out), flush=True)
        for f in planned:
            print("[mission] fault injection: %s on the %s from sim %g s %s" % (
                f["name"], f["vehicle"], f["start_s"], "to the end" if f["end_s"] is None else "to %g s" % f["end_s"]),
                flush=True)
        last_print = 0.0
        died = {}  # vehicle -> simulated time when its stack was found dead
        found_t = None  # when the AUV's status first said TARGET_FOUND (--kill V@found+S)
        while True:
            select.select([m.proc.stdout for m in mons.values()], [], [], 0.05)
            u, av = mons["usv"].poll(), mons["auv"].poll()
            if channel:
                channel.pump()
            if clock:
                clock.tick([v for v in mons if v not in died])
            sim_t = max(u.get("sim_time", 0.0), av.get("sim_time", 0.0))
            if link_faults:
                for f in link_faults:
                    if f["start_s"] <= sim_t < (f["end_s"] if f["end_s"] is not None else float("inf")):
                        if f.get("injected_s") is None:
                            f["injected_s"] = round(sim_t, 2)
                            print("[mission] fault injection: the radio link is down at sim %.1f s" % sim_t, flush=True)
                        radio.down()
                    elif f.get("injected_s") is not None and f.get("ended_s") is None:
                        f["ended_s"] = round(sim_t, 2)
                        radio.up()
                        print("[mission] the radio link is up again at sim %.1f s" % sim_t, flush=True)
            for f in geofence:  # once; a full pipe to the monitor: the next round
                if f.get("injected_s") is None and sim_t >= f["start_s"] and mons["auv"].send(phantom_target(sim_t)):
                    f["injected_s"], f["target_ned"] = round(sim_t, 2), list(PHANTOM_TARGET_NED)
                    print("[mission] fault injection: a target %.0f m north of the origin published on the AUV's "
                          "/target at sim %.1f s" % (PHANTOM_TARGET_NED[0], sim_t), flush=True)
            if found_t is None and av.get("phase") == "TARGET_FOUND":
                found_t = sim_t
            kill_at = a.kill and (a.kill[1] if a.kill[1] is not None else
                                  (found_t + a.kill[2] if found_t is not None else None))
            if kill_at is not None and a.kill[0] not in died and sim_t >= kill_at:
                print("[mission] fault injection: killing the %s stack at sim %.1f s" % (a.kill[0], sim_t), flush=True)
                kill_tree(launches[a.kill[0]].pid)
                launches[a.kill[0]].wait()
            for v, p in launches.items():
                if v not in died and p.poll() is not None:
                    died[v] = sim_t
                    print("[mission] the %s stack died at sim %.1f s (exit %s)" % (v, sim_t, p.returncode), flush=True)
            if shots:
                shots.maybe_shoot(u.get("phase"))
            if not a.quiet and time.time() - last_print >= 2.0:
                print(fmt_progress(u, av), flush=True)
                last_print = time.time()
            if died:
                outcome = after_death(died, launches, {"usv": u, "auv": av}, a.after_kill)
                if outcome:
                    break
                continue
            # the end: the USV reports the AUV recovered (with or without a target: the scenario's expectation and
            # the report judge the rest)
            if u.get("phase") == "RECOVERED" and u.get("finished"):
                outcome = {"recovered": True, "reason": "the AUV is recovered: " + u.get("detail", "")}
                break
            if sim_t > max_sim:
                outcome = {"reason": "simulated time limit %.0f s reached (AUV %s: %s; USV %s: %s)" % (
                    max_sim, av.get("phase"), av.get("detail", ""), u.get("phase"), u.get("detail", ""))}
                break
            if time.time() - clock_t0 > 30 and sim_t == 0.0:
                outcome = {"reason": "no simulated time after 30 s: simulators not running"}
                break
        if shots:
            outcome["rviz_pixels"] = shots.close(u.get("phase"))
        outcome["sim_time_s"] = round(sim_t, 1)
        outcome["auv_model"] = a.auv_model  # its length, for the hull's clearance to it
        outcome["run_wall_s"] = round(time.time() - clock_t0, 2)  # the simulated run alone, start-up excluded
        print(fmt_progress(u, av), flush=True)
        if channel:
            print("[mission] acoustic channel (USV truth to the AUV master): " + channel.summary(), flush=True)
        if clock:
            print("[mission] shared clock: times let go before a stack's navigation and controller got there "
                  "(status_monitor.Pace): " + ", ".join("%s %s" % (v, mons[v].last.get("pace_waits", "?")) for v in mons),
                  flush=True)
        print("[mission] simulated radio: " + radio.summary(), flush=True)
        outcome["radio"] = radio.stats()
        radio.close()
        # MasterSet's exit stops roslaunch with SIGINT: rosbag closes its bags cleanly.
    wall = time.time() - t0
    for v in VEHICLES:  # a killed rosbag leaves an unindexed .active file: recover it, lose no data
        bag = os.path.join(out, v + ".bag")
        if not os.path.exists(bag) and os.path.exists(bag + ".active"):
            fixed = os.path.join(out, "reindexed")
            os.makedirs(fixed, exist_ok=True)
            r = subprocess.run(["rosbag", "reindex", "-q", "--output-dir", fixed, bag + ".active"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            if r.returncode == 0 and os.path.exists(os.path.join(fixed, v + ".bag.active")):
                shutil.move(os.path.join(fixed, v + ".bag.active"), bag)
                os.remove(bag + ".active")
            else:
                print("[mission] could not reindex %s.active: %s" % (bag, r.stderr.strip()[-300:]), flush=True)
            shutil.rmtree(fixed, ignore_errors=True)
    m = report.build(os.path.join(out, "usv.bag"), os.path.join(out, "auv.bag"), a.scenario, out,
                     wall_time_s=round(wall, 2), outcome=outcome, planned_faults=planned)
    print("[mission] %s: %s" % ("SUCCESS" if m["success"] else "FAILED (%s)" % m["outcome"], outcome["reason"]))
    print("[mission] metrics: " + ", ".join("%s=%s" % (k, m[k]) for k in (
        "outcome", "usv_xte_est_rmse_m", "auv_xte_true_rmse_m", "target_error_m", "min_clearance_m", "auv_nav_source",
        "auv_nav_rmse_m", "usbl_fixes_received", "usbl_fixes_rejected", "usbl_rejected_outliers", "usbl_outliers",
        "auv_hold_excursion_m", "auv_ascent_drift_m", "recovery_distance_m", "usv_auv_min_clearance_m",
        "find_to_recovery_s", "sim_time_s", "wall_time_s")))
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
