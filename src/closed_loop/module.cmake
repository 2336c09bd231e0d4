# closed_loop: the ROS-free loops built from the classes the nodelets run; the tracking benchmark.
offshore_gnc_tool(tracking_bench SOURCES src/closed_loop/tracking_bench.cpp)
