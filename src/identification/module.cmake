# identification: fitting the vehicle models to a team's logs (thesis chapter 3) with Ceres, the only module that
# links it; the model_fit tool (it reads rosbags too: ROS) and the fit benchmark's C API.
find_package(Ceres REQUIRED)
target_link_libraries(offshore_gnc_identification PUBLIC Ceres::ceres)
offshore_gnc_tool(model_fit SOURCES src/identification/model_fit_main.cpp ROS)
# bench/model_fit.sh loads this with ctypes: SciPy and Ceres on the same residuals
add_library(offshore_gnc_model_fit_bench SHARED src/identification/model_fit_bench.cpp)
target_link_libraries(offshore_gnc_model_fit_bench offshore_gnc_identification)
