// What every decoded telegram must satisfy, whatever bytes it came from. Both LMS fuzz
// targets check it; a violation aborts (the fuzzer reports it as a crash).
#pragma once

#include "ugv/sick_lms2xx/telegram.hpp"

namespace ugv::fuzz {

// Decodes t as a scan and as every reply the session reads, and checks:
//  - the telegram's spans lie inside its raw bytes and LEN is within kMaxLen;
//  - a decoded scan has at most (kMaxLen - 4) / 2 values (what a LEN of 812 can carry),
//    one flag and one field byte per value, and each range is NaN exactly when its flag is
//    not ok, otherwise within [0, range_max_m(units)];
//  - a configuration reply is at least kConfigMinBytes long (its accessors index into it).
void check_telegram(const sick_lms2xx::Telegram& t);

}  // namespace ugv::fuzz
