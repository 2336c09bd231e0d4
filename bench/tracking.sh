# Closed-loop path following with 0.2 m/s cross current: cross-track RMSE/SD/MAE with and without crab compensation
set -euo pipefail
"$WS/devel/lib/offshore_gnc/tracking_bench" "$@"
