// ugv-gps configuration: every key, its default and its range (docs/gps.md lists them).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ugv/novatel/session.hpp"
#include "ugv/runtime/config.hpp"

namespace ugv::gps_daemon {

enum class Protocol { automatic, novatel, nmea };

struct GpsConfig
{
    std::string device = "/dev/ugv/gps";
    int baud = 9600;                       // the rate the port is opened at
    int com_baud = 0;                      // configure mode: switch the receiver to this (0 = keep)
    Protocol protocol = Protocol::automatic;
    bool configure = true;                 // mode = "configure" | "passive"
    std::vector<novatel::LogRequest> logs; // configure mode: what to LOG and how often
    std::string channel_fix = "GPS_FIX";
    std::string channel_vel = "GPS_VEL";
    std::string channel_raw = "RAW_GPS";
    bool publish_raw = false;
    int leap_seconds = 18;
    int64_t output_latency_us = 0;         // receiver latency used when its clock is not FINE
    int64_t silence_timeout_us = 0;        // resolved: 0 in the file = 5 x the fastest log period
    int reply_timeout_ms = 1000;
    std::string raw_device_name = "gps";
};

// Reads and validates every key (throws runtime::ConfigError, the daemon exits 2).
GpsConfig read_config(runtime::Config& config);

// "BESTPOSB" or "BESTPOSB 0.25" -> request; default_period_s when no period is given.
// Throws std::invalid_argument with the reason.
novatel::LogRequest parse_log_entry(const std::string& entry, double default_period_s);

}  // namespace ugv::gps_daemon
