// Time stamps. utime = microseconds since the Unix epoch (CLOCK_REALTIME), the LCM convention.
#pragma once

#include <cstdint>

namespace ugv::io {

// CLOCK_REALTIME now, in microseconds since the Unix epoch.
int64_t now_utime();

// CLOCK_MONOTONIC now, in microseconds: for timeouts and rates, never for stamps on the wire.
int64_t monotonic_us();

}  // namespace ugv::io
