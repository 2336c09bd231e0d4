# WGS84 -> local NED -> WGS84 round trips per second (GeographicLib), a baseline for the bench harness.
set -euo pipefail
"$WS/devel/lib/offshore_gnc/geo_bench" "$@"
