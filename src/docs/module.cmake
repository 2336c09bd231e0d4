# docs: the reference generated from the code. param_docs prints docs/parameters.md from every module's parameter
# tables (a test compares the file with its output), so it stands above every module whose tables it prints.
offshore_gnc_tool(param_docs SOURCES src/docs/param_docs_main.cpp)
