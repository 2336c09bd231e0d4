#!/usr/bin/env bash
# Fuzzes the CAN decoders with libFuzzer (clang, AddressSanitizer + UndefinedBehaviorSanitizer).
#   scripts/can-fuzz.sh [SECONDS_PER_TARGET=300] [OUT_DIR=.ws-fuzz-can]
# Targets: src/can/candump_fuzz.cpp (candump text -> can_decode's decoders), src/can/frame_fuzz.cpp (binary
# frames -> NMEA 2000 / waterjet decoders, bus monitor, gateway policy, emulator). Crashes are written to
# OUT_DIR/<target>/crash-*; the corpus grows in OUT_DIR/<target>/corpus (keep it between runs).
# Needs clang and libclang-rt-14-dev (scripts/packages.txt). Exit status non-zero on a crash.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
secs="${1:-300}"
out="${2:-$REPO/.ws-fuzz-can}"
CXX="${CLANGXX:-$(command -v clang++ || command -v clang++-14 || true)}"
[ -n "$CXX" ] || { echo "can-fuzz: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2; exit 2; }
mkdir -p "$out"
core=(frame nmea2000 waterjet_protocol decode emulator gateway socket_can)
flags=(-std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -I"$REPO/include")
rc=0
for t in candump frame; do
  bin="$out/${t}_fuzz"
  srcs=("$REPO/src/can/${t}_fuzz.cpp")
  for c in "${core[@]}"; do srcs+=("$REPO/src/can/$c.cpp"); done
  newest="$(ls -t "${srcs[@]}" "$REPO"/include/offshore_gnc/can/*.h | head -n1)"
  if [ ! -x "$bin" ] || [ "$newest" -nt "$bin" ]; then
    "$CXX" "${flags[@]}" "${srcs[@]}" -lsocketcan -o "$bin"
  fi
  mkdir -p "$out/$t/corpus"
  # Seeds: valid frames of every kind, so the fuzzer starts inside the decoders instead of at the checksum.
  if [ "$t" = candump ]; then
    for l in "(1700000000.000000) can0 09F80102#F8A1A024F073240E" "can0 09F11240#055C3DFF7FF4FDFC" \
             "can0 09F80240#09FCB87A0101FFFF" "can0 0CFF1020#803EC0E0007D030E" "can0 10FF2030#3A070000000000B7" \
             "can0 20000040#0000000000000000" "can0 1F334455##1AABBCCDDEEFF00112233" "can0 123#R"; do
      printf '%s' "$l" > "$out/$t/corpus/seed-$(printf '%s' "$l" | md5sum | cut -c1-8)"
    done
  else
    printf '\x02\x01\xf8\x89\x08\xf8\xa1\xa0\x24\xf0\x73\x24\x0e' > "$out/$t/corpus/seed-pos"
    printf '\x40\x12\xf1\x89\x08\x05\x5c\x3d\xff\x7f\xf4\xfd\xfc' > "$out/$t/corpus/seed-hdg"
    printf '\x40\x00\x00\x20\x08\x00\x00\x00\x00\x00\x00\x00\x00' > "$out/$t/corpus/seed-busoff"
  fi
  echo "can-fuzz: $t for ${secs}s" >&2
  ( cd "$out/$t" && "$bin" -max_total_time="$secs" -max_len=128 -print_final_stats=1 corpus ) \
    > "$out/$t.log" 2>&1 || { rc=1; echo "can-fuzz: $t FAILED, see $out/$t.log" >&2; tail -n 30 "$out/$t.log" >&2; }
  grep -E "^stat::number_of_executed_units|^#[0-9]+.*DONE" "$out/$t.log" | tail -n 2 >&2 || true
done
exit $rc
