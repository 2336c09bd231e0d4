# can: SocketCAN driver (libsocketcan for bus-off restart), codecs, gateway and emulator nodelets, can_decode.
find_library(OFFSHORE_GNC_SOCKETCAN_LIB socketcan REQUIRED)
target_link_libraries(offshore_gnc_can PUBLIC ${OFFSHORE_GNC_SOCKETCAN_LIB})
offshore_gnc_tool(can_decode SOURCES src/can/can_decode_main.cpp)
# Tests that need a real vcan0: test/suites/can_vcan.sh runs them, in a VM when the host kernel has no CAN.
# Debian's prebuilt libgtest: catkin's own gtest targets do not exist yet when module.cmake is read.
if(CATKIN_ENABLE_TESTING)
  find_package(GTest REQUIRED)
  file(GLOB can_vcan_tests CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/unit/can/vcan/*.cpp)
  add_executable(test_can_vcan ${can_vcan_tests})
  target_link_libraries(test_can_vcan offshore_gnc_can GTest::gtest_main)
  set_target_properties(test_can_vcan PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/lib/${PROJECT_NAME})
endif()
