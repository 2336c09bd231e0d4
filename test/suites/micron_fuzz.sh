#!/usr/bin/env bash
# Fuzz smoke run of the SeaNet codec + Micron driver + emulator (scripts/fuzz-micron) for a short fixed time with
# ASan + UBSan; the long run is `scripts/fuzz-micron 3600`. Env: TEST_RESULTS_DIR, WS, MICRON_FUZZ_SECONDS (20).
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env micron-fuzz
secs="${MICRON_FUZZ_SECONDS:-20}"
"$REPO/scripts/fuzz-micron" "$secs" "$work" > "$work/suite.log" 2>&1; rc=$?
junit_fuzz micron_fuzz codec_session_fuzz "$rc" "$work/fuzz.log" "$secs"
junit_write micron_fuzz "$out/micron_fuzz.xml"
