# micron: the SeaNet codec, driver session and head emulator (core); MicronSonar / MicronEmulator nodelets; the
# capture decoder CLI. Needs usbl (the reconnecting serial line) and sim (the emulator draws beams with the
# simulator's sonar model). The libFuzzer target src/micron/micron_fuzz.cpp is built with clang by
# scripts/fuzz-micron, not here.
foreach(dep usbl sim)
  if(NOT dep IN_LIST OFFSHORE_GNC_MODULES)
    message(FATAL_ERROR "module micron needs module ${dep} (OFFSHORE_GNC_MODULES=${OFFSHORE_GNC_MODULES})")
  endif()
endforeach()
offshore_gnc_tool(micron_decode SOURCES src/micron/micron_decode_main.cpp)
