# ugv-sim lms: the SICK LMS 2xx emulator. The device model is a library of its own so the
# driver's tests can run it in-process, without a pseudo-terminal.
ugv_add_library(NAME ugv_sim_lms
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/lms_device.cpp ${CMAKE_CURRENT_LIST_DIR}/fault_spec.cpp
  PUBLIC_LIBS ugv_sick_lms2xx)
target_include_directories(ugv_sim_lms PUBLIC ${CMAKE_CURRENT_LIST_DIR} PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../include)
target_sources(ugv-sim PRIVATE ${CMAKE_CURRENT_LIST_DIR}/lms_command.cpp)
target_include_directories(ugv-sim PRIVATE ${CLI11_INCLUDE_DIR})
target_link_libraries(ugv-sim PRIVATE ugv_sim_lms ugv_io)
