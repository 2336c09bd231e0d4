# LiDAR targets (MRS1000-size, dense 128x1024 and simulated harbour frames) vs PCL 3-D Euclidean clustering and organised segmentation, and one sonar sweep
set -euo pipefail
# One core, as the figures are stated for one core.
exec taskset -c 0 "$WS/devel/lib/offshore_gnc/perception_bench" "$@"
