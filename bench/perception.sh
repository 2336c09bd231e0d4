# LiDAR targets (MRS1000 4x1100 and dense 128x1024 frames) vs PCL EuclideanClusterExtraction, and one sonar sweep
set -euo pipefail
# One core, as the figures are stated for one core.
exec taskset -c 0 "$WS/devel/lib/offshore_gnc/perception_bench" "$@"
