# Campaign throughput on the local cores beside the same runs one after another (missions/s), each mission's real-time factor
# Usage: ./scripts/bench campaign [--spec FILE] [--missions N] [--jobs J]
# The spec's first N runs (default: the envelope's first 20, missions of the default scenario's size: its 40 x 20 m
# search area), once J at a time (default: every core) and once sequentially, in the same run of this script. Each
# figure is the campaign's own (runs over the wall time of the running, scenario generation and report excluded); a
# mission's real-time factor is its simulated over its wall time (mission_rosfree's sim_time_s / wall_time_s). Both
# passes must give the same records (runs are pure functions of spec and index). Last line: one JSON object.
set -euo pipefail
spec="$REPO/config/campaigns/envelope.yaml"
missions=20
jobs="$(nproc)"
while [ $# -gt 0 ]; do
  case "$1" in
    --spec) spec="$(realpath "$2")"; shift 2 ;;
    --missions) missions="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
export PYTHONPATH="$REPO/python${PYTHONPATH:+:$PYTHONPATH}"
for pass in parallel:"$jobs" sequential:1; do
  echo "${pass%%:*}: $missions missions of $(basename "$spec"), ${pass##*:} at a time ..."
  rc=0
  /usr/bin/python3 -m offshore_gnc.campaign "$spec" --missions "$missions" --jobs "${pass##*:}" --quiet \
    --out "$tmp/${pass%%:*}" > "$tmp/${pass%%:*}.out" || rc=$?
  [ $rc -le 1 ] || { cat "$tmp/${pass%%:*}.out" >&2; exit 1; }  # 1: some runs could not run, still timed
  tail -n 1 "$tmp/${pass%%:*}.out" | cut -c1-200
done
/usr/bin/python3 - "$tmp" "$jobs" <<'PY'
import json, statistics, sys
from offshore_gnc.campaign import runs
tmp, jobs = sys.argv[1], int(sys.argv[2])
last = {p: json.loads(open("%s/%s.out" % (tmp, p)).read().strip().splitlines()[-1]) for p in ("parallel", "sequential")}
recs = {p: runs.Store("%s/%s" % (tmp, p)).records(10 ** 9) for p in last}
def rtf(p):
    return [r["result"]["sim_time_s"] / r["result"]["wall_time_s"] for r in recs[p]
            if r["result"] and r["result"].get("wall_time_s")]
par, seq = last["parallel"]["missions_per_s"], last["sequential"]["missions_per_s"]
out = {"missions": last["parallel"]["missions"], "jobs": jobs,
       "parallel_missions_per_s": par, "sequential_missions_per_s": seq, "speedup": round(par / seq, 2),
       "sim_time_s_total": round(sum(r["result"]["sim_time_s"] for r in recs["sequential"] if r["result"]), 1)}
for p in ("parallel", "sequential"):
    x = rtf(p)
    out.update({"rtf_median_%s" % p: round(statistics.median(x), 1), "rtf_min_%s" % p: round(min(x), 1),
                "rtf_max_%s" % p: round(max(x), 1)})
out["identical_records"] = [runs.comparable(r) for r in recs["parallel"]] == [runs.comparable(r) for r in recs["sequential"]]
print(json.dumps(out))
PY
