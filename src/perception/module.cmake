# perception: OpenCV (core, imgproc) for the Cartesian sonar image in the core. The benchmark against PCL lives in
# closed_loop (its harbour frame comes from the simulator's LiDAR, a layer above).
find_package(OpenCV REQUIRED COMPONENTS core imgproc)
target_include_directories(offshore_gnc_perception SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS})
target_link_libraries(offshore_gnc_perception PUBLIC opencv_core opencv_imgproc)

