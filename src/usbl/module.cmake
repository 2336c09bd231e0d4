# usbl: the capture decoder CLI (ROS-free). The libFuzzer target test/fuzz/usbl.cpp is built with clang by
# `scripts/fuzz usbl` (the project compiler is g++), not here.
offshore_gnc_tool(usbl_decode SOURCES src/usbl/usbl_decode_main.cpp)
offshore_gnc_tool(usbl_bench SOURCES src/usbl/usbl_bench.cpp)
