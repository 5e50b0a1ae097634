# ugv-sim lms: the SICK LMS 2xx emulator. fault_spec.cpp parses the --fault plans.
ugv_sim_emulator(lms MODEL_SOURCES fault_spec.cpp lms_variants.cpp LIBS ugv_sick_lms2xx COMMAND_LIBS ugv_io)
