"""The report's figures from a small bag written here: cross-track indicators, clearance, target error."""
import json
import math
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
from offshore_gnc import report  # noqa: E402


def test_tracking_metrics_hand_computed(tmp_path):
    """The report's indicators come from the C++ tracking_metrics tool: hand-computed figures on a CSV whose
    non-finite and non-following rows are skipped."""
    csv = tmp_path / "xte.csv"
    csv.write_text("t,mode,cross_track_error\n0,1,1.0\n1,1,-1.0\n2,1,2.0\n3,1,nan\n4,2,50.0\n")
    s = report.tracking_metrics(str(csv))
    assert s["n"] == 3
    assert s["rmse"] == pytest.approx(math.sqrt(6.0 / 3), abs=1e-4)
    assert s["mae"] == pytest.approx(4.0 / 3, abs=1e-4)
    mean = 2.0 / 3
    assert s["sd"] == pytest.approx(math.sqrt(((1 - mean) ** 2 + (-1 - mean) ** 2 + (2 - mean) ** 2) / 3), abs=1e-4)
    assert math.isnan(report.tracking_metrics(str(tmp_path / "missing.bag"))["rmse"])


def test_report_from_bags(tmp_path):
    import rosbag
    import rospy
    from nav_msgs.msg import Odometry, Path
    from geometry_msgs.msg import PoseStamped
    from offshore_gnc.msg import GuidanceStatus, MissionStatus, Target

    usv_bag = str(tmp_path / "usv.bag")
    with rosbag.Bag(usv_bag, "w") as b:
        for i in range(50):  # the USV drives north along east = 0.5 m, past a buoy at (25, 3)
            t = rospy.Time(100 + i)
            o = Odometry()
            o.header.stamp = t
            o.pose.pose.position.x = 0.5      # ENU x = east
            o.pose.pose.position.y = float(i)  # ENU y = north
            o.pose.pose.orientation.z = o.pose.pose.orientation.w = math.sqrt(0.5)  # bow north (ENU yaw 90 deg)
            b.write("/usv/ground_truth/odom", o, t)
            g = GuidanceStatus()
            g.mode = GuidanceStatus.MODE_FOLLOW_PATH
            # the transit (to 142 s), +-0.5 m; then still on a leg, arrived (9 m) and in the recovery (3 m on the
            # estimate, the truth 0.5 m off a leg due north through east 0): neither counts as the transit's
            g.cross_track_error = (0.5 if i % 2 else -0.5) if i < 42 else 9.0 if i < 46 else 3.0
            if i >= 46:
                g.reference_mode = GuidanceStatus.REFERENCE_FOLLOW
                g.reference_point.x, g.path_angle = float(i), 0.0
            b.write("/usv/guidance/status", g, t)
        p = Path()
        p.header.frame_id = "map_ned"
        for n in (0.0, 10.0, 20.0):
            ps = PoseStamped()
            ps.pose.position.x = n
            p.poses.append(ps)
        b.write("/usv/guidance/path", p, rospy.Time(100))
        tg = Target()
        tg.origin.x, tg.origin.y, tg.origin.z = 45.0, 4.0, 5.0
        b.write("/target", tg, rospy.Time(120))
        for phase, t in (("TRANSIT", 100), ("ARRIVED", 142), ("RECOVERY", 146)):
            b.write("/usv/mission/status", MissionStatus(vehicle="usv", phase=phase, detail=phase), rospy.Time(t))
        s = MissionStatus(vehicle="usv", phase="RECOVERED", finished=True, success=True, detail="recovered")
        b.write("/usv/mission/status", s, rospy.Time(149))
    sc = tmp_path / "sc.yaml"
    sc.write_text("name: t\norigin: {latitude: 61.45, longitude: 23.72}\nusv: {start: {north: 0, east: 0}}\n"
                  "auv: {start: {north: 5, east: 5, depth: 2}}\n"
                  "obstacles:\n  - {type: buoy, north: 25.0, east: 3.0, radius: 0.5}\n"
                  "targets:\n  - {north: 45.0, east: 3.0, depth: 5.0, radius: 0.5}\n")
    out = tmp_path / "report"
    m = report.build(usv_bag, None, str(sc), str(out), wall_time_s=12.0)
    assert m["success"] is True and m["recovered"] is True, m["outcome"]  # success needs the AUV recovered (RECOVERED)
    assert m["usv_xte_est_rmse_m"] == pytest.approx(0.5) and m["usv_xte_est_samples"] == 42  # the transit's
    assert m["usv_xte_est_mae_m"] == pytest.approx(0.5)
    assert m["usv_recovery_xte_true_rmse_m"] == pytest.approx(0.5)
    # from the hull (config/usv.yaml's outline, 1.3 m to each side of the centreline), not the reference point
    assert m["min_clearance_m"] == pytest.approx(2.5 - 0.5 - 1.3, abs=1e-3)
    assert m["outcome"] == "success"
    assert m["target_error_m"] == pytest.approx(1.0)
    # where it held at the target: its last ARRIVED status (142 s), not where the recovery took it
    assert m["usv_final_distance_to_target_m"] == pytest.approx(math.hypot(45.0 - 42.0, 3.0 - 0.5))
    assert m["auv_xte_true_rmse_m"] is None  # no AUV bag: reported as unknown, not as zero
    assert m["sim_time_s"] == pytest.approx(49.0)
    for f in ("metrics.json", "summary.md", "map.png", "cross_track.png"):
        assert (out / f).stat().st_size > 0, f
    assert json.load(open(out / "metrics.json"))["wall_time_s"] == 12.0
    assert "SUCCESS" in (out / "summary.md").read_text()


def test_auv_tracking_counted_from_the_first_waypoint(tmp_path):
    """The AUV's cross-track figures on the truth (its true position's distance from the leg followed: the line
    through the status' reference point along its path angle) leave out the approach to its path (leg 1), reported
    apart (Table 4.4); the guidance's own figure (on the estimate) too. The leg index is not looked up in the
    published path (LOS merges waypoints closer than min_leg_length: the index need not count the path's)."""
    import math
    import rosbag
    import rospy
    from geometry_msgs.msg import PoseStamped
    from nav_msgs.msg import Odometry, Path
    from offshore_gnc.msg import GuidanceStatus

    auv_bag = str(tmp_path / "auv.bag")
    with rosbag.Bag(auv_bag, "w") as b:
        p = Path()
        p.header.frame_id = "map_ned"
        # a duplicate waypoint (merged by LOS): index 2 of this path is not the leg LOS calls 2
        for n, e in ((0.0, 0.0), (0.0, 10.0), (0.0, 10.0), (20.0, 10.0), (20.0, 20.0)):
            ps = PoseStamped()
            ps.pose.position.x, ps.pose.position.y = n, e
            p.poses.append(ps)
        b.write("/auv/guidance/planned_path", p, rospy.Time(99))
        for i in range(31):
            t = rospy.Time(100 + i)
            o = Odometry()
            o.header.stamp = t
            # leg 1 (i < 10): 5 m north of the eastward leg; leg 2 (north along east = 10): 0.2 m east of it
            o.pose.pose.position.x = float(i) if i < 10 else 10.2        # ENU x = east
            o.pose.pose.position.y = 5.0 if i < 10 else float(i - 10)    # ENU y = north
            b.write("/auv/ground_truth/odom", o, t)
            g = GuidanceStatus(mode=GuidanceStatus.MODE_FOLLOW_PATH, num_waypoints=4,
                               reference_mode=GuidanceStatus.REFERENCE_FOLLOW)
            g.active_leg = 1 if i < 10 else 2
            g.path_angle = math.pi / 2 if i < 10 else 0.0
            g.reference_point.x, g.reference_point.y = (0.0, float(i)) if i < 10 else (float(i - 10), 10.0)
            g.cross_track_error = 0.1  # the guidance's own error, on the estimate
            if i < 30:
                b.write("/auv/guidance/status", g, t)
        g = GuidanceStatus(mode=GuidanceStatus.MODE_STATION_KEEPING, active_leg=2, cross_track_error=9.0,
                           reference_mode=GuidanceStatus.REFERENCE_HOLD)
        b.write("/auv/guidance/status", g, rospy.Time(130))  # not following: in neither figure
    m = report.build(None, auv_bag, None, str(tmp_path / "report"))
    assert m["auv_xte_true_samples"] == 20 and m["auv_xte_true_rmse_m"] == pytest.approx(0.2, abs=1e-4)
    assert m["auv_approach_xte_true_samples"] == 10 and m["auv_approach_xte_true_rmse_m"] == pytest.approx(5.0, abs=1e-4)
    assert m["auv_xte_est_rmse_m"] == pytest.approx(0.1, abs=1e-4)


def test_auv_navigation_error_and_usbl_fixes(tmp_path):
    """The AUV's navigation figures: its estimate (/auv/odom) against the truth interpolated at the estimate's
    stamps (estimates outside the truth's span skipped), and the USBL fixes received and rejected: by a quality gate
    or the navigation filter's, and whether each was an outlier (farther than 3 m from the truth at its stamp)."""
    import rosbag
    import rospy
    from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
    from nav_msgs.msg import Odometry
    from offshore_gnc.msg import UsblFix

    def odom(t, north, east):
        o = Odometry()
        o.header.stamp = rospy.Time.from_sec(t)
        o.header.frame_id = "map"
        o.pose.pose.position.x = east   # ENU x = east
        o.pose.pose.position.y = north  # ENU y = north
        o.pose.pose.position.z = -5.0
        o.pose.pose.orientation.w = 1.0
        return o

    auv_bag = str(tmp_path / "auv.bag")
    with rosbag.Bag(auv_bag, "w") as b:
        for i in range(11):  # truth: 1 m/s north from (0, 0), 100..110 s, at 1 Hz
            b.write("/auv/ground_truth/odom", odom(100.0 + i, float(i), 0.0), rospy.Time(100 + i))
        # estimate: 0.5 m east of the truth, between the truth's samples (interpolated) and on them; the two at
        # 99.5 s and 110.5 s are outside the truth's span and do not count (3 m further north)
        est = [(99.5, -0.5 + 3.0)] + [(100.0 + 0.25 * k, 0.25 * k) for k in range(41)] + [(110.5, 10.5 + 3.0)]
        for t, north in est:
            b.write("/auv/odom", odom(t, north, 0.5), rospy.Time.from_sec(t))
        # fixes 0.3 m east of the truth, but the fit-error one 6 m east and the last 8 m east (the filter's gate
        # refused it: it comes on /auv/navigation/refused_fixes as well)
        for k, quality in enumerate([UsblFix.QUALITY_OK, UsblFix.QUALITY_FIT_ERROR, UsblFix.QUALITY_OK,
                                     UsblFix.QUALITY_STALE, UsblFix.QUALITY_OK, UsblFix.QUALITY_OK]):
            f = UsblFix(quality=quality, range=20.0 + k)
            f.header.stamp = rospy.Time(min(101 + 2 * k, 110))
            f.position_ned.x, f.position_ned.y, f.position_ned.z = min(1.0 + 2 * k, 10.0), {1: 6.0, 5: 8.0}.get(k, 0.3), 5.0
            f.latitude = f.longitude = float("nan")
            b.write("/auv/usbl/fix", f, f.header.stamp)
            if k == 5:
                b.write("/auv/navigation/refused_fixes", f, f.header.stamp)
        # the simulated pair's diagnostics: its count of reflected replies, the last message's
        for t, n in ((105, 1), (110, 2)):
            d = DiagnosticArray()
            d.status = [DiagnosticStatus(name="usbl_sim: usbl_sim", values=[KeyValue("pings", "9"),
                                                                            KeyValue("multipath", str(n))])]
            b.write("/diagnostics", d, rospy.Time(t))
    out = tmp_path / "report"
    m = report.build(None, auv_bag, None, str(out))
    assert m["usbl_multipath_replies"] == 2
    assert m["auv_nav_source"] == "usbl"
    assert m["auv_nav_samples"] == 41
    assert m["auv_nav_rmse_m"] == pytest.approx(0.5, abs=1e-9)
    assert m["auv_nav_max_m"] == pytest.approx(0.5, abs=1e-9)
    assert m["usbl_fixes_received"] == 6
    assert m["usbl_fixes_rejected"] == 3
    assert m["usbl_rejected_by"] == {"fit_error": 1, "stale": 1, "gated": 1}
    assert m["usbl_outliers"] == 2 and m["usbl_rejected_outliers"] == 2 and m["usbl_outliers_accepted"] == 0
    saved = json.load(open(out / "metrics.json"))
    assert saved["auv_nav_rmse_m"] == pytest.approx(0.5) and saved["usbl_fixes_rejected"] == 3
    summary = (out / "summary.md").read_text()
    assert "| AUV navigation error, horizontal (estimate vs truth; usbl) | RMSE 0.500 m, max 0.500 m | |" in summary
    assert "| USBL fixes | 6 received, 3 rejected (fit_error 1, gated 1, stale 1) | |" in summary
    assert m["usbl_rejected_by_gates"] == 2 and m["usbl_rejected_by_gates_outliers"] == 2
    assert "| USBL outliers (> 3 m from the truth) | 2, of them rejected 2; rejected by the outlier gates (fit error, " \
        "depth, the filter's) 2, of them outliers 2, without a position 0 | |" in summary
    assert (out / "map.png").stat().st_size > 0 and (out / "navigation.png").stat().st_size > 0

    # only rejected fixes and no estimate: the INS, nothing to compare (unknown, not zero)
    ins_bag = str(tmp_path / "ins.bag")
    with rosbag.Bag(ins_bag, "w") as b:
        for i in range(3):
            b.write("/auv/ground_truth/odom", odom(100.0 + i, float(i), 0.0), rospy.Time(100 + i))
        b.write("/auv/usbl/fix", UsblFix(quality=UsblFix.QUALITY_DEPTH), rospy.Time(101))
    m = report.build(None, ins_bag, None, str(tmp_path / "report-ins"))
    assert m["auv_nav_source"] == "ins"
    assert m["auv_nav_rmse_m"] is None and m["auv_nav_max_m"] is None and m["auv_nav_samples"] == 0
    assert m["usbl_fixes_received"] == 1 and m["usbl_fixes_rejected"] == 1
    assert m["usbl_multipath_replies"] is None  # no simulator's diagnostics: unknown (as on hardware)


def test_fault_entries_carry_the_issues_keys_and_say_what_happened():
    """report.fault_reports on hand-made recordings: a GPS outage answered by its rule (detection, the first neutral
    command, the release), a phantom target refused by the USV mission on arrival, and a DVL outage no rule answers;
    SafeStates for hold and surface from the true speed and depth."""
    import rospy
    from offshore_gnc.msg import FaultEvent, MissionStatus, SafetyState, Target

    def stamped(m, t):
        m.header.stamp = rospy.Time.from_sec(t)
        return (t, m)

    planned = [{"name": "gps", "vehicle": "usv", "rule": "gps_timeout", "start_s": 10.0, "end_s": 20.0},
               {"name": "geofence", "vehicle": "both", "rule": "", "start_s": 30.0, "end_s": None,
                "injected_s": 30.0, "target_ned": [5000.0, 0.0, 5.0]},
               {"name": "dvl", "vehicle": "auv", "rule": "", "start_s": 5.0, "end_s": 8.0}]
    events = {v: [stamped(FaultEvent(name=n, active=True), t0), stamped(FaultEvent(name=n, active=False), t1)]
              for v, n, t0, t1 in (("usv", "gps", 10.0, 20.0), ("auv", "dvl", 5.0, 8.0))}
    transitions = {"usv": [
        stamped(SafetyState(active_rule="gps_timeout", active_rules=["gps_timeout"], action_name="neutral",
                            reason="gps silent for 3.0 s (timeout 3.0 s)"), 13.05),
        stamped(SafetyState(active_rule="gps_timeout", active_rules=[], action_name="none", reason="released"), 22.1)]}
    safe = report.SafeStates({"usv": [(13.0, False), (13.1, True), (13.2, True)]},
                             {"usv": [(40.0, 1.2), (41.0, 0.5), (42.0, 0.2)]}, {"auv": [(50.0, 3.0), (55.0, 0.4)]})
    refused = "waiting for the AUV's target; refused a target: target 5.0 km from the origin is outside the region"
    status = [stamped(MissionStatus(detail="waiting for the AUV's target"), 31.0),
              stamped(MissionStatus(detail=refused), 32.5)]
    phantom = Target()
    phantom.origin.x = 5000.0
    f = {r["name"]: r for r in report.fault_reports(planned, events, transitions, safe=safe, usv_status=status,
                                                     usv_targets=[(32.4, phantom)])}
    for r in f.values():
        assert {"name", "injected_at_s", "detected_at_s", "action", "safe_state_at_s", "recovered_at_s",
                "summary"} <= set(r), r
    g = f["gps"]
    assert (g["injected_at_s"], g["detected_at_s"], g["action"]) == (10.0, 13.05, "neutral")
    assert (g["safe_state_at_s"], g["recovered_at_s"], g["ended_at_s"]) == (13.1, 22.1, 20.0)
    assert g["summary"] == ("`gps` (USV) injected at 10.0 s, ended at 20.0 s: gps_timeout -> neutral after 3.05 s "
                            "(gps silent for 3.0 s (timeout 3.0 s)); neutral actuators from 13.1 s; released at 22.1 s.")
    fence = f["geofence"]
    assert (fence["arrived_at_s"], fence["detected_at_s"], fence["action"]) == (32.4, 32.5, "refuse")
    assert fence["reason"] == "target 5.0 km from the origin is outside the region"
    assert fence["safe_state_at_s"] == 32.5 and fence["recovered_at_s"] is None
    assert "nothing to recover" in fence["summary"]
    # a USV master whose clock trails the job's round receives the phantom (stamped at injection) "before" it
    late = Target()
    late.origin.x = 5000.0
    late.header.stamp = rospy.Time.from_sec(30.0)
    r = report.fault_reports(planned[1:2], {}, {}, usv_status=status, usv_targets=[(29.8, late)])
    assert r[0]["arrived_at_s"] == 29.8, r
    d = f["dvl"]
    assert d["detected_at_s"] is None and d["action"] is None and "no rule answered it" in d["summary"], d
    assert safe.reached("usv", "hold", 40.0) == 42.0  # under 0.5 m/s
    assert safe.reached("auv", "surface", 49.0) == 55.0  # under 0.5 m deep
    assert safe.reached("usv", "surface", 13.0) == 13.1  # the USV's surface is neutral
    assert safe.reached("usv", "warn", 7.0) == 7.0 and safe.reached("auv", "surface", 60.0) is None


def test_recovery_figures_and_the_auv_left_in_the_water(tmp_path):
    """After the find (docs/mission.md, "Recovery"): the AUV's hold excursion from its hold point (3-D, from on station
    until the ascent), its drift while coming up (once it rose 0.3 m), the hull's distance to it (the C++ tool, the AUV
    a disc of its length), the times from the statuses' stamps; and without RECOVERED the outcome auv_adrift."""
    import rosbag
    import rospy
    from geometry_msgs.msg import Point
    from nav_msgs.msg import Odometry
    from offshore_gnc.msg import MissionStatus, Target

    def odom(n, e, d, t, yaw_enu=0.0):
        o = Odometry()
        o.header.stamp = rospy.Time(t)
        o.pose.pose.position.x, o.pose.pose.position.y, o.pose.pose.position.z = e, n, -d
        o.pose.pose.orientation.z, o.pose.pose.orientation.w = math.sin(yaw_enu / 2), math.cos(yaw_enu / 2)
        return o

    def status(vehicle, phase, t, hold=(float("nan"),) * 3, since=float("nan"), **kw):
        m = MissionStatus(vehicle=vehicle, phase=phase, on_station_since=since, hold_point=Point(*hold), **kw)
        m.header.stamp = rospy.Time(t)
        return m

    auv_bag, usv_bag = str(tmp_path / "auv.bag"), str(tmp_path / "usv.bag")
    with rosbag.Bag(auv_bag, "w") as b:
        # holding at (40, 0, 3): on station from 102 s, 0.5 m off at 110 s (and 3 m off at 101 s, before on station)
        track = [(100, 37, 0, 3), (101, 37, 0, 3), (102, 39.8, 0, 3), (110, 40.5, 0, 3), (120, 40.2, 0, 3),
                 # ascending from 121 s: 0.4 m off the surfacing point at 2.9 m (not yet risen), 0.6 m once risen
                 (122, 40.4, 0, 2.9), (130, 40.0, 0.6, 2.0), (150, 40.0, 0.2, 0.0)]
        for n, e_, d, t in [(n, e_, d, t) for t, n, e_, d in track]:
            b.write("/auv/ground_truth/odom", odom(n, e_, d, t), rospy.Time(t))
        b.write("/auv/mission/status", status("auv", "COVERAGE", 50), rospy.Time(50))
        tg = Target()
        tg.origin.x, tg.origin.y, tg.origin.z = 45.0, 0.5, 3.0
        b.write("/target", tg, rospy.Time(100))
        b.write("/auv/mission/status", status("auv", "TARGET_FOUND", 100, (40, 0, 3), 102.0), rospy.Time(100))
        b.write("/auv/mission/status", status("auv", "TARGET_FOUND", 110, (40, 0, 3), 102.0), rospy.Time(110))
        b.write("/auv/mission/status", status("auv", "ASCENT", 121, (40, 0, 3)), rospy.Time(121))
        b.write("/auv/mission/status", status("auv", "SURFACED", 145, (40, 0, 0), stationary=True), rospy.Time(145))
    with rosbag.Bag(usv_bag, "w") as b:
        for t in range(100, 151):  # at the target (3 m east of it) until ARRIVED ends, then 10 m east of the
            # surfacing point, bow west toward it (ENU yaw 180 deg)
            n, e_ = (45, 3) if t <= 120 else (40, 10)
            b.write("/usv/ground_truth/odom", odom(n, e_, 0, t, math.pi), rospy.Time(t))
        b.write("/usv/mission/status", status("usv", "ARRIVED", 120), rospy.Time(120))
        b.write("/usv/mission/status", status("usv", "RECOVERY", 146, (40, 10, 0)), rospy.Time(146))
    sc = tmp_path / "sc.yaml"
    sc.write_text("name: t\norigin: {latitude: 61.45, longitude: 23.72}\nusv: {start: {north: 0, east: 0}}\n"
                  "auv: {start: {north: 5, east: 5, depth: 2}}\n"
                  "targets:\n  - {north: 45.0, east: 0.0, depth: 5.0, radius: 0.5}\n")
    m = report.build(usv_bag, auv_bag, str(sc), str(tmp_path / "r"), outcome={"reason": "time", "sim_time_s": 150.0})
    assert m["auv_hold_excursion_m"] == pytest.approx(0.5)
    assert m["auv_ascent_drift_m"] == pytest.approx(0.6)
    assert m["auv_surface_excursion_m"] == pytest.approx(0.2)  # at the surface from 145 s: 0.2 m off at 150 s
    assert (m["found_at_s"], m["ascent_at_s"], m["surfaced_at_s"]) == (100.0, 121.0, 145.0)
    assert m["recovered_at_s"] is None and m["find_to_recovery_s"] is None and m["recovered"] is False
    # the bow 5.3 m ahead of the reference point, 9.8 m from the AUV's centre at the end, the Girona500 1.5 m long
    assert m["recovery_distance_m"] == pytest.approx(9.8 - 5.3 - 0.75, abs=1e-3)
    assert m["usv_auv_min_clearance_m"] == pytest.approx(9.8 - 5.3 - 0.75, abs=1e-3)  # only near the surface
    assert m["target_error_m"] == pytest.approx(0.5)
    assert m["usv_final_distance_to_target_m"] == pytest.approx(3.0)  # where it held at the target
    assert m["outcome"] == "auv_adrift"  # the USV arrived, the AUV came up: nobody picked it up
    assert "hull to the AUV" in (tmp_path / "r" / "summary.md").read_text()
    assert (tmp_path / "r" / "map.png").stat().st_size > 0
