# closed_loop: the ROS-free loops built from the classes the nodelets run; the tracking benchmark and the
# whole mission in one process (both read the vehicles' configuration files from config/).
offshore_gnc_tool(tracking_bench SOURCES src/closed_loop/tracking_bench.cpp)
offshore_gnc_tool(mission_rosfree SOURCES src/closed_loop/mission_rosfree_main.cpp)
target_compile_definitions(mission_rosfree PRIVATE OFFSHORE_GNC_CONFIG_DIR="${PROJECT_SOURCE_DIR}/config")
offshore_gnc_tool(param_docs SOURCES src/closed_loop/param_docs_main.cpp)
