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
            b.write("/usv/ground_truth/odom", o, t)
            g = GuidanceStatus()
            g.mode = GuidanceStatus.MODE_FOLLOW_PATH
            g.cross_track_error = 0.5 if i % 2 else -0.5
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
        s = MissionStatus(vehicle="usv", phase="ARRIVED", finished=True, success=True, detail="arrived")
        b.write("/usv/mission/status", s, rospy.Time(149))
    sc = tmp_path / "sc.yaml"
    sc.write_text("name: t\nobstacles:\n  - {type: buoy, north: 25.0, east: 3.0, radius: 0.5}\n"
                  "targets:\n  - {north: 45.0, east: 3.0, depth: 5.0}\n")
    out = tmp_path / "report"
    m = report.build(usv_bag, None, str(sc), str(out), wall_time_s=12.0)
    assert m["success"] is True
    assert m["usv_rmse_m"] == pytest.approx(0.5)
    assert m["usv_mae_m"] == pytest.approx(0.5)
    assert m["min_clearance_m"] == pytest.approx(2.5 - 0.5)
    assert m["target_error_m"] == pytest.approx(1.0)
    assert m["usv_final_distance_to_target_m"] == pytest.approx(math.hypot(45.0 - 49.0, 3.0 - 0.5))
    assert m["auv_rmse_m"] is None  # no AUV bag: reported as unknown, not as zero
    assert m["sim_time_s"] == pytest.approx(49.0)
    for f in ("metrics.json", "summary.md", "map.png", "cross_track.png"):
        assert (out / f).stat().st_size > 0, f
    assert json.load(open(out / "metrics.json"))["wall_time_s"] == 12.0
    assert "SUCCESS" in (out / "summary.md").read_text()


def test_auv_tracking_counted_from_the_first_waypoint(tmp_path):
    """The AUV's cross-track figures leave out the approach to its path (leg 1), reported apart (Table 4.4)."""
    import rosbag
    import rospy
    from offshore_gnc.msg import GuidanceStatus

    auv_bag = str(tmp_path / "auv.bag")
    with rosbag.Bag(auv_bag, "w") as b:
        for i in range(30):
            g = GuidanceStatus(mode=GuidanceStatus.MODE_FOLLOW_PATH, num_waypoints=6)
            g.active_leg = 1 if i < 10 else 2 + i // 10
            g.cross_track_error = 5.0 if i < 10 else (0.2 if i % 2 else -0.2)
            b.write("/auv/guidance/status", g, rospy.Time(100 + i))
        g = GuidanceStatus(mode=GuidanceStatus.MODE_STATION_KEEPING, active_leg=5, cross_track_error=9.0)
        b.write("/auv/guidance/status", g, rospy.Time(131))  # not following: in neither figure
    m = report.build(None, auv_bag, None, str(tmp_path / "report"))
    assert m["auv_xte_samples"] == 20 and m["auv_rmse_m"] == pytest.approx(0.2, abs=1e-4)
    assert m["auv_approach_samples"] == 10 and m["auv_approach_rmse_m"] == pytest.approx(5.0, abs=1e-4)
