# docs: what is generated from the code. param_docs prints docs/parameters.md from every module's parameter
# tables and, with --cfg, the dynamic_reconfigure scripts cfg/*.cfg (the core here writes them; tests compare the
# checked-in files with its output), so it stands above every module whose tables it prints.
offshore_gnc_tool(param_docs SOURCES src/docs/param_docs_main.cpp)
# the vehicles' manifests, for the launch files' blocks and the simulator seeds' columns
target_compile_definitions(param_docs PRIVATE OFFSHORE_GNC_CONFIG_DIR="${PROJECT_SOURCE_DIR}/config")
