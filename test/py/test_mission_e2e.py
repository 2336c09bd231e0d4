"""The co-operative mission end to end, as the main job runs it: two real masters, both vehicle stacks in
simulation on one shared (lockstep) simulated clock, the relay between them; then the report's figures against
stated bounds, rviz's picture of the USV during the run, and what happens when one vehicle's stack dies."""
import json
import os
import sys

from offshore_gnc.testing import bounds, run_job

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
JOB = os.path.join(REPO, "python", "offshore_gnc", "mission_job.py")

# Bounds: test/bounds.yaml, one place for each figure, set from the runs in test/bounds_measured.yaml
# (./scripts/measure_bounds; issue 30's rule, audited by test_bounds.py). Notes on them:
# - the USV's cross-track is the transit's (with the recovery's legs round the AUV in it, cut by the 16 m circle of
#   acceptance, one job's run of 2026-12-05 gave 2.69 m);
# - the hold at the target counts from on station; the survivor's drift is the same dynamic-positioning hold;
# - the recovery's end: the bow asked 4 m off the AUV's reported position, RECOVERED with each vehicle within its
#   station_radius (1 m) of its point on its own navigation: the report the point was planned from up to 1 m from
#   the AUV's hold point and the AUV at the end up to 1 m from it on the other side (replanned only past
#   recovery_replan, 2 m), the bow 1 m off its point and the navigation errors give up to 4 + 2 + 1 + 1 = 8 m.
MIN_PIXELS = 30  # of each colour in rviz's 3-D view (the job's Screenshots.MIN_PIXELS)
USV_TIMEOUT_S = 30.0  # config/mission/auv.yaml (mission::AuvMissionParams): no USV status this long, it comes up


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
    # every figure of test/bounds.yaml's ros_default: the target, the USV's cross-track, wait and hold, the AUV's
    # navigation and cross-track, the recovery's hold, end and least distance
    assert not bounds.breaches(m, "ros_default"), (bounds.breaches(m, "ros_default"), m)
    assert m["find_to_recovery_s"] is not None and m["found_at_s"] < m["ascent_at_s"] < m["surfaced_at_s"] \
        < m["recovered_at_s"], m
    assert m["min_clearance_m"] is not None and m["min_clearance_m"] > 0.0, m  # the hull never touched the buoy
    assert m["usv_xte_est_samples"] > 0, m
    # the AUV navigated on USBL fixes (placed by the USV's relayed GPS and heading), fused in AuvNavigation
    assert m["auv_nav_source"] == "usbl", m
    # at the surface on its own GPS too (the simulator's /auv/gps/fix, as the ROS-free mission's), and the
    # control's speed through the water went to the navigation for a silent DVL
    import rosbag
    with rosbag.Bag(os.path.join(str(tmp_path / "default"), "auv.bag")) as bag:
        counts = {t: bag.get_message_count(t) for t in ("/auv/gps/fix", "/auv/commanded_velocity")}
        nav = [dict((kv.key, kv.value) for kv in st.values) for _, d, _ in bag.read_messages(topics=["/diagnostics"])
               for st in d.status if st.name.endswith("navigation: navigation")]
    assert counts["/auv/gps/fix"] > 10 and counts["/auv/commanded_velocity"] > 1000, counts
    assert nav and "gps_without_site" not in nav[-1] and nav[-1].get("bad_gps", "0") == "0", nav[-1:]
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
    assert m["site"]["latitude"] == -42.8821 and m["site"]["longitude"] == 147.3514, m["site"]
    assert m["auv_nav_source"] == "usbl" and m["auv_xte_true_samples"] > 500, m
    assert not bounds.breaches(m, "ros_acolor"), (bounds.breaches(m, "ros_acolor"), m)
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
    assert not bounds.breaches(m, "ros_no_target"), (bounds.breaches(m, "ros_no_target"), m)


def test_auv_stack_dies_usv_holds_position(tmp_path):
    """Kill -9 of the AUV's whole stack while it searches: the USV never gets a target, notices the silence,
    keeps holding position; the job says so, fails, and still recovers the AUV's unfinished bag."""
    r, m = run("pyhajarvi.yaml", tmp_path / "kill", "--kill", "auv@100", "--after-kill", "120")
    assert r.returncode == 1, r.stdout[-3000:]
    assert m["success"] is False
    assert m["outcome"] == "stack_died" and list(m["stacks_died"]) == ["auv"] and "auv stack died" in m["reason"], m

    assert m["usv_final_phase"] == "PEER_LOST", m
    assert not bounds.breaches(m, "ros_auv_dies"), (bounds.breaches(m, "ros_auv_dies"), m)  # the survivor's hold
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
    assert not bounds.breaches(m, "ros_usv_dies"), (bounds.breaches(m, "ros_usv_dies"), m)
