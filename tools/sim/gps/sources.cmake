# ugv-sim gps: the NovAtel OEM4-class receiver emulator. The emulator logic is a library of
# its own (no I/O) so the session's unit tests can run against it; gps_command.cpp is the pty.
add_library(ugv_sim_gps STATIC ${CMAKE_CURRENT_LIST_DIR}/gps_emulator.cpp)
target_include_directories(ugv_sim_gps PUBLIC ${CMAKE_CURRENT_LIST_DIR}/include PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../include)
target_link_libraries(ugv_sim_gps PUBLIC ugv_novatel PRIVATE ugv_warnings)

target_sources(ugv-sim PRIVATE ${CMAKE_CURRENT_LIST_DIR}/gps_command.cpp)
target_link_libraries(ugv-sim PRIVATE ugv_sim_gps ugv_io)
target_include_directories(ugv-sim PRIVATE ${CLI11_INCLUDE_DIR})
