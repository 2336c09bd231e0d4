"""The mission report's summary.md (report.py): the figures against the thesis', the faults in a sentence each."""
import os

from offshore_gnc.report_metrics import NAV_RECOVERED_M, OUTLIER_M


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
