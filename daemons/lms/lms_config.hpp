// ugv-lms configuration: every key, its default and its range (docs/lms.md lists them).
#pragma once

#include <string>

#include "ugv/runtime/config.hpp"
#include "ugv/sick_lms2xx/session.hpp"

namespace ugv::lms_daemon {

struct LmsConfig
{
    std::string device = "/dev/ugv/lms";  // serial port (RS-422 adapter)
    std::string channel = "LMS_SCAN";
    std::string raw_channel = "RAW_LMS";
    std::string sensor_id = "lms";
    bool publish_raw = false;
    sick_lms2xx::SessionConfig session;
};

// Reads and validates every key; a bad value throws runtime::ConfigError (`FILE: KEY: why`).
LmsConfig read_config(runtime::Config& cfg);

}  // namespace ugv::lms_daemon
