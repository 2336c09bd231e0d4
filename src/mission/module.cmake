# mission: the scenario check the main job runs before starting anything (uses the simulator's loader).
offshore_gnc_tool(scenario_check SOURCES src/mission/scenario_check_main.cpp)
