# ugv-sim servo: a CiA 402 drive behind an slcan adapter on a pseudo-terminal. The emulator
# logic is a library of its own (no I/O) so that tests can drive it directly.
add_library(ugv_sim_servo STATIC
  ${CMAKE_CURRENT_LIST_DIR}/object_dictionary.cpp
  ${CMAKE_CURRENT_LIST_DIR}/drive_emulator.cpp
  ${CMAKE_CURRENT_LIST_DIR}/slcan_adapter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/serial_line_faults.cpp)
target_include_directories(ugv_sim_servo PUBLIC ${CMAKE_CURRENT_LIST_DIR} ${CMAKE_CURRENT_LIST_DIR}/../include)
target_link_libraries(ugv_sim_servo PUBLIC ugv_canopen ugv_io PRIVATE ugv_warnings)
target_sources(ugv-sim PRIVATE ${CMAKE_CURRENT_LIST_DIR}/servo_main.cpp)
target_link_libraries(ugv-sim PRIVATE ugv_sim_servo)
