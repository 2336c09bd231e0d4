# The whole co-operative mission ROS-free (mission_rosfree) vs the ROS main job, the same scenario, navigation and seeds
# Usage: ./scripts/bench mission [--scenario FILE] [--auv-model girona500|acolor] [--runs N] [--ros-rate R]
# Both navigate the AUV on USBL fixes placed by the USV's relayed GPS and heading; the ROS job runs at --ros-rate
# (default 20, the main job's: the fastest at which its stacks keep up on a 2-core machine; at --rate 0 each
# simulator ran its granted half second in a burst and the stacks fell behind within it: seed 1's USV cross-track
# 1.77 m against 0.98 m, 64 USBL outliers against 7) and both
# are timed on the simulated run alone (the ROS job from its shared clock's start: masters and stacks' start-up
# excluded). A run that fails is counted, not fatal. N runs each (ROS-free seeds 1..N; the ROS job's sensor noise comes from its launch
# files' seeds); medians compared. Last line: one JSON object with each figure of both, their ratio (ROS-free / ROS)
# and the speed-up of the simulated run; each mission runs to the AUV's recovery (docs/mission.md).
set -euo pipefail
scenario="$REPO/config/scenarios/pyhajarvi.yaml"
model=girona500
runs=3
ros_rate=20
while [ $# -gt 0 ]; do
  case "$1" in
    --scenario) scenario="$(realpath "$2")"; shift 2 ;;
    --auv-model) model="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --ros-rate) ros_rate="$2"; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for i in $(seq 1 "$runs"); do
  echo "ROS-free mission (mission_rosfree, one process), seed $i:"
  "$WS/devel/lib/offshore_gnc/mission_rosfree" --scenario "$scenario" --auv-model "$model" --seed "$i" \
    | tee "$tmp/rosfree$i.json" | cut -c1-160 || true  # exit 1: the mission failed; its metrics still count
done
for i in $(seq 1 "$runs"); do
  echo "ROS mission (two masters, the vehicles' stacks, shared lockstep clock at --rate $ros_rate), run $i of $runs:"
  /usr/bin/python3 "$REPO/python/offshore_gnc/mission_job.py" --scenario "$scenario" --auv-model "$model" --quiet \
    --rate "$ros_rate" --out "$tmp/ros$i" | tail -n 2 || true
done
/usr/bin/python3 - "$tmp" "$runs" "$ros_rate" <<'PY'
import json, sys, statistics
tmp, runs = sys.argv[1], int(sys.argv[2])
free = [json.loads(open("%s/rosfree%d.json" % (tmp, i)).read().strip().splitlines()[-1]) for i in range(1, runs + 1)]
ros = [json.load(open("%s/ros%d/metrics.json" % (tmp, i))) for i in range(1, runs + 1)]
def med(rs, k):
    v = [r[k] for r in rs if r.get(k) is not None]
    return statistics.median(v) if v else None
out = {"runs": runs, "ros_rate": float(sys.argv[3])}
for k in ("usv_xte_est_rmse_m", "auv_xte_true_rmse_m", "auv_nav_rmse_m", "target_error_m", "usv_hold_p95_m", "usv_wait_drift_m",
          "min_clearance_m", "auv_hold_excursion_m", "auv_ascent_drift_m", "recovery_distance_m", "usv_auv_min_clearance_m",
          "find_to_recovery_s", "sim_time_s"):
    a, b = med(free, k), med(ros, k)
    out[k + "_rosfree"], out[k + "_ros"] = a, b
    out[k + "_ratio"] = round(a / b, 3) if a is not None and b else None
out["success_rosfree"] = sum(r["outcome"] == "success" for r in free)
out["success_ros"] = sum(r["outcome"] == "success" for r in ros)
out["recovered_rosfree"] = sum(bool(r.get("recovered")) for r in free)
out["recovered_ros"] = sum(bool(r.get("recovered")) for r in ros)
out["rosfree_run_s"] = med(free, "wall_time_s")
out["ros_run_s"] = med(ros, "run_wall_time_s")
out["rosfree_realtime_x"] = round(out["sim_time_s_rosfree"] / out["rosfree_run_s"], 1)
out["ros_realtime_x"] = round(out["sim_time_s_ros"] / out["ros_run_s"], 1)
out["speedup"] = round(out["ros_run_s"] / out["rosfree_run_s"], 1)
print(json.dumps(out))
PY
