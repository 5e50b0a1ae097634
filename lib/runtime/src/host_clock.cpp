#include "ugv/runtime/host_clock.hpp"

#include <sys/timex.h>

#include "ugv/io/clock.hpp"

namespace ugv::runtime {

HostClockState read_host_clock()
{
    HostClockState s;
    s.test_offset_us = io::clock_test_offset_us();
    timex tx{};
    tx.modes = 0;  // read only
    const int state = ::adjtimex(&tx);
    if (state < 0) return s;
    s.synchronised = state != TIME_ERROR && (tx.status & STA_UNSYNC) == 0;
    s.est_error_us = tx.esterror;
    s.max_error_us = tx.maxerror;
    s.pps_status = (tx.status & (STA_PPSTIME | STA_PPSFREQ)) != 0 ? 1 : 0;
    return s;
}

}  // namespace ugv::runtime
