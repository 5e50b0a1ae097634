// Calls a handler so that nothing escapes into LCM's C code: an exception is caught, counted
// and logged (rate-limited by the caller's log).
#pragma once

#include "ugv/bus/bus.hpp"

namespace ugv::bus::detail {

void call_guarded(const RawHandler& handler, BusCounters& counters, const std::string& channel, const uint8_t* data,
                  std::size_t size, int64_t recv_utime);

}  // namespace ugv::bus::detail
