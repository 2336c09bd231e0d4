# relay: OpenSSL (HMAC-SHA256 frame authentication) and zlib (optional compression) in the ROS-free core.
find_package(OpenSSL REQUIRED)
find_package(ZLIB REQUIRED)
target_link_libraries(offshore_gnc_core PUBLIC OpenSSL::Crypto ZLIB::ZLIB)
offshore_gnc_tool(relay_bench SOURCES src/relay/relay_bench_main.cpp ROS)
