# The whole co-operative mission ROS-free (mission_rosfree) vs the ROS main job, the same scenario, navigation and seeds
# Usage: ./scripts/bench mission [--scenario FILE] [--auv-model girona500|acolor] [--runs N]
# Both navigate the AUV on USBL fixes placed by the USV's relayed GPS and heading; the ROS job runs at full speed
# (--rate 0) and both are timed on the simulated run alone (the ROS job from its shared clock's start: masters and
# stacks' start-up excluded). N runs each (ROS-free seeds 1..N; the ROS job's sensor noise comes from its launch
# files' seeds); medians compared. Last line: one JSON object with each figure of both, their ratio (ROS-free / ROS)
# and the speed-up of the simulated run.
set -euo pipefail
scenario="$REPO/config/scenarios/pyhajarvi.yaml"
model=girona500
runs=3
while [ $# -gt 0 ]; do
  case "$1" in
    --scenario) scenario="$(realpath "$2")"; shift 2 ;;
    --auv-model) model="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for i in $(seq 1 "$runs"); do
  echo "ROS-free mission (mission_rosfree, one process), seed $i:"
  "$WS/devel/lib/offshore_gnc/mission_rosfree" --scenario "$scenario" --auv-model "$model" --seed "$i" \
    | tee "$tmp/rosfree$i.json" | cut -c1-160
done
for i in $(seq 1 "$runs"); do
  echo "ROS mission (two masters, the vehicles' stacks, shared lockstep clock at full speed), run $i of $runs:"
  /usr/bin/python3 "$REPO/python/offshore_gnc/mission_job.py" --scenario "$scenario" --auv-model "$model" --quiet \
    --rate 0 --out "$tmp/ros$i" | tail -n 2
done
/usr/bin/python3 - "$tmp" "$runs" <<'PY'
import json, sys, statistics
tmp, runs = sys.argv[1], int(sys.argv[2])
free = [json.loads(open("%s/rosfree%d.json" % (tmp, i)).read().strip().splitlines()[-1]) for i in range(1, runs + 1)]
ros = [json.load(open("%s/ros%d/metrics.json" % (tmp, i))) for i in range(1, runs + 1)]
def med(rs, k):
    v = [r[k] for r in rs if r.get(k) is not None]
    return statistics.median(v) if v else None
out = {"runs": runs}
for k in ("usv_xte_est_rmse_m", "auv_xte_true_rmse_m", "auv_nav_rmse_m", "target_error_m", "usv_hold_p95_m", "usv_wait_drift_m",
          "min_clearance_m", "sim_time_s"):
    a, b = med(free, k), med(ros, k)
    out[k + "_rosfree"], out[k + "_ros"] = a, b
    out[k + "_ratio"] = round(a / b, 3) if a is not None and b else None
out["success_rosfree"] = sum(r["outcome"] == "success" for r in free)
out["success_ros"] = sum(r["outcome"] == "success" for r in ros)
out["rosfree_run_s"] = med(free, "wall_time_s")
out["ros_run_s"] = med(ros, "run_wall_time_s")
out["rosfree_realtime_x"] = round(out["sim_time_s_rosfree"] / out["rosfree_run_s"], 1)
out["ros_realtime_x"] = round(out["sim_time_s_ros"] / out["ros_run_s"], 1)
out["speedup"] = round(out["ros_run_s"] / out["rosfree_run_s"], 1)
print(json.dumps(out))
PY
