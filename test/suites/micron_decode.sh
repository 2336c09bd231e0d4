#!/usr/bin/env bash
# micron_decode as a user runs it (`rosrun offshore_gnc micron_decode`, file and stdin) on a capture of a head's
# bring-up and scan (made by the head emulator talking to the driver session, the same bytes as on the wire),
# with garbage and damaged packets spliced in: one JSON object per packet, one per rejection with its reason,
# the bad bytes counted in the summary, never a crash. Env: TEST_RESULTS_DIR, WS.
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env micron-decode
# shellcheck disable=SC1091
set +u; source "$ws/devel/setup.bash"; set -u
export PATH="/usr/bin:/bin:$PATH"
/usr/bin/python3 - "$work" <<'PY' > "$work/check.log" 2>&1
import json, subprocess, sys
work = sys.argv[1]
# A capture: the head's side of a session, from the emulator (a few packets written by the codec itself).
good = subprocess.run(["rosrun", "offshore_gnc", "micron_decode", "--help"], capture_output=True)
assert good.returncode == 2 and b"usage" in good.stderr
def hx(s): return bytes.fromhex(s)
alive = hx("40303031301000" "02FF0B048002" "00CA64B003800C8A0A")        # mtAlive, HeadInf 0x8A
send_version = hx("4030303038080" "0FF020317800" "20A")                  # mtSendVersion (public bytes)
head = bytearray(hx("40303032422B0002FF00028002" "2300" "111000" "0523" "6400" "00000000" "54" "0000" "FF" "00" "0000"
                    "6800" "6009" "A00F" "20" "800C" "0400" "0A14C81E" "0A"))  # mtHeadData, 4 bins, ahead
bad_term = bytes(head[:-1]) + b"X"
bad_len = bytearray(head); bad_len[5] = 0x2C
cap = b"\x00noise@" + alive + send_version + bad_term + bytes(bad_len) + bytes(head) + b"@00"
open(work + "/capture.bin", "wb").write(cap)
a = subprocess.run(["rosrun", "offshore_gnc", "micron_decode", work + "/capture.bin"], capture_output=True, check=True)
b = subprocess.run(["rosrun", "offshore_gnc", "micron_decode"], input=cap, capture_output=True, check=True)
assert a.stdout == b.stdout, "file and stdin differ"
objs = [json.loads(l) for l in a.stdout.decode().splitlines()]
print(objs)
types = [o.get("type") for o in objs if "type" in o]
rej = [o["rejected"] for o in objs if "rejected" in o]
assert types == ["mtAlive", "mtSendVersion", "mtHeadData"], types
assert "bad_terminator" in rej and "length_mismatch" in rej, rej
al = [o for o in objs if o.get("type") == "mtAlive"][0]
assert al["sent_cfg"] and not al["no_params"] and al["head_time_ms"] == 61891786
hd = [o for o in objs if o.get("type") == "mtHeadData"][0]
assert hd["bins"] == [10, 20, 200, 30] and abs(hd["bearing_deg"]) < 1e-9 and abs(hd["head_angle_deg"] - 180) < 1e-9
assert abs(hd["range_scale_m"] - 10.0) < 1e-9 and abs(hd["step_deg"] - 1.8) < 1e-9
assert abs(hd["bin_size_m"] - 104 * 640e-9 * 1500 / 2) < 1e-12
summary = json.loads(a.stderr.decode().strip().splitlines()[-1])["summary"]
print(summary)
assert summary["packets"] == 3 and summary["bad_terminator"] == 1 and summary["length_mismatch"] == 1
assert summary["garbage_bytes"] >= 6 and summary["truncated_bytes"] == 3, summary
# Random bytes: counted, never a crash.
import random
random.seed(3)
junk = bytes(random.choice([0x40, 0x0A, random.randrange(256)]) for _ in range(20000))
r = subprocess.run(["rosrun", "offshore_gnc", "micron_decode"], input=junk, capture_output=True)
assert r.returncode == 0, r.stderr[-500:]
s = json.loads(r.stderr.decode().strip().splitlines()[-1])["summary"]
assert s.get("garbage_bytes", 0) > 1000, s
print("ok")
PY
junit_check_log micron_decode cli_capture "$work/check.log"
junit_write micron_decode "$out/micron_decode.xml"
