#!/usr/bin/env bash
# Fuzz smoke run of the scenario loader (scripts/fuzz scenario, ASan + UBSan). Long run: scripts/fuzz scenario 3600.
# Env: TEST_RESULTS_DIR, WS, SIM_FUZZ_SECONDS (default 15).
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env sim-fuzz
fuzz_smoke sim_fuzz "${SIM_FUZZ_SECONDS:-15}" scenario
junit_write sim_fuzz "$out/sim_fuzz.xml"
