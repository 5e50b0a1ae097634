# ugv-sim world: one simulated vehicle (lib/simworld) driving the four device emulators of
# the folders beside this one, each on its own pseudo-terminal, from one clock.
target_sources(ugv-sim PRIVATE ${CMAKE_CURRENT_LIST_DIR}/world_command.cpp ${CMAKE_CURRENT_LIST_DIR}/device_ports.cpp
  ${CMAKE_CURRENT_LIST_DIR}/run_folder.cpp)
target_link_libraries(ugv-sim PRIVATE ugv_simworld ugv_sim_lms ugv_sim_gps ugv_sim_imu ugv_sim_servo ugv_lcmtypes
  ugv_geometry ugv_io ugv_bus)
