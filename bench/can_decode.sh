# can_decode throughput on a synthetic 200k-line candump log vs a plain Python decoder of the same frames
# Baseline: what a user without our tool writes (Python 3 stdlib: regex + struct; NMEA 2000 PGNs only, so it
# skips the waterjet frames that can_decode checks (CRC) and decodes: its object count is lower).
set -euo pipefail
WS="${WS:-$REPO/build/.ws}"
bin="$WS/devel/lib/offshore_gnc/can_decode"
[ -x "$bin" ] || { echo "can_decode not built in $WS" >&2; exit 1; }
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
n=200000
/usr/bin/python3 - "$tmp/log" "$n" <<'PY'
import sys
frames = ["09F80140#F8A1A024F073240E", "09F11240#055C3DFF7FF4FDFC", "09F80240#09FCB87A0101FFFF",
          "0CFF1020#803EC0E0007D030E", "18EEFF05#0102030405060708"]
with open(sys.argv[1], "w") as f:
    for i in range(int(sys.argv[2])):
        f.write("(%.6f) can0 %s\n" % (1700000000 + i * 0.001, frames[i % len(frames)]))
PY
cat > "$tmp/baseline.py" <<'PY'
import json, re, struct, sys
line_re = re.compile(r"\(([0-9.]+)\)\s+(\S+)\s+([0-9A-Fa-f]{8})#([0-9A-Fa-f]*)")
out = sys.stdout
for line in open(sys.argv[1]):
    m = line_re.match(line)
    if not m:
        continue
    cid = int(m.group(3), 16); data = bytes.fromhex(m.group(4))
    pf = (cid >> 16) & 0xFF
    pgn = ((cid >> 8) & 0x3FF00) if pf < 240 else ((cid >> 8) & 0x3FFFF)
    d = {"t": float(m.group(1)), "pgn": pgn, "source": cid & 0xFF}
    if pgn == 129025 and len(data) == 8:
        lat, lon = struct.unpack("<ii", data); d.update(latitude_deg=lat * 1e-7, longitude_deg=lon * 1e-7)
    elif pgn == 127250 and len(data) == 8:
        sid, hdg, dev, var, ref = struct.unpack("<BHhhB", data); d.update(heading_rad=hdg * 1e-4)
    elif pgn == 129026 and len(data) == 8:
        sid, ref, cog, sog, _ = struct.unpack("<BBHHH", data); d.update(cog_rad=cog * 1e-4, sog_mps=sog * 1e-2)
    else:
        continue
    out.write(json.dumps(d) + "\n")
PY
t() { local s e; s=$(date +%s.%N); "$@" > "$tmp/out" 2>/dev/null; e=$(date +%s.%N); echo "$e - $s" | bc -l; }
ours=$(t "$bin" "$tmp/log"); ours_lines=$(wc -l < "$tmp/out")
base=$(t /usr/bin/python3 "$tmp/baseline.py" "$tmp/log"); base_lines=$(wc -l < "$tmp/out")
echo "can_decode: $ours_lines objects in ${ours}s; python baseline: $base_lines objects in ${base}s" >&2
printf '{"bench":"can_decode","lines":%d,"can_decode_s":%.3f,"can_decode_lines_per_s":%.0f,"python_baseline_s":%.3f,"python_lines_per_s":%.0f,"can_decode_objects":%d,"python_objects":%d}\n' \
  "$n" "$ours" "$(echo "$n / $ours" | bc -l)" "$base" "$(echo "$n / $base" | bc -l)" "$ours_lines" "$base_lines"
