#!/usr/bin/env bash
# Fuzz smoke run: each CAN decoder fuzz target (scripts/fuzz candump|frame) for a short fixed time with ASan+UBSan.
# Longer runs: scripts/fuzz candump 3600. Env: TEST_RESULTS_DIR, WS, CAN_FUZZ_SECONDS (default 15 per target).
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env can-fuzz
fuzz_smoke can_fuzz "${CAN_FUZZ_SECONDS:-15}" candump frame
junit_write can_fuzz "$out/can_fuzz.xml"
