# ugv-sim gps: the NovAtel OEM4-class receiver emulator.
ugv_sim_emulator(gps LIBS ugv_novatel COMMAND_LIBS ugv_io)
