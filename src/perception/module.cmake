# perception: OpenCV (core, imgproc) for the Cartesian sonar image in the core; PCL only in the benchmark
# (the EuclideanClusterExtraction baseline), so no other file pays PCL's compile time.
find_package(OpenCV REQUIRED COMPONENTS core imgproc)
target_include_directories(offshore_gnc_perception SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS})
target_link_libraries(offshore_gnc_perception PUBLIC opencv_core opencv_imgproc)

find_package(PCL QUIET COMPONENTS common search kdtree segmentation)
if(PCL_FOUND)
  offshore_gnc_tool(perception_bench SOURCES src/perception/perception_bench.cpp LIBS ${PCL_LIBRARIES})
  target_include_directories(perception_bench SYSTEM PRIVATE ${PCL_INCLUDE_DIRS})
  target_compile_definitions(perception_bench PRIVATE ${PCL_DEFINITIONS})
else()
  message(WARNING "perception: PCL not found, perception_bench (PCL baseline) not built")
endif()
