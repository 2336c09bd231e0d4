#!/usr/bin/env bash
# Fuzz smoke runs of the relay (ASan + UBSan): frames, HMAC and zlib (scripts/fuzz relay_wire), and a hostile peer
# against a real engine (scripts/fuzz relay_session). Long runs: scripts/fuzz relay_session 3600.
# Env: TEST_RESULTS_DIR, WS, RELAY_FUZZ_SECONDS (default 15 per target).
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env relay-fuzz
fuzz_smoke relay_fuzz "${RELAY_FUZZ_SECONDS:-15}" relay_wire relay_session
junit_write relay_fuzz "$out/relay_fuzz.xml"
