// Time stamps. utime = microseconds since the Unix epoch (CLOCK_REALTIME), the LCM convention.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace ugv::io {

// CLOCK_REALTIME now, in microseconds since the Unix epoch, plus the test offset below.
int64_t now_utime();

// CLOCK_MONOTONIC now, in microseconds: for timeouts and rates, never for stamps on the wire.
int64_t monotonic_us();

// A test and bench aid, faketime-style: UGV_CLOCK_OFFSET_S (seconds, may be negative,
// |offset| <= 86400) is added to every now_utime() of the process, so one process plays a
// host whose clock is off (docs/time.md). Read once, at the first call; 0 when unset.
// A value that is not a number in that range prints one line and exits with status 2.
int64_t clock_test_offset_us();

// The parse behind it: the offset in us, or nullopt with why (tests).
std::optional<int64_t> parse_clock_offset(const char* text, std::string& why);

inline constexpr const char* kClockOffsetEnv = "UGV_CLOCK_OFFSET_S";

}  // namespace ugv::io
