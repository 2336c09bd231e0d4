#!/usr/bin/env bash
# Fuzz smoke run of the SeaTrac codec (scripts/fuzz usbl) for a short fixed time with ASan + UBSan; the long run
# is `scripts/fuzz usbl 3600`. Env: TEST_RESULTS_DIR, WS, USBL_FUZZ_SECONDS (default 20).
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env usbl-fuzz
fuzz_smoke usbl_fuzz "${USBL_FUZZ_SECONDS:-20}" usbl
junit_write usbl_fuzz "$out/usbl_fuzz.xml"
