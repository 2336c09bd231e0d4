# Simulator real-time factors (USV alone, AUV alone, both with all sensors at real rates, one core).
set -euo pipefail
cd "$REPO"
"$WS/devel/lib/offshore_gnc/sim_bench" config/scenarios/pyhajarvi_map.yaml "${1:-120}"
