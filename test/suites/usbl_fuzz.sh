#!/usr/bin/env bash
# Fuzz smoke run of the SeaTrac codec (scripts/fuzz-usbl) for a short fixed time with ASan + UBSan; the long run
# is `scripts/fuzz-usbl 3600`. Env: TEST_RESULTS_DIR, WS, USBL_FUZZ_SECONDS (default 20).
set -uo pipefail
REPO="$(cd "$(dirname "$0")/../.." && pwd)"
out="${TEST_RESULTS_DIR:?TEST_RESULTS_DIR not set}"
secs="${USBL_FUZZ_SECONDS:-20}"
work="${WS:-$REPO/build/.ws}/usbl-fuzz"
mkdir -p "$out" "$work"
"$REPO/scripts/fuzz-usbl" "$secs" "$work" > "$work/suite.log" 2>&1; rc=$?
execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/fuzz.log" 2>/dev/null | tail -n1)"
if [ $rc = 0 ] && [ -n "$execs" ] && [ "$execs" -gt 1000 ]; then
  case="<testcase classname=\"usbl_fuzz\" name=\"codec_fuzz\" time=\"$secs\"><system-out>$execs inputs</system-out></testcase>"; fails=0
else
  case="<testcase classname=\"usbl_fuzz\" name=\"codec_fuzz\"><failure message=\"fuzz run failed (rc $rc) or too few inputs (${execs:-0}); see $work/fuzz.log\"/></testcase>"; fails=1
fi
echo "usbl_fuzz: ${execs:-0} inputs in ${secs}s" >&2
printf '<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="usbl_fuzz" tests="1" failures="%d" errors="0" skipped="0">%s</testsuite>\n' \
  "$fails" "$case" > "$out/usbl_fuzz.xml"
[ $fails = 0 ]
