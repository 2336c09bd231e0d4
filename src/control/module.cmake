# control: closed-loop benchmark (uses the sim module's plants; build with --modules "sim guidance control").
offshore_gnc_tool(tracking_bench SOURCES src/control/tracking_bench.cpp)
