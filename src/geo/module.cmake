offshore_gnc_tool(geo_bench SOURCES src/geo/geo_bench.cpp)
