#!/usr/bin/env bash
# Fuzz smoke run of the SeaNet codec + Micron driver + emulator (scripts/fuzz micron) with ASan + UBSan; the long
# run is `scripts/fuzz micron 3600`. Env: TEST_RESULTS_DIR, WS, MICRON_FUZZ_SECONDS (default 20).
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env micron-fuzz
fuzz_smoke micron_fuzz "${MICRON_FUZZ_SECONDS:-20}" micron
junit_write micron_fuzz "$out/micron_fuzz.xml"
