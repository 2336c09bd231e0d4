# Vehicle models alone: real-time factor of the USV (3-DOF and Nomoto) and AUV (Girona500, aColor) models at dt 0.01 s.
set -euo pipefail
cd "$REPO"
"$WS/devel/lib/offshore_gnc/models_bench" "${1:-600}"
