#!/usr/bin/env bash
# usbl_decode as a user runs it (`rosrun offshore_gnc usbl_decode`, file and stdin): a capture of good frames,
# garbage and damaged frames -> one JSON object per message in SI units, one per rejection with its reason.
# Env: TEST_RESULTS_DIR, WS.
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env usbl-decode
# shellcheck disable=SC1091
set +u; source "$ws/devel/setup.bash"; set -u
export PATH="/usr/bin:/bin:$PATH"
cap="$work/capture.bin"
{
  printf 'noise\x00\xff'
  printf '#40020680B6\r\n'            # PING_SEND to beacon 2 (public example)
  printf '$43340266D5\r\n'            # PING_ERROR timeout (public example)
  printf '$43340266D6\r\n'            # bad CRC
  printf '$4334026\r\n'               # odd hex length
  printf '$990102507E\r\n'            # unknown CID 0x99, valid CRC
} > "$cap"
cat "$REPO/test/suites/usbl_decode_resp.txt" >> "$cap"
/usr/bin/python3 - "$cap" "$work" <<'PY' > "$work/check.log" 2>&1
import json, subprocess, sys
cap, work = sys.argv[1], sys.argv[2]
a = subprocess.run(["rosrun", "offshore_gnc", "usbl_decode", cap], capture_output=True, check=True)
b = subprocess.run(["rosrun", "offshore_gnc", "usbl_decode"], input=open(cap, "rb").read(), capture_output=True, check=True)
assert a.stdout == b.stdout, "file and stdin differ"
objs = [json.loads(l) for l in a.stdout.decode().splitlines()]
cids = [o.get("cid") for o in objs]
rej = [o["rejected"] for o in objs if "rejected" in o]
print(cids, rej)
assert cids[:2] == ["PING_SEND", "PING_ERROR"], cids
assert objs[0]["dest_id"] == 2 and objs[1]["status_name"] == "XCVR_RESP_TIMEOUT"
assert rej[:2] == ["bad_crc", "odd_hex_length"], rej
assert rej[2] == "unknown_cid", rej
resp = [o for o in objs if o.get("cid") == "PING_RESP"]
assert len(resp) == 1, objs
r = resp[0]
assert abs(r["range_m"] - 100.0) < 1e-9 and abs(r["azimuth_deg"] - 45.0) < 1e-9 and abs(r["elevation_deg"] + 30.0) < 1e-9
assert abs(r["sound_speed_mps"] - 1500.0) < 1e-9 and abs(r["depth_m"] - 60.0) < 1e-9 and len(r["usbl_rssi_db"]) == 4
summary = json.loads(a.stderr.decode().strip().splitlines()[-1])["summary"]
assert summary["frames_ok"] == 3 and summary["bad_crc"] >= 1 and summary["garbage_bytes"] == 7, summary
print("ok")
PY
junit_check_log usbl_decode cli_capture "$work/check.log"
junit_write usbl_decode "$out/usbl_decode.xml"
