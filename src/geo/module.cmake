# geo: GeographicLib (LocalCartesian, UTM) in the ROS-free core; the benchmark tool.
target_include_directories(offshore_gnc_geo SYSTEM PUBLIC ${GeographicLib_INCLUDE_DIRS})
target_link_libraries(offshore_gnc_geo PUBLIC ${GeographicLib_LIBRARIES})
offshore_gnc_tool(geo_bench SOURCES src/geo/geo_bench.cpp)
