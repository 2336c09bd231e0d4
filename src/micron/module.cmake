# micron: the SeaNet codec and the driver session (core); the MicronSonar nodelet on a serial line (the serial
# module); the capture decoder CLI. No simulator here: the emulator is micron_sim. The libFuzzer target
# test/fuzz/micron.cpp (codec, driver and emulator) is built with clang by scripts/fuzz micron, not here.
offshore_gnc_tool(micron_decode SOURCES src/micron/micron_decode_main.cpp)
