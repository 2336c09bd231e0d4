# relay: OpenSSL (HMAC-SHA256 frame authentication) and zlib (optional compression) in the ROS-free core.
find_package(OpenSSL REQUIRED)
find_package(ZLIB REQUIRED)
target_link_libraries(offshore_gnc_core PUBLIC OpenSSL::Crypto ZLIB::ZLIB)
offshore_gnc_tool(relay_bench SOURCES src/relay/relay_bench_main.cpp ROS)
# relay_node: the same ROS side as the Relay nodelet, built from the relay's own sources and linked only with
# what they use (roscpp, topic_tools, diagnostic_updater, OpenSSL, zlib): no plugin loading and none of the
# stack's PCL/OpenCV/GDAL libraries at start-up (0.13 s of dynamic loading), so the relay is up quickly.
add_executable(relay_node src/relay/relay_node_main.cpp src/relay/engine.cpp src/relay/policy.cpp
               src/relay/wire.cpp src/relay/key.cpp src/ros/ros_params.cpp)
target_include_directories(relay_node PRIVATE include)
target_include_directories(relay_node SYSTEM PRIVATE ${catkin_INCLUDE_DIRS} ${EIGEN3_INCLUDE_DIR})
target_link_libraries(relay_node ${roscpp_LIBRARIES} ${topic_tools_LIBRARIES} ${diagnostic_updater_LIBRARIES}
                      OpenSSL::Crypto ZLIB::ZLIB pthread)
target_link_options(relay_node PRIVATE -Wl,--as-needed)
add_dependencies(relay_node ${PROJECT_NAME}_generate_messages_cpp)
install(TARGETS relay_node RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
# the deployment-key tool (launch/relay.launch runs its --check on hardware)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/relay-key DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/scripts)
