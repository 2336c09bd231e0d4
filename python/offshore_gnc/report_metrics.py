"""The mission report's figures (report.py): cross-track errors (through the C++ tool `tracking_metrics`), the AUV
navigation's error and the USBL fixes scored against the truth, the outcome and clearances (`mission_outcome`), the
recovery and station keeping, and what each injected fault did."""
import json
import math
import os
import subprocess

from offshore_gnc import VEHICLES, tools
from offshore_gnc.report_bags import _at, _interpolate, _interpolate3, _phase_at, _stamp

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
            on, off, watched = f.get("injected_s"), f.get("ended_s"), VEHICLES
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
