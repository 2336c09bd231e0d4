# sim: scenario files (yaml-cpp) and map images (OpenCV) in the ROS-free core; the benchmark tool.
find_package(yaml-cpp REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs)
target_include_directories(offshore_gnc_core SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS})
target_link_libraries(offshore_gnc_core PUBLIC yaml-cpp opencv_core opencv_imgproc opencv_imgcodecs)
offshore_gnc_tool(sim_bench SOURCES src/sim/sim_bench.cpp)
offshore_gnc_tool(sim_log SOURCES src/sim/sim_log_main.cpp)
