# ugv-sim imu: the MicroStrain 3DM-GX1 emulator.
ugv_sim_emulator(imu MODEL_SOURCES ahrs_model.cpp LIBS ugv_microstrain_gx1 COMMAND_LIBS ugv_io)
