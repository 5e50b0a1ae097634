# ugv-sim world: one simulated vehicle (lib/simworld) driving the four device emulators of
# the folders beside this one, each on its own pseudo-terminal, from one clock.
ugv_sim_command(world SOURCES device_ports.cpp run_folder.cpp
  LIBS ugv_simworld ugv_sim_lms ugv_sim_gps ugv_sim_imu ugv_sim_servo ugv_lcmtypes ugv_geometry ugv_io ugv_bus
    ugv_runtime)
