# relay: OpenSSL (HMAC-SHA256 frame authentication) and zlib (optional compression) in the ROS-free core.
find_package(OpenSSL REQUIRED)
find_package(ZLIB REQUIRED)
target_link_libraries(offshore_gnc_relay PUBLIC OpenSSL::Crypto ZLIB::ZLIB)
offshore_gnc_tool(relay_bench SOURCES src/relay/relay_bench_main.cpp ROS)
# relay_node: the Relay nodelet's ROS side (RelayRos) as a plain node: no plugin loading, and (--as-needed)
# none of the stack's PCL/OpenCV/GDAL libraries at start-up, so the relay is up quickly.
offshore_gnc_tool(relay_node SOURCES src/relay/relay_node_main.cpp ROS)
# the deployment-key tool (launch/relay.launch runs its --check on hardware)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/relay-key DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/scripts)
