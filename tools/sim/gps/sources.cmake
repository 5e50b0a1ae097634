# ugv-sim gps: the NovAtel OEM4-class receiver emulator.
ugv_sim_emulator(gps MODEL_SOURCES position_error.cpp LIBS ugv_novatel COMMAND_LIBS ugv_io)
