#!/usr/bin/python3
"""Mission report from the two vehicles' rosbags and the scenario: map plot, cross-track plots, metrics.

    python3 report.py --usv-bag usv.bag --auv-bag auv.bag --scenario config/scenarios/pyhajarvi.yaml --out DIR

Writes DIR/metrics.json, DIR/summary.md, DIR/map.png, DIR/cross_track.png, DIR/navigation.png. Positions are
plotted in the local NED frame (north up, east right), metres. Cross-track indicators follow thesis Tables 4.4 and
5.1 (RMSE, SD, MAE of the LOS cross-track error while following a path). The AUV's navigation: the horizontal
error of its estimate /auv/odom against its ground truth, and the USBL fixes it received (/auv/usbl/fix): those
the positioning's quality gates rejected and those the navigation filter refused (/auv/navigation/refused_fixes),
each scored against the simulator's truth, so the report says how many of the rejected fixes were outliers.
"""
import argparse
import bisect
import json
import math
import os
import subprocess

import yaml

from offshore_gnc import tools

THESIS = {  # field-test figures for comparison (thesis Table 5.1 USV; Table 4.4 Girona500 AUV)
    "usv_xte_est_rmse_m": 1.5482, "usv_xte_est_sd_m": 0.7764, "usv_xte_est_mae_m": 1.3397, "auv_xte_true_rmse_m": 0.23,
}

MODE_FOLLOW_PATH = 1  # GuidanceStatus.MODE_FOLLOW_PATH (for the plots; the metrics tool filters the same)
REFERENCE_FOLLOW = 1  # GuidanceStatus.REFERENCE_FOLLOW
QUALITY_OK = 0  # UsblFix.QUALITY_OK: the only fixes navigation may use
QUALITY_NAMES = {1: "filter_error", 2: "fit_error", 3: "stale", 4: "depth", 5: "no_position"}  # UsblFix.QUALITY_*
# A USBL fix farther than this from the AUV's true position at its stamp is an outlier: three times the 1 m sigma
# the navigation gives a fix (fix_min_sigma; range * fix_angle_sigma stays below it within 100 m).
OUTLIER_M = 3.0
OUTLIER_GATES = ("filter_error", "fit_error", "depth", "gated")  # rejections for the fix's own quality
REFERENCE_HOLD = 2  # GuidanceStatus.REFERENCE_HOLD
ACTION_HOLD = 2  # SafetyState.ACTION_HOLD


def tracking_metrics(path, selector=None):
    """Cross-track RMSE, SD and MAE (thesis Tables 4.4, 5.1) of a bag's GuidanceStatus topic in path-following
    mode, or of a CSV column, from the C++ tool `tracking_metrics` (the one implementation; the tracking bench
    uses the same code). NaN figures and n = 0 when there is nothing to measure."""
    cmd = [tools.path("tracking_metrics"), path] + ([selector] if selector else [])
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) if os.path.exists(path) else None
    if r is None or r.returncode != 0:
        return {"rmse": float("nan"), "sd": float("nan"), "mae": float("nan"), "n": 0}
    d = json.loads(r.stdout.strip().splitlines()[-1])
    return {"rmse": d["rmse_m"], "sd": d["sd_m"], "mae": d["mae_m"], "n": d["samples"]}


def split_tracking(status_msgs, truth=None):
    """Cross-track figures of a vehicle's GuidanceStatus samples: all of them, and split at the first waypoint
    reached: the approach (leg 1, from wherever the vehicle was to the path's first switch; thesis Table 4.4 leaves
    it out) and the tracking after it (legs 2 on). Each on the guidance's own error (on its navigation estimate) and,
    given the true track [(t, north, east, ...)], on the truth: the true position's distance from the leg followed,
    the line through the sample's reference point (the estimate's projection on the leg) along its path angle. Not
    the published path's waypoints k-1 and k: LOS merges waypoints closer than min_leg_length, so active_leg need not
    count them. All through the same C++ tool as the bag figures, fed CSV files."""
    import tempfile
    truth_xte = []
    for t, m in status_msgs:
        p = _interpolate(truth or [], t)
        if p is None or m.reference_mode != REFERENCE_FOLLOW:
            truth_xte.append(float("nan"))
            continue
        q, chi = m.reference_point, m.path_angle
        truth_xte.append(-(p[0] - q.x) * math.sin(chi) + (p[1] - q.y) * math.cos(chi))
    out = {}
    with tempfile.TemporaryDirectory() as d:
        for name, keep in (("all", lambda m: True), ("approach", lambda m: m.active_leg < 2),
                           ("tracking", lambda m: m.active_leg >= 2)):
            csv = os.path.join(d, name + ".csv")
            with open(csv, "w") as f:
                f.write("mode,cross_track_error,cross_track_error_truth\n")
                for (_, m), xt in zip(status_msgs, truth_xte):
                    if keep(m):
                        f.write("%d,%r,%r\n" % (m.mode, m.cross_track_error, xt))
            out[name] = tracking_metrics(csv)
            out[name + "_truth"] = tracking_metrics(csv, "cross_track_error_truth")
    return out


def _interpolate(track, t):
    """(north, east) of a track [(t, north, east, ...)] at time t (linear), None outside its span."""
    import bisect
    times = [p[0] for p in track]
    if not times or t < times[0] or t > times[-1]:
        return None
    i = bisect.bisect_left(times, t)
    if times[i] == t:
        return track[i][1], track[i][2]
    (t0, n0, e0, *_), (t1, n1, e1, *_) = track[i - 1], track[i]
    w = (t - t0) / (t1 - t0)
    return n0 + w * (n1 - n0), e0 + w * (e1 - e0)


def read_bag(path, topics):
    """{topic: [(t, msg), ...]} for the topics present in a bag (missing bag -> empty)."""
    out = {t: [] for t in topics}
    if not path or not os.path.exists(path):
        return out
    import rosbag
    with rosbag.Bag(path) as bag:
        for topic, msg, t in bag.read_messages(topics=topics):
            out[topic].append((t.to_sec(), msg))
    return out


def odom_track_ned(msgs):
    """nav_msgs/Odometry in map (ENU) -> [(t, north, east, down)]."""
    return [(t, m.pose.pose.position.y, m.pose.pose.position.x, -m.pose.pose.position.z) for t, m in msgs]


def _stamp(t, m):
    """A message's header stamp [s], or its bag time when the stamp is unset."""
    s = m.header.stamp.to_sec()
    return s if s > 0.0 else t


def nav_error(estimate, truth):
    """Horizontal errors [(t, m)] of an estimate track against the truth interpolated linearly in time at each
    estimate's time; estimates outside the truth's time span are skipped. Both as [(t, north, east, ...)]."""
    truth = sorted(truth)
    errors = []
    for t, n, e, *_ in estimate:
        p = _interpolate(truth, t)
        if p is not None:
            errors.append((t, math.hypot(n - p[0], e - p[1])))
    return errors


def _interpolate3(track, t):
    """(north, east, down) of a track [(t, north, east, down)] at time t (linear), None outside its span."""
    times = [p[0] for p in track]
    if not times or t < times[0] or t > times[-1]:
        return None
    i = bisect.bisect_left(times, t)
    if times[i] == t:
        return track[i][1:4]
    a, b = track[i - 1], track[i]
    w = (t - a[0]) / (b[0] - a[0])
    return tuple(a[k] + w * (b[k] - a[k]) for k in (1, 2, 3))


def usbl_verdicts(fixes, refused, truth):
    """Every USBL fix scored against the truth: [(stamp, verdict, error_m or None)], verdict "fused", "gated" (the
    navigation filter refused it) or the positioning's rejection (fit_error, depth, stale, ...); and the summary
    {rejected, rejected_by, outliers, rejected_outliers, accepted_outliers, gates, gates_outliers} (an outlier:
    farther than OUTLIER_M from the truth; gates: the rejections for a fix's own quality, the ones meant to catch
    outliers, as against stale fixes, which lacked the USV's pose in time)."""
    refused_keys = {(m.header.stamp.to_nsec(), m.range) for m in refused}
    truth = sorted(truth)
    scored = []
    for m in fixes:
        stamp = m.header.stamp.to_sec()
        p, q = (m.position_ned.x, m.position_ned.y, m.position_ned.z), _interpolate3(truth, stamp)
        err = math.dist(p, q) if q is not None and all(math.isfinite(v) for v in p) else None
        if m.quality != QUALITY_OK:
            verdict = QUALITY_NAMES.get(m.quality, "quality_%d" % m.quality)
        else:
            verdict = "gated" if (m.header.stamp.to_nsec(), m.range) in refused_keys else "fused"
        scored.append((stamp, verdict, err))
    rejected = [(v, e) for _, v, e in scored if v != "fused"]
    gates = [(v, e) for v, e in rejected if v in OUTLIER_GATES]
    by = {}
    for v, _ in rejected:
        by[v] = by.get(v, 0) + 1
    return scored, {
        "rejected": len(rejected), "rejected_by": by,
        "outliers": sum(1 for _, _, e in scored if e is not None and e > OUTLIER_M),
        "rejected_outliers": sum(1 for _, e in rejected if e is not None and e > OUTLIER_M),
        "accepted_outliers": sum(1 for _, v, e in scored if v == "fused" and e is not None and e > OUTLIER_M),
        "gates": len(gates), "gates_outliers": sum(1 for _, e in gates if e is not None and e > OUTLIER_M),
        "gates_unplaced": sum(1 for _, e in gates if e is None)}


def sim_counter(diagnostics, status, key):
    """A counter of a simulator's diagnostics (the last status whose name ends with `status`), None without one."""
    value = None
    for _, m in diagnostics:
        for st in m.status:
            if st.name.endswith(status):
                value = next((int(kv.value) for kv in st.values if kv.key == key), value)
    return value


def path_ned(path_msg):
    """nav_msgs/Path -> [(north, east)], whatever its frame (map_ned or map)."""
    ned = path_msg.header.frame_id.endswith("ned")
    pts = []
    for p in path_msg.poses:
        x, y = p.pose.position.x, p.pose.position.y
        pts.append((x, y) if ned else (y, x))
    return pts


def judge(scenario, usv_odom, facts, auv_track=(), auv_model="girona500"):
    """The run's outcome and the USV hull's clearances, by the ROS-free mission's own code (the C++ tool
    `mission_outcome`: the hull of config/usv.yaml, turning with the boat, against the scenario's true shapes and the
    AUV near the surface; the classes of closed_loop/outcome.h). usv_odom: the USV's ground truth [(t, Odometry)];
    auv_track: the AUV's [(t, north, east, down)]; facts: held, recovered, auv_no_target, target_error (NaN: none
    reported), died, safety_stop. Returns (outcome, min_clearance_m, usv_auv_min_clearance_m, recovery_distance_m),
    NaN for what could not be measured."""
    import tempfile
    files = []
    try:
        with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
            files.append(f.name)
            f.write("t,north,east,yaw\n")
            for t, m in usv_odom:
                q = m.pose.pose.orientation
                yaw_enu = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
                f.write("%.3f,%.4f,%.4f,%.5f\n" % (t, m.pose.pose.position.y, m.pose.pose.position.x,
                                                   math.pi / 2 - yaw_enu))
        args = [tools.path("mission_outcome"), "--scenario", scenario, "--usv-track", files[0]]
        if auv_track:
            with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
                files.append(f.name)
                f.write("t,north,east,down\n")
                for t, n, e, d in sorted(auv_track):
                    f.write("%.3f,%.4f,%.4f,%.4f\n" % (t, n, e, d))
            args += ["--auv-track", files[1], "--auv-model", auv_model]
        for k, v in facts.items():
            args += ["--" + k.replace("_", "-"), "nan" if isinstance(v, float) and v != v else str(int(v) if isinstance(v, bool) else v)]
        r = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    finally:
        for name in files:
            os.remove(name)
    if r.returncode != 0:
        raise RuntimeError("mission_outcome failed: " + r.stderr.strip())
    d = json.loads(r.stdout.strip().splitlines()[-1])
    nan = float("nan")
    return (d["outcome"], nan if d["min_clearance_m"] is None else d["min_clearance_m"],
            nan if d["usv_auv_min_clearance_m"] is None else d["usv_auv_min_clearance_m"],
            nan if d["recovery_distance_m"] is None else d["recovery_distance_m"])


RISEN_M = 0.3  # the ascent's drift counts once the AUV rose this much (closed_loop/mission.cpp kRisen)
STATION_M = 1.0  # guidance's hold point is the station the USV's status names (config/mission/usv.yaml station_radius)
SEARCHING = ("IDLE", "COVERAGE")


def _phase_at(status, t):
    """The latest status at time t (status sorted by time), None before the first."""
    i = bisect.bisect_right([x for x, _ in status], t)
    return status[i - 1][1] if i else None


def recovery_figures(auv_track, auv_status, usv_status):
    """docs/mission.md, "Recovery" (the ROS-free mission computes the same): the AUV's largest 3-D distance from its
    hold point from on station there until the ascent (auv_hold_excursion_m), its largest horizontal distance from the
    surfacing point during the ascent once it rose RISEN_M (auv_ascent_drift_m), its largest horizontal distance from
    the point it holds at the surface while there (auv_surface_excursion_m), and when the search ended, the ascent
    began, the AUV surfaced and the USV reported RECOVERED (absolute simulated times, NaN: never), each read from the
    mission statuses [(t, MissionStatus)] at their stamps; auv_track [(t, north, east, down)]."""
    nan = float("nan")
    a = [(_stamp(t, m), m) for t, m in auv_status]
    u = [(_stamp(t, m), m) for t, m in usv_status]
    first = lambda status, phases: next((t for t, m in status if m.phase in phases), nan)  # noqa: E731
    fig = {"found_at_s": first(a, ("TARGET_FOUND", "NO_TARGET")), "ascent_at_s": first(a, ("ASCENT",)),
           "surfaced_at_s": first(a, ("SURFACED", "RECOVERED")), "recovered_at_s": first(u, ("RECOVERED",))}
    fig["find_to_recovery_s"] = fig["recovered_at_s"] - fig["found_at_s"]
    hold, drift, surface, start_depth = [], [], [], None
    for t, n, e, d in auv_track:
        m = _phase_at(a, t)
        if m is None:
            continue
        p = m.hold_point
        if m.phase == "TARGET_FOUND" and m.on_station_since == m.on_station_since and t >= m.on_station_since:
            hold.append(math.sqrt((n - p.x) ** 2 + (e - p.y) ** 2 + (d - p.z) ** 2))
        if m.phase == "ASCENT":
            start_depth = d if start_depth is None else start_depth
            if d < start_depth - RISEN_M:
                drift.append(math.hypot(n - p.x, e - p.y))
        if m.phase in ("SURFACED", "RECOVERED"):
            surface.append(math.hypot(n - p.x, e - p.y))
    fig["auv_hold_excursion_m"] = max(hold) if hold else nan
    fig["auv_ascent_drift_m"] = max(drift) if drift else nan
    fig["auv_surface_excursion_m"] = max(surface) if surface else nan
    return fig


def _drift_after(track, t0):
    """Largest horizontal distance of a track from where it was at time t0 [m] (NaN without data after t0)."""
    after = [p for p in track if p[0] >= t0]
    if not after:
        return float("nan")
    return max(math.hypot(n - after[0][1], e - after[0][2]) for _, n, e, _ in after)


NAV_RECOVERED_M = 1.5  # issue 16: the navigation error after a USBL outage is back under this
# a vehicle holding position: its true speed over ground is under this (the USV's dynamic positioning moves it
# about its point at 0.35-0.5 m/s in the current)
HOLD_SPEED_MPS = 0.5
SURFACED_M = 0.5       # an AUV at the surface: its true depth is under this
REFUSED = "refused a target"  # the USV mission's status once it refused a target (mission::UsvMission)


class SafeStates:
    """When a vehicle was in an action's safe state after some time, from the bags: a warning (and a refused
    target: the USV goes on with what it was doing) at once; neutral at its first neutral actuator command; hold
    once its true speed over ground is under HOLD_SPEED_MPS; surface (and abort, which surfaces) once its true depth
    is under SURFACED_M (the USV: neutral). neutral: {vehicle: [(t, bool)]}; speed, depth: {vehicle: [(t, value)]}."""

    def __init__(self, neutral, speed, depth):
        self.neutral, self.speed, self.depth = neutral, speed, depth

    def reached(self, vehicle, action, t0):
        if t0 is None:
            return None
        if action in ("warn", "refuse"):
            return t0
        if action in ("surface", "abort") and vehicle != "usv":
            series, ok = self.depth.get(vehicle, []), lambda d: d < SURFACED_M
        elif action == "hold":
            series, ok = self.speed.get(vehicle, []), lambda v: v < HOLD_SPEED_MPS
        else:
            series, ok = self.neutral.get(vehicle, []), bool
        return next((round(t, 2) for t, x in series if t >= t0 - 1e-6 and ok(x)), None)


SAFE_STATE_WORDS = {"warn": "a warning only", "refuse": "the target refused, the USV going on with what it was doing",
                    "neutral": "neutral actuators", "hold": "holding (under %.1f m/s)" % HOLD_SPEED_MPS,
                    "surface": "at the surface (under %.1f m)" % SURFACED_M, "abort": "aborted at the surface"}


def _sentence(r):
    """The fault entry in one sentence (summary.md)."""
    def _s(v):
        return "n/a" if v is None else "%.1f" % v
    head = "`%s` (%s) injected at %s s" % (r["name"], r["vehicle"].upper(), _s(r["injected_at_s"]))
    if r["ended_at_s"] is not None:
        head += ", ended at %s s" % _s(r["ended_at_s"])
    if r["injected_at_s"] is None:
        return head + ": never took effect in the run."
    if r["detected_at_s"] is None:
        what = "no rule answered it" if not r["rule"] else "%s never became active" % r["rule"]
        return head + ": %s%s." % (what, "; other rules: " + ", ".join(
            "%s -> %s" % (x["rule"], x["action"]) for x in r["responses"]) if r["responses"] else "")
    out = head + ": %s -> %s after %.2f s (%s)" % (
        r["rule"] or "the USV mission", r["action"], r["detected_at_s"] - r["injected_at_s"], r["reason"])
    state = SAFE_STATE_WORDS.get(r["action"], r["action"])
    out += "; %s from %s s" % (state, _s(r["safe_state_at_s"])) if r["safe_state_at_s"] is not None else \
        "; %s never reached in the run" % state
    if r["action"] == "refuse":
        out += "; nothing to recover"
    elif r["recovered_at_s"] is not None:
        out += "; released at %s s" % _s(r["recovered_at_s"])
    else:
        out += "; not released in the run"
    return out + "."


def fault_reports(planned, events, transitions, nav_err=(), nav_sigma=(), nav_status=(), safe=None, usv_status=(),
                  usv_targets=()):
    """One entry per planned fault (mission_job --fault) with the issue's keys: name, injected_at_s (when the
    simulator announced it on /<v>/sim/faults, or the job noted it), detected_at_s and action (when the fault's own
    rule, FaultKind::rule, became active and what it commands; for `geofence` when the USV mission refused the
    target, action "refuse"), safe_state_at_s (SafeStates), recovered_at_s (the rule's release), plus ended_at_s,
    every rule the supervisor activated on that vehicle from its start to 10 s after its end (rule, action, delay,
    release, reason) and a one-sentence summary; for `geofence` also when its target reached the USV master
    (arrived_at_s, the bag's time: the relay's latency). For a USBL outage also the navigation: largest error and position
    sigma while it lasted, the filter's statuses, and how long after it the error stayed under NAV_RECOVERED_M.
    events/transitions: {vehicle: [(t, msg)]}; nav_err, nav_sigma: [(t, m)]; nav_status: [(t, str)];
    usv_status: [(t, MissionStatus)]; usv_targets: [(t, Target)] on the USV master."""
    safe = safe or SafeStates({}, {}, {})
    reports = []
    for f in planned:
        v, start = f["vehicle"], f["start_s"]
        end = f["end_s"] if f["end_s"] is not None else float("inf")
        if v == "both":  # injected by the job itself (the radio, the phantom target), which noted when
            on, off, watched = f.get("injected_s"), f.get("ended_s"), ("usv", "auv")
        else:
            ev = events.get(v, [])
            on = next((_stamp(t, m) for t, m in ev if m.name == f["name"] and m.active and _stamp(t, m) >= start - 0.5),
                      None)
            off = next((_stamp(t, m) for t, m in ev if m.name == f["name"] and not m.active and on is not None
                        and _stamp(t, m) > on), None)
            watched = (v,)
        responses = []
        for w in watched:
            tr = transitions.get(w, [])
            for t, m in tr:
                ts = _stamp(t, m)
                if on is None or ts < on or ts > end + 10.0 or m.active_rule not in m.active_rules:
                    continue
                release = next((_stamp(t2, m2) for t2, m2 in tr if _stamp(t2, m2) > ts and
                                m2.active_rule == m.active_rule and m.active_rule not in m2.active_rules), None)
                responses.append({"vehicle": w, "rule": m.active_rule, "action": m.action_name,
                                  "after_s": round(ts - on, 2),
                                  "released_s": round(release, 2) if release is not None else None,
                                  "reason": m.reason})
        rule = f.get("rule") or None
        first = next((x for x in responses if x["rule"] == rule), None) if rule else None
        arrived = None
        if f["name"] == "geofence" and on is not None:  # the USV mission's region check answers it
            p = f.get("target_ned") or (float("nan"),) * 2
            # matched by the phantom's own stamp (its injection time), not by the bag's time: under load the USV
            # master's clock can trail the job's round by more than the relay's latency
            arrived = next((t for t, m in usv_targets if _stamp(t, m) >= on - 1e-6 and
                            math.hypot(m.origin.x - p[0], m.origin.y - p[1]) < 1.0), None)
            refusal = next(((_stamp(t, m), m.detail) for t, m in usv_status
                            if _stamp(t, m) >= on - 1e-6 and REFUSED in m.detail), None)
            if refusal:
                first = {"vehicle": "usv", "rule": None, "action": "refuse", "after_s": round(refusal[0] - on, 2),
                         "released_s": None, "reason": refusal[1].split(REFUSED + ": ", 1)[-1]}
        detected = round(on + first["after_s"], 2) if first else None
        r = {"name": f["name"], "vehicle": v, "rule": rule,
             "injected_at_s": round(on, 2) if on is not None else None,
             "detected_at_s": detected,
             "action": first["action"] if first else None,
             "safe_state_at_s": safe.reached(first["vehicle"], first["action"], detected) if first else None,
             "recovered_at_s": first["released_s"] if first else None,
             "reason": first["reason"] if first else None,
             "start_s": start, "end_s": f["end_s"],
             "ended_at_s": round(off, 2) if off is not None else None, "responses": responses}
        if f["name"] == "geofence":
            r["arrived_at_s"] = round(arrived, 2) if arrived is not None else None
        if f["name"] == "usbl" and on is not None:
            during = [e for t, e in nav_err if on <= t < end]
            sig = [e for t, e in nav_sigma if on <= t < end]
            sig_before = [e for t, e in nav_sigma if on - 10.0 <= t < on]
            after = [(t, e) for t, e in nav_err if t >= end]
            bad = [t for t, e in after if e >= NAV_RECOVERED_M]
            r.update({
                "nav_error_max_m": round(max(during), 3) if during else None,
                "nav_sigma_before_m": round(max(sig_before), 3) if sig_before else None,
                "nav_sigma_max_m": round(max(sig), 3) if sig else None,
                "nav_statuses": sorted({st for t, st in nav_status if on <= t < end + 5.0}),
                # from the outage's end until the error stays under the bound (0: it never left it)
                "nav_recovered_after_s": (round(max(bad) - end, 2) if bad else 0.0) if after else None,
            })
        r["summary"] = _sentence(r)
        reports.append(r)
    return reports


def _percentile(values, q):
    """Nearest-rank percentile, as closed_loop/mission.cpp (NaN without samples)."""
    v = sorted(values)
    if not v:
        return float("nan")
    return v[min(max(int(math.ceil(q * len(v))), 1), len(v)) - 1]


def _at(track, t):
    """The track sample nearest in time to t (track sorted by time)."""
    i = bisect.bisect_left([p[0] for p in track], t)
    return min(track[max(i - 1, 0):i + 1], key=lambda p: abs(p[0] - t))


def station_keeping(usv_track, mission_status, guidance_status):
    """docs/mission.md: (usv_wait_drift_m, usv_hold_p95_m, usv_recovery_hold_p95_m). The wait: from the first
    STATION_KEEPING status until the first TRANSIT, the largest distance from where it began. The hold: while the USV
    mission reports it on station (on_station_since of its latest status) at the target (ARRIVED), each guidance
    sample that holds a point, the distance of the true position from that point; its 95th percentile. The same
    beside the AUV (RECOVERY, RECOVERED: the run-in, then the recovery point)."""
    wait = [t for t, m in mission_status if m.phase == "STATION_KEEPING"]
    transit = next((t for t, m in mission_status if m.phase == "TRANSIT"), float("inf"))
    drift = float("nan")
    if wait and usv_track and wait[0] < transit:
        during = [p for p in usv_track if wait[0] <= p[0] <= transit]
        if during:
            drift = max(math.hypot(n - during[0][1], e - during[0][2]) for _, n, e, _ in during)
    status = [(_stamp(t, m), m) for t, m in mission_status]
    errors, recovery = [], []
    for t, m in guidance_status if usv_track else ():
        st = _phase_at(status, t)
        if st is None or st.phase not in ("ARRIVED", "RECOVERY", "RECOVERED") or not t >= st.on_station_since:
            continue
        # the point its status says it holds: a new station (the recovery's run-in, then beside the AUV) is
        # guidance's before the next status says so
        if math.hypot(m.reference_point.x - st.hold_point.x, m.reference_point.y - st.hold_point.y) > STATION_M:
            continue
        if m.reference_mode == REFERENCE_HOLD:
            _, n, e, _ = _at(usv_track, t)
            (errors if st.phase == "ARRIVED" else recovery).append(
                math.hypot(n - m.reference_point.x, e - m.reference_point.y))
    return drift, _percentile(errors, 0.95), _percentile(recovery, 0.95)


def build(usv_bag, auv_bag, scenario, out, wall_time_s=float("nan"), outcome=None, planned_faults=()):
    os.makedirs(out, exist_ok=True)
    sc = yaml.safe_load(open(scenario)) if scenario else {}
    u = read_bag(usv_bag, ["/usv/ground_truth/odom", "/usv/guidance/path", "/usv/guidance/planned_path",
                           "/usv/guidance/status",
                           "/usv/guidance/safety_boxes", "/usv/obstacles", "/target", "/usv/mission/status",
                           "/usv/sim/faults", "/usv/safety/transitions", "/usv/joystick_cmd"])
    a = read_bag(auv_bag, ["/auv/ground_truth/odom", "/auv/guidance/path", "/auv/guidance/planned_path",
                           "/auv/guidance/status",
                           "/auv/sonar/targets", "/target", "/auv/mission/status", "/auv/odom", "/auv/usbl/fix",
                           "/auv/navigation/refused_fixes",
                           "/auv/sim/faults", "/auv/safety/transitions", "/auv/navigation/status", "/diagnostics",
                           "/auv/thruster_setpoints", "/auv/rc_channels"])
    usv_track = odom_track_ned(u["/usv/ground_truth/odom"])
    auv_track = odom_track_ned(a["/auv/ground_truth/odom"])
    # the AUV's navigation: its estimate against its truth, each at its header stamp; the fixes it received
    auv_est_track = odom_track_ned(a["/auv/odom"])
    nav_err = nav_error([(_stamp(t, m),) + p[1:] for (t, m), p in zip(a["/auv/odom"], auv_est_track)],
                        [(_stamp(t, m),) + p[1:] for (t, m), p in zip(a["/auv/ground_truth/odom"], auv_track)])
    # horizontal position sigma the estimate reports (the larger of north and east)
    nav_sigma = [(_stamp(t, m), math.sqrt(max(m.pose.covariance[0], m.pose.covariance[7], 0.0))) for t, m in a["/auv/odom"]]
    fixes = [m for _, m in a["/auv/usbl/fix"]]
    fixes_ok = [m for m in fixes if m.quality == QUALITY_OK]
    fix_scores, usbl = usbl_verdicts(fixes, [m for _, m in a["/auv/navigation/refused_fixes"]],
                                     [(_stamp(t, m),) + p[1:] for (t, m), p in zip(a["/auv/ground_truth/odom"], auv_track)])
    # The USV's path following is its transit to the target (Table 5.1's figure); the recovery's short legs round the
    # AUV, entered and cut by its 16 m circle of acceptance, are reported apart. Each guidance sample in the phase of
    # the USV mission's latest status.
    usv_phases = [(_stamp(t, m), m) for t, m in u["/usv/mission/status"]]
    usv_transit, usv_recovery = [], []
    for t, m in u["/usv/guidance/status"]:
        st = _phase_at(usv_phases, t)
        if st is not None and st.phase == "TRANSIT":
            usv_transit.append((t, m))
        elif st is not None and st.phase == "RECOVERY":
            usv_recovery.append((t, m))
    usv_xte = [(t, m.cross_track_error) for t, m in usv_transit if m.mode == MODE_FOLLOW_PATH]
    usv_recovery_xte = [(t, m.cross_track_error) for t, m in usv_recovery if m.mode == MODE_FOLLOW_PATH]
    # The AUV's search (until it reports it over): its tracking and navigation figures; after it the AUV holds, comes
    # up and holds at the surface (the hold paths' lead-ins are no search legs), reported apart.
    auv_end_t = next((t for t, m in a["/auv/mission/status"] if m.phase not in SEARCHING and m.phase), float("inf"))
    auv_searching = [(t, m) for t, m in a["/auv/guidance/status"] if t <= auv_end_t]
    auv_xte = [(t, m.cross_track_error) for t, m in auv_searching if m.mode == MODE_FOLLOW_PATH]
    wait_drift, hold_p95, recovery_hold_p95 = station_keeping(usv_track, u["/usv/mission/status"],
                                                              u["/usv/guidance/status"])
    au_split = split_tracking(auv_searching, auv_track)
    us_split = split_tracking(usv_transit, usv_track)
    us, us_true = us_split["all"], us_split["all_truth"]
    us_recovery = split_tracking(usv_recovery, usv_track)["all_truth"]
    au, au_approach = au_split["tracking_truth"], au_split["approach_truth"]
    nav_during = [e for t, e in nav_err if t <= auv_end_t]
    nav_after = [e for t, e in nav_err if t > auv_end_t]
    # a USBL outage's recovery is judged during the AUV's mission, not in the surface drift after it
    safe = SafeStates(
        {"usv": [(_stamp(t, m), m.surge == 0.0 and m.sway == 0.0 and m.yaw == 0.0) for t, m in u["/usv/joystick_cmd"]],
         "auv": sorted([(_stamp(t, m), not any(m.setpoint)) for t, m in a["/auv/thruster_setpoints"]] +
                       [(_stamp(t, m), all(c == 1500 for c in m.channels[2:6])) for t, m in a["/auv/rc_channels"]])},
        {v: [(_stamp(t, m), math.hypot(m.twist.twist.linear.x, m.twist.twist.linear.y)) for t, m in bag[topic]]
         for v, bag, topic in (("usv", u, "/usv/ground_truth/odom"), ("auv", a, "/auv/ground_truth/odom"))},
        {"auv": [(_stamp(t, m), -m.pose.pose.position.z) for t, m in a["/auv/ground_truth/odom"]]})
    faults = fault_reports(list(planned_faults), {"usv": u["/usv/sim/faults"], "auv": a["/auv/sim/faults"]},
                           {"usv": u["/usv/safety/transitions"], "auv": a["/auv/safety/transitions"]},
                           [(t, e) for t, e in nav_err if t <= auv_end_t], nav_sigma,
                           [(t, m.data) for t, m in a["/auv/navigation/status"]], safe, u["/usv/mission/status"],
                           u["/target"])

    targets_true = sc.get("targets", []) or []
    detected = None
    phantoms = [f["target_ned"] for f in planned_faults if f.get("target_ned")]  # the geofence fault's: no detection
    for t, m in (u["/target"] or a["/target"]):
        if not any(math.hypot(m.origin.x - p[0], m.origin.y - p[1]) < 1.0 for p in phantoms):
            detected = (t, m)
    # The mechanical sonar scans horizontally: it measures where the target is, not how deep (the detection
    # carries the AUV's depth). The localisation error is therefore horizontal; the 3-D figure is reported too.
    target_error = target_error_3d = float("nan")
    if detected and targets_true:
        p = detected[1].origin
        best = min(targets_true, key=lambda tt: math.hypot(p.x - tt["north"], p.y - tt["east"]))
        target_error = math.hypot(p.x - best["north"], p.y - best["east"])
        target_error_3d = math.sqrt(target_error ** 2 + (p.z - best.get("depth", p.z)) ** 2)
    auv_found_t = next((t for t, m in a["/auv/mission/status"] if m.phase == "TARGET_FOUND"), None)
    auv_start_t = a["/auv/mission/status"][0][0] if a["/auv/mission/status"] else None
    last_usv = u["/usv/mission/status"][-1][1] if u["/usv/mission/status"] else None
    last_auv = a["/auv/mission/status"][-1][1] if a["/auv/mission/status"] else None
    all_t = [t for t, *_ in usv_track + auv_track]
    sim_time = (max(all_t) - min(all_t)) if all_t else float("nan")
    if outcome and "sim_time_s" in outcome:  # when the job decided the outcome, not when the bags closed
        sim_time = outcome["sim_time_s"]
    died = (outcome or {}).get("died") or {}
    # held: the USV came to the target (ARRIVED); recovered: it reported RECOVERED (the job's end, or the bag's)
    held = any(m.phase == "ARRIVED" for _, m in u["/usv/mission/status"])
    recovered = bool((outcome or {}).get("recovered")) or any(m.phase == "RECOVERED" for _, m in u["/usv/mission/status"])
    safety_stop = any(m.active_rule in m.active_rules and m.active_rule != "manual" and m.action >= ACTION_HOLD
                      for _, m in u["/usv/safety/transitions"] + a["/auv/safety/transitions"])
    # where the USV really held at the target (its last ARRIVED status: it then leaves for the AUV), else where it
    # ended, against the true target (the stand-off is part of this distance)
    arrived_t = [_stamp(t, m) for t, m in u["/usv/mission/status"] if m.phase == "ARRIVED"]
    usv_at = (_at(usv_track, arrived_t[-1]) if arrived_t else usv_track[-1]) if usv_track else None
    final_distance = (min(math.hypot(usv_at[1] - tt["north"], usv_at[2] - tt["east"]) for tt in targets_true)
                      if usv_at and targets_true else float("nan"))
    verdict, min_clearance, auv_clearance, recovery_distance = judge(scenario, u["/usv/ground_truth/odom"], {
        "held": held, "recovered": recovered,
        "auv_no_target": any(m.phase == "NO_TARGET" for _, m in a["/auv/mission/status"]),
        "target_error": target_error, "final_distance": final_distance, "died": bool(died),
        "safety_stop": safety_stop},
        auv_track, (outcome or {}).get("auv_model", "girona500")) if scenario else (
        "timeout", float("nan"), float("nan"), float("nan"))
    rec = recovery_figures(auv_track, a["/auv/mission/status"], u["/usv/mission/status"])

    metrics = {
        "success": verdict == "success",
        "outcome": verdict,  # closed_loop/outcome.h's class; the sentence in reason
        "reason": (outcome or {}).get("reason", last_usv.detail if last_usv else "no USV status recorded"),
        # cross-track errors while following a path (the USV's transit, the AUV's search): _est on the vehicle's
        # navigation estimate (guidance's own, as the thesis' Table 5.1 was measured on the USV's GPS), _true the true
        # position's distance from the leg
        "usv_xte_est_rmse_m": us["rmse"], "usv_xte_est_sd_m": us["sd"], "usv_xte_est_mae_m": us["mae"],
        "usv_xte_est_samples": us["n"], "usv_xte_true_rmse_m": us_true["rmse"], "usv_xte_true_samples": us_true["n"],
        "usv_recovery_xte_true_rmse_m": us_recovery["rmse"],  # the USV on the recovery's legs
        "auv_xte_true_rmse_m": au["rmse"], "auv_xte_true_sd_m": au["sd"], "auv_xte_true_mae_m": au["mae"],
        "auv_xte_true_samples": au["n"],
        # the AUV's figures above count from the first waypoint reached (as Table 4.4); its approach apart
        "auv_approach_xte_true_rmse_m": au_approach["rmse"], "auv_approach_xte_true_samples": au_approach["n"],
        # the same from the guidance's own cross-track error, i.e. on the AUV's navigation estimate
        "auv_xte_est_rmse_m": au_split["tracking"]["rmse"],
        "target_error_m": target_error, "target_error_3d_m": target_error_3d,
        # what the AUV navigated on, and how well: its estimate's horizontal error against its ground truth
        "auv_nav_source": "usbl" if fixes_ok else "ins",
        "auv_nav_rmse_m": math.sqrt(sum(e * e for e in nav_during) / len(nav_during)) if nav_during else float("nan"),
        "auv_nav_max_m": max(nav_during) if nav_during else float("nan"), "auv_nav_samples": len(nav_during),
        "auv_nav_after_max_m": max(nav_after) if nav_after else float("nan"),
        # rejected: by the positioning's quality gates or the navigation filter's; an outlier is a fix farther than
        # OUTLIER_M from the truth, and the report says how many of the rejected ones were (and got through)
        "usbl_fixes_received": len(fixes), "usbl_fixes_rejected": usbl["rejected"],
        "usbl_rejected_by": usbl["rejected_by"], "usbl_outliers": usbl["outliers"],
        "usbl_rejected_outliers": usbl["rejected_outliers"], "usbl_outliers_accepted": usbl["accepted_outliers"],
        "usbl_outlier_threshold_m": OUTLIER_M,
        # the rejections meant to catch outliers (fit error, depth, the filter's gate) and how many were: the rest
        # of the rejected (stale) lacked the USV's relayed pose at their time; unplaced: no position to score
        "usbl_rejected_by_gates": usbl["gates"], "usbl_rejected_by_gates_outliers": usbl["gates_outliers"],
        "usbl_rejected_by_gates_unplaced": usbl["gates_unplaced"],
        # the simulated pair's own count of replies sent by a reflected path (its last diagnostics; None on hardware)
        "usbl_multipath_replies": sim_counter(a["/diagnostics"], "usbl_sim", "multipath"),
        "radio": (outcome or {}).get("radio"),  # what crossed the simulated radio between the relays (the job's)
        "detection_time_s": (auv_found_t - auv_start_t) if (auv_found_t and auv_start_t) else float("nan"),
        "min_clearance_m": min_clearance,  # the hull's (sim/contact.h), not the reference point's
        # where the USV really held at the target (before the recovery took it on), against the true target (the
        # stand-off is part of this distance); off_station when farther than the stand-off plus the tolerance
        "usv_final_distance_to_target_m": final_distance,
        "usv_wait_drift_m": wait_drift, "usv_hold_p95_m": hold_p95, "usv_recovery_hold_p95_m": recovery_hold_p95,
        # after the find (docs/mission.md, "Recovery"): the AUV keeping the spot, coming up, and the USV beside it
        "recovered": recovered, "auv_hold_excursion_m": rec["auv_hold_excursion_m"],
        "auv_ascent_drift_m": rec["auv_ascent_drift_m"], "auv_surface_excursion_m": rec["auv_surface_excursion_m"],
        "recovery_distance_m": recovery_distance,  # the USV hull to the AUV at the end
        "usv_auv_min_clearance_m": auv_clearance,  # the least of that while the AUV was near the surface
        "find_to_recovery_s": rec["find_to_recovery_s"],
        "found_at_s": rec["found_at_s"], "ascent_at_s": rec["ascent_at_s"], "surfaced_at_s": rec["surfaced_at_s"],
        "recovered_at_s": rec["recovered_at_s"],
        "sim_time_s": sim_time, "wall_time_s": wall_time_s,
        # the simulated run alone (from the shared clock's start), what the ROS-free runner's wall_time_s measures
        "run_wall_time_s": (outcome or {}).get("run_wall_s", float("nan")),
        "stacks_died": {v: round(t, 1) for v, t in died.items()},
        # how far the surviving vehicle moved after the other's stack died (safe behaviour = holding position)
        "survivor_drift_m": _drift_after(usv_track if "auv" in died else auv_track, min(died.values()))
        if len(died) == 1 else float("nan"),
        "faults": faults,
        "usv_final_phase": last_usv.phase if last_usv else None,
        "auv_final_phase": last_auv.phase if last_auv else None,
        "thesis": THESIS,
        # the site every position is relative to (the scenario's origin; map.png is local NED about it)
        "site": {k: (sc.get("origin") or {}).get(k) for k in ("latitude", "longitude", "altitude")},
    }
    # JSON has no NaN: write null for figures that could not be computed
    if outcome and outcome.get("rviz_pixels") is not None:
        metrics["rviz_pixels"] = outcome["rviz_pixels"]
    clean = {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in metrics.items()}
    with open(os.path.join(out, "metrics.json"), "w") as f:
        json.dump(clean, f, indent=2)

    _plots(out, sc, usv_track, auv_track, u, a, detected, (usv_xte, usv_recovery_xte), auv_xte, auv_est_track,
           fixes_ok)
    _navigation_plot(out, nav_err, fix_scores, auv_end_t)
    _summary(out, clean, scenario)
    return clean


def _plots(out, sc, usv_track, auv_track, u, a, detected, usv_xte, auv_xte, auv_est_track=(), fixes_ok=()):
    """map.png and cross_track.png; usv_xte: (the transit's, the recovery's) [(t, e)]."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle, Polygon

    after_find = any(m.phase not in SEARCHING for _, m in a["/auv/mission/status"])
    if after_find:  # the recovery is a few metres across: a second panel, 40 m about it
        fig, (ax, zoom) = plt.subplots(1, 2, figsize=(13, 7.5), gridspec_kw={"width_ratios": [1.6, 1]})
    else:
        fig, ax = plt.subplots(figsize=(8, 8))
    for ob in sc.get("obstacles", []) or []:
        ax.add_patch(Circle((ob["east"], ob["north"]), float(ob.get("radius", 0.5)), color="red", alpha=0.6))
    if u["/usv/guidance/safety_boxes"]:
        for box in u["/usv/guidance/safety_boxes"][-1][1].boxes:
            ax.add_patch(Polygon([(c.y, c.x) for c in box.corners], closed=True, fill=False, ec="orange", lw=1.5))
    for vehicle, bag, color in (("usv", u, "green"), ("auv", a, "cyan")):
        # the longest path guidance planned (SBB waypoints included), else the mission's path
        for topic in ("/%s/guidance/planned_path" % vehicle, "/%s/guidance/path" % vehicle):
            paths = [path_ned(m) for _, m in bag[topic]]
            paths = [p for p in paths if p]
            if paths:
                pts = max(paths, key=len)
                ax.plot([p[1] for p in pts], [p[0] for p in pts], "o--", color=color, ms=3, lw=1,
                        label="%s planned path" % vehicle.upper())
                break
    if usv_track:
        ax.plot([p[2] for p in usv_track], [p[1] for p in usv_track], color="blue", lw=2, label="USV trajectory")
    if auv_track:
        ax.plot([p[2] for p in auv_track], [p[1] for p in auv_track], color="purple", lw=1.5, label="AUV trajectory")
    if auv_est_track:
        ax.plot([p[2] for p in auv_est_track], [p[1] for p in auv_est_track], "--", color="magenta", lw=0.8,
                label="AUV estimate (/auv/odom)")
    fix_pts = [(f.position_ned.x, f.position_ned.y) for f in fixes_ok
               if math.isfinite(f.position_ned.x) and math.isfinite(f.position_ned.y)]
    if fix_pts:
        ax.plot([p[1] for p in fix_pts], [p[0] for p in fix_pts], ".", color="darkorange", ms=3, ls="none",
                label="USBL fixes (accepted)")
    for tt in sc.get("targets", []) or []:
        ax.plot(tt["east"], tt["north"], "k*", ms=14, label="target (true)")
    drawn = _draw_recovery(ax, usv_track, auv_track, u["/usv/mission/status"], a["/auv/mission/status"])
    if detected:
        p = detected[1].origin
        ax.plot(p.y, p.x, "rx", ms=12, mew=2, label="target (detected)")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    o = sc.get("origin") or {}
    site = " (about %.5f, %.5f)" % (o["latitude"], o["longitude"]) if "latitude" in o and "longitude" in o else ""
    ax.set_title("Co-operative mission: %s%s" % (sc.get("name", ""), site))
    if after_find:
        for track, color in ((usv_track, "blue"), (auv_track, "purple")):
            if track:
                zoom.plot([p[2] for p in track], [p[1] for p in track], color=color, lw=0.8, alpha=0.5)
        for tt in sc.get("targets", []) or []:
            zoom.plot(tt["east"], tt["north"], "k*", ms=14)
        _draw_recovery(zoom, usv_track, auv_track, u["/usv/mission/status"], a["/auv/mission/status"], legend=False)
        if drawn:
            cn, ce = sum(p[0] for p in drawn) / len(drawn), sum(p[1] for p in drawn) / len(drawn)
            zoom.set_xlim(ce - 20, ce + 20)
            zoom.set_ylim(cn - 20, cn + 20)
        zoom.set_aspect("equal", adjustable="box")
        zoom.grid(True, alpha=0.3)
        zoom.set_xlabel("east [m]")
        zoom.set_title("after the find: hold (square), ascent (orange), surface (circle), recovery (green)", fontsize=8)
    fig.savefig(os.path.join(out, "map.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)

    fig, axs = plt.subplots(2, 1, figsize=(9, 6), sharex=False)
    # time on path: the transit, then the recovery's legs (grey) after it
    usv_transit, usv_recovery = usv_xte
    for axx, xte, rest, name in ((axs[0], usv_transit, usv_recovery, "USV"), (axs[1], auv_xte, [], "AUV")):
        if xte:
            t0 = xte[0][0]
            axx.plot([t - t0 for t, _ in xte], [e for _, e in xte], lw=1, label="transit" if rest else None)
        if rest:
            t0 = rest[0][0] - ((xte[-1][0] - xte[0][0]) if xte else 0.0)
            axx.plot([t - t0 for t, _ in rest], [e for _, e in rest], lw=1, color="0.6",
                     label="the recovery's legs round the AUV (reported apart)")
            axx.legend(loc="lower left", fontsize=8)
        axx.axhline(0, color="k", lw=0.5)
        axx.set_ylabel("%s e(t) [m]" % name)
        axx.grid(True, alpha=0.3)
    axs[1].set_xlabel("time on path [s]")
    fig.suptitle("LOS cross-track error")
    fig.savefig(os.path.join(out, "cross_track.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)


def _draw_recovery(ax, usv_track, auv_track, usv_status, auv_status, legend=True):
    """The recovery on map.png's axes: the AUV's hold point at the find, its ascent (its track while ASCENT), where it
    held at the surface, the USV's way to it (its track from RECOVERY on) and the point it held beside it. Returns the
    points drawn [(north, east)] (empty: nothing after the find)."""
    a = [(_stamp(t, m), m) for t, m in auv_status]
    u = [(_stamp(t, m), m) for t, m in usv_status]
    finite = lambda p: p is not None and p.x == p.x and p.y == p.y  # noqa: E731
    hold = next((m.hold_point for _, m in a if m.phase == "TARGET_FOUND" and finite(m.hold_point)), None)
    surface = next((m.hold_point for _, m in reversed(a) if m.phase in ("SURFACED", "RECOVERED")), None)
    station = next((m.hold_point for _, m in reversed(u) if m.phase in ("RECOVERY", "RECOVERED")), None)
    ascent = [t for t, m in a if m.phase == "ASCENT"]
    recovery = [t for t, m in u if m.phase in ("RECOVERY", "RECOVERED")]
    label = (lambda x: x) if legend else (lambda x: None)
    if ascent:
        pts = [p for p in auv_track if ascent[0] <= p[0] <= ascent[-1] + 0.5]
        ax.plot([p[2] for p in pts], [p[1] for p in pts], color="orange", lw=2.5, label=label("AUV ascent"))
    if recovery and usv_track:
        pts = [p for p in usv_track if p[0] >= recovery[0]]
        ax.plot([p[2] for p in pts], [p[1] for p in pts], color="limegreen", lw=2.5, label=label("USV recovery"))
    drawn = []
    for p, kw, text in ((hold, dict(marker="s", color="blue", mfc="none"), "AUV hold point (at depth)"),
                        (surface, dict(marker="o", color="orange", mfc="none"), "AUV at the surface"),
                        (station, dict(marker="^", color="green"), "USV recovery point")):
        if finite(p):
            ax.plot(p.y, p.x, ls="none", ms=9, mew=2, label=label(text), **kw)
            drawn.append((p.x, p.y))
    if drawn and auv_track:
        ax.plot(auv_track[-1][2], auv_track[-1][1], "x", color="purple", ms=9, mew=2, label=label("AUV at the end"))
    return drawn


def _navigation_plot(out, nav_err, fix_scores, auv_end_t):
    """navigation.png: the AUV's navigation error over time, and each USBL fix's error against the truth by what
    became of it (fused, refused by the filter's gate, rejected by a quality gate), the outlier line drawn."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    if nav_err:
        axs[0].plot([t for t, _ in nav_err], [e for _, e in nav_err], lw=1, color="purple")
    if math.isfinite(auv_end_t):
        for ax in axs:
            ax.axvline(auv_end_t, color="grey", lw=0.8, ls=":")
    axs[0].set_ylabel("navigation error [m]")
    axs[0].grid(True, alpha=0.3)
    floor = 0.02  # fixes without a position (no USV pose near them) are drawn here
    styles = {"fused": ("o", "darkorange", 3, "fused"), "gated": ("x", "red", 6, "refused by the filter's gate"),
              "fit_error": ("+", "blue", 6, "rejected: fit error"), "depth": ("+", "green", 6, "rejected: depth"),
              "stale": ("|", "grey", 6, "rejected: stale (no USV pose in time)")}
    for verdict in sorted({v for _, v, _ in fix_scores}, key=lambda v: (v != "fused", v != "gated", v)):
        pts = [(t, max(e, floor) if e is not None else floor) for t, v, e in fix_scores if v == verdict]
        marker, colour, size, label = styles.get(verdict, ("+", "purple", 6, "rejected: " + verdict))
        axs[1].plot([t for t, _ in pts], [e for _, e in pts], marker, color=colour, ms=size, ls="none",
                    label="%s (%d)" % (label, len(pts)))
    axs[1].axhline(OUTLIER_M, color="k", lw=0.8, ls="--", label="outlier (%.0f m)" % OUTLIER_M)
    axs[1].set_yscale("log")
    axs[1].set_ylim(bottom=floor * 0.7)
    axs[1].set_ylabel("USBL fix error vs truth [m]\n(bottom: no position)")
    axs[1].set_xlabel("simulated time [s] (dotted: the AUV's mission ends)")
    axs[1].grid(True, alpha=0.3)
    axs[1].legend(loc="upper right", fontsize=7)
    fig.suptitle("AUV navigation on USBL fixes")
    fig.savefig(os.path.join(out, "navigation.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)


def _fmt(v, unit=""):
    return "n/a" if v is None else ("%.3f%s" % (v, unit) if isinstance(v, float) else str(v))


def _summary(out, m, scenario):
    th = m["thesis"]
    lines = [
        "# Mission report", "",
        "Scenario: `%s`%s" % (scenario, ", site %.6f, %.6f (local north-east-down frame about it)" % (
            m["site"]["latitude"], m["site"]["longitude"]) if m.get("site", {}).get("latitude") is not None else ""),
        "",
        "**%s** (%s) - %s" % ("SUCCESS" if m["success"] else "FAILED", m["outcome"], m["reason"]), "",
        "| figure | this run | thesis field test |", "| --- | --- | --- |",
        "| USV cross-track RMSE in the transit, on its GPS estimate (guidance's own) | %s | %.4f m (Table 5.1) |" % (
            _fmt(m["usv_xte_est_rmse_m"], " m"), th["usv_xte_est_rmse_m"]),
        "| USV cross-track SD, on its estimate | %s | %.4f m |" % (_fmt(m["usv_xte_est_sd_m"], " m"), th["usv_xte_est_sd_m"]),
        "| USV cross-track MAE, on its estimate | %s | %.4f m |" % (
            _fmt(m["usv_xte_est_mae_m"], " m"), th["usv_xte_est_mae_m"]),
        "| USV cross-track RMSE in the transit, true position | %s | |" % _fmt(m["usv_xte_true_rmse_m"], " m"),
        "| USV cross-track RMSE, true position, on the recovery's legs round the AUV | %s | |" % _fmt(
            m.get("usv_recovery_xte_true_rmse_m"), " m"),
        "| AUV cross-track RMSE, true position, from the first waypoint | %s | %.2f m (Table 4.4, Girona500) |" % (
            _fmt(m["auv_xte_true_rmse_m"], " m"), th["auv_xte_true_rmse_m"]),
        "| AUV cross-track RMSE, true position, on its approach (leg 1) | %s | |" % _fmt(
            m["auv_approach_xte_true_rmse_m"], " m"),
        "| AUV cross-track RMSE on its estimate (guidance's own), from the first waypoint | %s | |" % _fmt(
            m["auv_xte_est_rmse_m"], " m"),
        "| detection time | %s | |" % _fmt(m["detection_time_s"], " s"),
        "| target localisation error | %s | |" % _fmt(m["target_error_m"], " m"),
        "| minimum clearance, hull to obstacles | %s | |" % _fmt(m["min_clearance_m"], " m"),
        "| AUV navigation error, horizontal (estimate vs truth; %s) | RMSE %s, max %s | |" % (
            m["auv_nav_source"], _fmt(m["auv_nav_rmse_m"], " m"), _fmt(m["auv_nav_max_m"], " m")),
        "| USBL fixes | %d received, %d rejected (%s) | |" % (
            m["usbl_fixes_received"], m["usbl_fixes_rejected"],
            ", ".join("%s %d" % kv for kv in sorted(m.get("usbl_rejected_by", {}).items())) or "none"),
        "| USBL outliers (> %.0f m from the truth) | %d, of them rejected %d; rejected by the outlier gates (fit "
        "error, depth, the filter's) %d, of them outliers %d, without a position %d | |" % (
            OUTLIER_M, m["usbl_outliers"], m["usbl_outliers"] - m["usbl_outliers_accepted"],
            m["usbl_rejected_by_gates"], m["usbl_rejected_by_gates_outliers"], m["usbl_rejected_by_gates_unplaced"]),
        "| USBL replies by a reflected path (the simulated pair's count) | %s | |" % _fmt(m["usbl_multipath_replies"]),
        "| USV distance to the true target where it held there (its last ARRIVED) | %s | |" % _fmt(
            m["usv_final_distance_to_target_m"], " m"),
        "| USV drift while waiting for the target | %s | |" % _fmt(m["usv_wait_drift_m"], " m"),
        "| USV hold on station at the target, 95th percentile, from on station (within station_radius) | %s | |"
        % _fmt(m["usv_hold_p95_m"], " m"),
        "| USV hold on station in the recovery (run-in, beside the AUV), 95th percentile | %s | |"
        % _fmt(m.get("usv_recovery_hold_p95_m"), " m"),
        "| AUV hold at the find, largest excursion | %s | |" % _fmt(m["auv_hold_excursion_m"], " m"),
        "| AUV drift while ascending | %s | |" % _fmt(m["auv_ascent_drift_m"], " m"),
        "| AUV at the surface, largest distance from its point | %s | |" % _fmt(m["auv_surface_excursion_m"], " m"),
        "| USV hull to the AUV at the end (least near the surface) | %s (%s) | |" % (
            _fmt(m["recovery_distance_m"], " m"), _fmt(m["usv_auv_min_clearance_m"], " m")),
        "| search's end, ascent, at the surface, RECOVERED (simulated time) | %s, %s, %s, %s | |" % (
            _fmt(m["found_at_s"], " s"), _fmt(m["ascent_at_s"], " s"), _fmt(m["surfaced_at_s"], " s"),
            _fmt(m["recovered_at_s"], " s")),
        "| from the find to the recovery | %s | |" % _fmt(m["find_to_recovery_s"], " s"),
        "| simulated time | %s | |" % _fmt(m["sim_time_s"], " s"),
        "| wall time | %s | |" % _fmt(m["wall_time_s"], " s"),
        "", "Final phases: USV %s, AUV %s." % (m["usv_final_phase"], m["auv_final_phase"]), "",
    ]
    if m["stacks_died"]:
        lines += ["Stacks that died: %s (simulated time [s]); the other vehicle moved at most %s afterwards." % (
            ", ".join("%s at %s" % kv for kv in m["stacks_died"].items()), _fmt(m["survivor_drift_m"], " m")), ""]
    for f in m.get("faults", []):
        lines += ["Fault " + f["summary"] + (
            "" if "nav_error_max_m" not in f else
            " Navigation: error up to %s, sigma %s -> %s, statuses %s, back under %.1f m %s s after." % (
                _fmt(f["nav_error_max_m"], " m"), _fmt(f["nav_sigma_before_m"], " m"), _fmt(f["nav_sigma_max_m"], " m"),
                ", ".join(f["nav_statuses"]), NAV_RECOVERED_M, _fmt(f["nav_recovered_after_s"]))), ""]
    lines += ["![map](map.png)", "", "![cross-track error](cross_track.png)", "", "![navigation](navigation.png)", ""]
    if "rviz_pixels" in m:
        lines += ["![rviz, USV configuration](rviz_usv.png)", ""]
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--usv-bag")
    ap.add_argument("--auv-bag")
    ap.add_argument("--scenario")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    print(json.dumps(build(a.usv_bag, a.auv_bag, a.scenario, a.out), indent=2))


if __name__ == "__main__":
    main()
