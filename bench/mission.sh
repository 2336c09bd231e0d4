# The whole co-operative mission ROS-free in one process (mission_rosfree) vs the ROS mission (./scripts/mission), same scenario and seeds
# Usage: ./scripts/bench mission [--scenario FILE] [--auv-model girona500|acolor] [--runs N]
# Prints both runs' figures and one JSON line: usv_rmse_m_rosfree, usv_rmse_m_ros, auv_rmse_m_rosfree,
# auv_rmse_m_ros, rosfree_wall_s, ros_wall_s, the agreement (ratio ROS-free / ROS) and the speed-up.
set -euo pipefail
scenario="$REPO/config/scenarios/pyhajarvi.yaml"
model=girona500
runs=1
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
echo "ROS-free mission (mission_rosfree, one process):"
"$WS/devel/lib/offshore_gnc/mission_rosfree" --scenario "$scenario" --auv-model "$model" | tee "$tmp/rosfree.json"
for i in $(seq 1 "$runs"); do
  echo "ROS mission (./scripts/mission: two masters, the vehicles' stacks, shared lockstep clock), run $i of $runs:"
  /usr/bin/python3 "$REPO/python/offshore_gnc/mission_job.py" --scenario "$scenario" --auv-model "$model" --quiet \
    --out "$tmp/ros$i" | tail -n 2
done
/usr/bin/python3 - "$tmp" "$runs" <<'PY'
import json, sys, statistics
tmp, runs = sys.argv[1], int(sys.argv[2])
a = json.load(open(tmp + "/rosfree.json"))
ros = [json.load(open("%s/ros%d/metrics.json" % (tmp, i))) for i in range(1, runs + 1)]
def med(k):
    v = [r[k] for r in ros if r.get(k) is not None]
    return statistics.median(v) if v else None
out = {
    "usv_rmse_m_rosfree": a["usv_rmse_m"], "usv_rmse_m_ros": med("usv_rmse_m"),
    "auv_rmse_m_rosfree": a["auv_rmse_m"], "auv_rmse_m_ros": med("auv_rmse_m"),
    "target_error_m_rosfree": a["target_error_m"], "target_error_m_ros": med("target_error_m"),
    "sim_time_s_rosfree": a["sim_time_s"], "sim_time_s_ros": med("sim_time_s"),
    "rosfree_wall_s": a["wall_time_s"], "ros_wall_s": med("wall_time_s"),
    "success_rosfree": a["success"], "success_ros": all(r["success"] for r in ros), "ros_runs": runs,
}
def ratio(x, y):
    return round(x / y, 3) if x is not None and y else None
out["usv_rmse_ratio"] = ratio(out["usv_rmse_m_rosfree"], out["usv_rmse_m_ros"])
out["auv_rmse_ratio"] = ratio(out["auv_rmse_m_rosfree"], out["auv_rmse_m_ros"])
out["speedup"] = ratio(out["ros_wall_s"], out["rosfree_wall_s"])
print(json.dumps(out))
PY
