#!/usr/bin/env bash
# Fuzz smoke run: each CAN decoder fuzz target (scripts/can-fuzz.sh) for a short fixed time with ASan+UBSan.
# Longer runs: scripts/can-fuzz.sh 3600. Env: TEST_RESULTS_DIR, WS, CAN_FUZZ_SECONDS (default 15 per target).
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env can-fuzz
secs="${CAN_FUZZ_SECONDS:-15}"
"$REPO/scripts/can-fuzz.sh" "$secs" "$work" > "$work/suite.log" 2>&1; rc=$?
for t in candump frame; do
  junit_fuzz can_fuzz "${t}_fuzz" "$rc" "$work/$t.log" "$secs"
done
junit_write can_fuzz "$out/can_fuzz.xml"
