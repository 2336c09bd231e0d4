# shellcheck shell=bash
# Shared by test/suites/*.sh: JUnit XML that catkin_test_results counts, and the suites' common set-up.
# Source it; then
#   suite_env DIR              REPO, out (= $TEST_RESULTS_DIR), ws (= $WS or build/.ws), work (= $ws/DIR)
#   junit_case CLASS NAME [pass|fail|skip] [MESSAGE] [SECONDS] [OUTPUT]
#   junit_fuzz CLASS NAME RC LIBFUZZER_LOG SECONDS     pass when libFuzzer ran > 1000 inputs and exited 0
#   fuzz_smoke CLASS SECONDS TARGET...                 scripts/fuzz TARGET SECONDS $work/TARGET, one case each
#   junit_check_log CLASS NAME LOG                     pass when the log's last line is "ok"
#   junit_cannot_run CLASS NAME REASON   the real part cannot run here: a failure naming REASON, or a skip
#                                        when the user set OFFSHORE_GNC_ALLOW_SKIP=1 (README; CI never does)
#   junit_write SUITE FILE     writes the cases so far, starts a new suite; non-zero status on any failure
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
JUNIT_CASES="" JUNIT_TESTS=0 JUNIT_FAILS=0 JUNIT_SKIPS=0

suite_env() {
  out="${TEST_RESULTS_DIR:?TEST_RESULTS_DIR not set}"
  ws="${WS:-$REPO/build/.ws}"
  work="$ws/$1"
  mkdir -p "$out" "$work"
}

junit_escape() { printf '%s' "$1" | tr '\n' ' ' | sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' -e 's/"/\&quot;/g'; }

junit_case() {
  local msg time="" body=""
  msg="$(junit_escape "${4:-}")"
  [ -n "${5:-}" ] && time=" time=\"$5\""
  [ -n "${6:-}" ] && body="<system-out>$(junit_escape "$6")</system-out>"
  case "${3:-pass}" in
    fail) body="<failure message=\"$msg\"/>$body"; JUNIT_FAILS=$((JUNIT_FAILS + 1)) ;;
    skip) body="<skipped message=\"$msg\"/>"; JUNIT_SKIPS=$((JUNIT_SKIPS + 1)) ;;
  esac
  JUNIT_TESTS=$((JUNIT_TESTS + 1))
  JUNIT_CASES="$JUNIT_CASES<testcase classname=\"$1\" name=\"$2\"$time>$body</testcase>"
}

junit_fuzz() {
  local execs
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$4" 2>/dev/null | tail -n1)"
  echo "$1: $2: ${execs:-0} inputs in ${5}s" >&2
  if [ "$3" = 0 ] && [ -n "$execs" ] && [ "$execs" -gt 1000 ]; then
    junit_case "$1" "$2" pass "" "$5" "$execs inputs"
  else
    junit_case "$1" "$2" fail "fuzz run failed (rc $3) or too few inputs (${execs:-0}); see $4"
  fi
}

fuzz_smoke() {
  local class="$1" secs="$2" t rc
  shift 2
  for t in "$@"; do
    "$REPO/scripts/fuzz" "$t" "$secs" "$work/$t" > "$work/$t.out" 2>&1 && rc=0 || rc=$?
    junit_fuzz "$class" "${t}_fuzz" "$rc" "$work/$t/fuzz.log" "$secs"
  done
}

junit_check_log() {
  if tail -n1 "$3" | grep -qx ok; then
    junit_case "$1" "$2" pass
  else
    junit_case "$1" "$2" fail "$(tail -n 3 "$3")"
  fi
  cat "$3" >&2
}

junit_cannot_run() {
  if [ "${OFFSHORE_GNC_ALLOW_SKIP:-0}" = 1 ]; then
    echo "!!! skipped (OFFSHORE_GNC_ALLOW_SKIP=1): $1.$2: $3" >&2
    junit_case "$1" "$2" skip "$3"
  else
    echo "!!! FAILED: $1.$2 cannot run: $3 (OFFSHORE_GNC_ALLOW_SKIP=1 turns this into a skip)" >&2
    junit_case "$1" "$2" fail "cannot run: $3"
  fi
}

junit_write() {
  local fails=$JUNIT_FAILS
  printf '<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="%s" tests="%d" failures="%d" errors="0" skipped="%d">%s</testsuite>\n' \
    "$1" "$JUNIT_TESTS" "$JUNIT_FAILS" "$JUNIT_SKIPS" "$JUNIT_CASES" > "$2"
  JUNIT_CASES="" JUNIT_TESTS=0 JUNIT_FAILS=0 JUNIT_SKIPS=0
  [ "$fails" = 0 ]
}
