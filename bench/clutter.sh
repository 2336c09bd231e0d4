# No target in the moderate sea's clutter: config/scenarios/no_target.yaml ROS-free over 20 seeds (issue 32), false targets reported
# Usage: ./scripts/bench clutter [--scenario FILE] [--seeds N] [--sea-state NAME]  (default: moderate, whatever the
# scenario's own sea state)
# The surface, a bottom 7 m down, the buoy's mooring line and volume clutter all echo in the AUV's sonar; whitecaps
# and spray in the USV's LiDAR. Each seed draws every sensor's noise and clutter anew (mission_rosfree --seed S).
# Last line: one JSON object: runs, runs that reported a target, outcomes.
set -euo pipefail
scenario="$REPO/config/scenarios/no_target.yaml"
seeds=20
sea=moderate
while [ $# -gt 0 ]; do
  case "$1" in
    --scenario) scenario="$(realpath "$2")"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --sea-state) sea="$2"; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
# the scenario as it is, in the sea state asked for (its own line replaced, or one added)
if grep -q '^sea_state:' "$scenario"; then
  sed "s/^sea_state:.*/sea_state: $sea/" "$scenario" > "$tmp/scenario.yaml"
else
  { cat "$scenario"; echo "sea_state: $sea"; } > "$tmp/scenario.yaml"
fi
for i in $(seq 1 "$seeds"); do
  "$WS/devel/lib/offshore_gnc/mission_rosfree" --scenario "$tmp/scenario.yaml" --config "$REPO/config" --seed "$i" > "$tmp/$i.json" || true
  printf 'seed %2d: %s\n' "$i" "$(tail -n 1 "$tmp/$i.json" | cut -c1-150)"
done
/usr/bin/python3 - "$tmp" "$seeds" "$scenario" "$sea" <<'PY'
import json, os, sys
tmp, n, scenario, sea = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
runs = [json.loads(open(os.path.join(tmp, "%d.json" % i)).read().splitlines()[-1]) for i in range(1, n + 1)]
outcomes = {}
for r in runs:
    outcomes[r["outcome"]] = outcomes.get(r["outcome"], 0) + 1
found = [i + 1 for i, r in enumerate(runs) if r.get("detection_time_s") is not None]  # a detection confirmed
print(json.dumps({"scenario": os.path.basename(scenario), "sea_state": sea, "runs": n, "runs_with_a_target": len(found),
                  "seeds_with_a_target": found, "outcomes": outcomes}))
PY
