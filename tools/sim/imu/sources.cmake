# ugv-sim imu: the MicroStrain 3DM-GX1 emulator. The emulator logic is a library of its own
# (no I/O) so the driver's session tests can run against it; imu_command.cpp is the pty I/O.
add_library(ugv_sim_imu STATIC ${CMAKE_CURRENT_LIST_DIR}/gx1_emulator.cpp)
target_include_directories(ugv_sim_imu PUBLIC ${CMAKE_CURRENT_LIST_DIR}/include PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../include)
target_link_libraries(ugv_sim_imu PUBLIC ugv_microstrain_gx1 PRIVATE ugv_warnings)

target_sources(ugv-sim PRIVATE ${CMAKE_CURRENT_LIST_DIR}/imu_command.cpp)
target_link_libraries(ugv-sim PRIVATE ugv_sim_imu ugv_io)
target_include_directories(ugv-sim PRIVATE ${CLI11_INCLUDE_DIR})
