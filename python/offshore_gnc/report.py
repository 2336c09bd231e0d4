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
import json
import math
import os

import yaml

# The report's parts; the names tests and mission_job.py use stay importable from here.
from offshore_gnc.report_bags import _at, _stamp, odom_track_ned, path_ned, read_bag, sim_counter  # noqa: F401
from offshore_gnc.report_metrics import (  # noqa: F401
    ACTION_HOLD, MODE_FOLLOW_PATH, OUTLIER_M, QUALITY_OK, SEARCHING, THESIS, SafeStates, _drift_after, _phase_at,
    fault_reports, judge, nav_error, recovery_figures, split_tracking, station_keeping, tracking_metrics,
    usbl_verdicts)
from offshore_gnc.report_plots import _navigation_plot, _plots
from offshore_gnc.report_summary import _summary


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
