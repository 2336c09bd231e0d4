# models: YAML parameter files (yaml-cpp) and the identification's optimiser (Ceres) in the ROS-free core; the
# model_run, model_manoeuvre and model_fit tools (model_fit reads rosbags too: ROS) and the fit benchmark's C API.
find_package(yaml-cpp REQUIRED)
find_package(Ceres REQUIRED)
target_link_libraries(offshore_gnc_models PUBLIC yaml-cpp Ceres::ceres)
offshore_gnc_tool(model_run SOURCES src/models/model_run_main.cpp)
offshore_gnc_tool(model_manoeuvre SOURCES src/models/model_manoeuvre_main.cpp)
offshore_gnc_tool(model_fit SOURCES src/models/model_fit_main.cpp ROS)
offshore_gnc_tool(models_bench SOURCES src/models/models_bench.cpp)
# bench/model_fit.sh loads this with ctypes: SciPy and Ceres on the same residuals
add_library(offshore_gnc_model_fit_bench SHARED src/models/model_fit_bench.cpp)
target_link_libraries(offshore_gnc_model_fit_bench offshore_gnc_models)
