# SeaTrac decoder throughput (frames/s): this C++ codec vs a plain Python decoder of the same frames (what a ROS user of a Python SeaTrac driver gets), same stream.
set -euo pipefail
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cpp="$("$WS/devel/lib/offshore_gnc/usbl_bench" "$tmp/stream.bin")"
echo "$cpp"
/usr/bin/python3 - "$tmp/stream.bin" "$cpp" <<'PY'
import binascii, json, sys, time
# Table-driven CRC-16/ARC and line framing, as a Python driver does it; fields are not unpacked (a lower bound
# on the Python cost).
T = []
for i in range(256):
    c = i
    for _ in range(8):
        c = (c >> 1) ^ 0xA001 if c & 1 else c >> 1
    T.append(c)
def crc(b):
    c = 0
    for x in b:
        c = (c >> 8) ^ T[(c ^ x) & 0xFF]
    return c
data = open(sys.argv[1], "rb").read()
t0 = time.perf_counter()
ok = 0
for line in data.split(b"\r\n"):
    if len(line) < 7 or line[:1] not in (b"#", b"$"):
        continue
    b = binascii.unhexlify(line[1:])
    if crc(b[:-2]) == b[-2] | b[-1] << 8:
        ok += 1
s = time.perf_counter() - t0
r = json.loads(sys.argv[2])
assert ok == r["frames"], (ok, r["frames"])
py = ok / s
print(json.dumps({"cpp_frames_per_s": r["cpp_frames_per_s"], "python_frames_per_s": round(py),
                  "speedup": round(r["cpp_frames_per_s"] / py, 1), "cpp_mb_per_s": r["cpp_mb_per_s"]}))
PY
