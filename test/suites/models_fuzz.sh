#!/usr/bin/env bash
# Fuzz smoke run of the model parameter loaders (scripts/fuzz model_params, ASan + UBSan); long run:
# scripts/fuzz model_params 3600. Env: TEST_RESULTS_DIR, WS, MODELS_FUZZ_SECONDS (default 15).
set -uo pipefail
source "$(dirname "$0")/lib/junit.sh"
suite_env models-fuzz
fuzz_smoke models_fuzz "${MODELS_FUZZ_SECONDS:-15}" model_params
junit_write models_fuzz "$out/models_fuzz.xml"
