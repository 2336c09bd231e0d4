# sim: scenario files (yaml-cpp) and map images (OpenCV) in the ROS-free core; the benchmark tool and the
# scenario check the main job runs before it starts anything.
find_package(yaml-cpp REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs)
target_include_directories(offshore_gnc_sim SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS})
target_link_libraries(offshore_gnc_sim PUBLIC yaml-cpp opencv_core opencv_imgproc opencv_imgcodecs)
offshore_gnc_tool(sim_bench SOURCES src/sim/sim_bench.cpp)
offshore_gnc_tool(scenario_check SOURCES src/sim/scenario_check_main.cpp)
offshore_gnc_tool(sim_log SOURCES src/sim/sim_log_main.cpp)
offshore_gnc_tool(radio_params SOURCES src/sim/radio_params_main.cpp)
