# models: YAML parameter files (yaml-cpp) in the ROS-free core; the model_run and model_manoeuvre tools.
find_package(yaml-cpp REQUIRED)
target_link_libraries(offshore_gnc_models PUBLIC yaml-cpp)
offshore_gnc_tool(model_run SOURCES src/models/model_run_main.cpp)
offshore_gnc_tool(model_manoeuvre SOURCES src/models/model_manoeuvre_main.cpp)
offshore_gnc_tool(models_bench SOURCES src/models/models_bench.cpp)
