# Notch filters in the USV's loop on a moderate sea: wave-band power of the yaw command and cross-track, none / thesis / on the wave band
set -euo pipefail
"$WS/devel/lib/offshore_gnc/notch_bench" "$@"
