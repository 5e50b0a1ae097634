// Every event of an LCM log file in order, for the calibration commands.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <string>

namespace ugv::calibrate_tool {

// Calls on_event for each event; false when the file is not an LCM log.
template <typename F>
bool for_each_event(const std::string& path, F&& on_event)
{
    lcm::LogFile log(path, "r");
    if (!log.good()) return false;
    while (const lcm::LogEvent* ev = log.readNextEvent()) on_event(*ev);
    return true;
}

}  // namespace ugv::calibrate_tool
