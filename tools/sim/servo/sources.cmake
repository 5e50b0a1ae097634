# ugv-sim servo: a CiA 402 drive (servo_emulator, over object_dictionary) behind an slcan
# adapter (slcan_adapter) whose serial output serial_line_faults damages.
ugv_sim_emulator(servo MODEL_SOURCES object_dictionary.cpp slcan_adapter.cpp serial_line_faults.cpp
  LIBS ugv_canopen ugv_io COMMAND_LIBS ugv_io)
