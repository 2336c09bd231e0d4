#!/usr/bin/env bash
# Fuzz smoke run: each CAN decoder fuzz target (scripts/can-fuzz.sh) for a short fixed time with ASan+UBSan.
# Longer runs: scripts/can-fuzz.sh 3600. Env: TEST_RESULTS_DIR, CAN_FUZZ_SECONDS (default 15 per target).
set -uo pipefail
REPO="$(cd "$(dirname "$0")/../.." && pwd)"
out="${TEST_RESULTS_DIR:?TEST_RESULTS_DIR not set}"
secs="${CAN_FUZZ_SECONDS:-15}"
work="${WS:-$REPO/build/.ws}/can-fuzz"
mkdir -p "$out" "$work"
"$REPO/scripts/can-fuzz.sh" "$secs" "$work" > "$work/suite.log" 2>&1; rc=$?
cases=""; fails=0
for t in candump frame; do
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/$t.log" 2>/dev/null | tail -n1)"
  if [ $rc = 0 ] && [ -n "$execs" ] && [ "$execs" -gt 1000 ]; then
    cases="$cases<testcase classname=\"can_fuzz\" name=\"${t}_fuzz\" time=\"$secs\"><system-out>$execs inputs</system-out></testcase>"
  else
    fails=$((fails + 1))
    cases="$cases<testcase classname=\"can_fuzz\" name=\"${t}_fuzz\"><failure message=\"fuzz run failed or too few inputs (${execs:-0}); see $work/$t.log\"/></testcase>"
  fi
  echo "can_fuzz: $t: ${execs:-0} inputs in ${secs}s" >&2
done
printf '<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="can_fuzz" tests="2" failures="%d" errors="0" skipped="0">%s</testsuite>\n' \
  "$fails" "$cases" > "$out/can_fuzz.xml"
[ $fails = 0 ]
