# micron: the SeaNet codec, driver session and head emulator (core); MicronSonar / MicronEmulator nodelets; the
# capture decoder CLI. Uses usbl (the reconnecting serial line, pseudo-terminals) and sim (the emulator draws
# beams with the simulator's sonar model): the module graph in CMakeLists.txt says so. The libFuzzer target test/fuzz/micron.cpp is built with clang by
# scripts/fuzz micron, not here.
offshore_gnc_tool(micron_decode SOURCES src/micron/micron_decode_main.cpp)
