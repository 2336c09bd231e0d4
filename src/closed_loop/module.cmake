# closed_loop: the ROS-free loops built from the classes the nodelets run; the tracking benchmark and the
# whole mission in one process (both read the vehicles' configuration files from config/).
offshore_gnc_tool(tracking_bench SOURCES src/closed_loop/tracking_bench.cpp)
offshore_gnc_tool(mission_rosfree SOURCES src/closed_loop/mission_rosfree_main.cpp)
target_compile_definitions(mission_rosfree PRIVATE OFFSHORE_GNC_CONFIG_DIR="${PROJECT_SOURCE_DIR}/config")
# the main job's report judges its run with the same code (closed_loop/outcome.h, sim/contact.h)
offshore_gnc_tool(mission_outcome SOURCES src/closed_loop/mission_outcome_main.cpp)
target_compile_definitions(mission_outcome PRIVATE OFFSHORE_GNC_CONFIG_DIR="${PROJECT_SOURCE_DIR}/config")
# perception_bench: our extractor against PCL's EuclideanClusterExtraction on synthetic frames and a harbour frame
# from the simulator's MRS1000 ray caster; PCL only here, so no other file pays its compile time.
find_package(PCL QUIET COMPONENTS common search kdtree segmentation)
if(PCL_FOUND)
  offshore_gnc_tool(perception_bench SOURCES src/closed_loop/perception_bench.cpp LIBS ${PCL_LIBRARIES})
  target_include_directories(perception_bench SYSTEM PRIVATE ${PCL_INCLUDE_DIRS} ${PROJECT_SOURCE_DIR}/test/support)
  target_compile_definitions(perception_bench PRIVATE ${PCL_DEFINITIONS})
else()
  message(WARNING "closed_loop: PCL not found, perception_bench (PCL baseline) not built")
endif()
offshore_gnc_tool(notch_bench SOURCES src/closed_loop/notch_bench.cpp)
