// The host clock's synchronisation as the kernel keeps it (adjtimex / ntp_adjtime, read
// only): whether an NTP daemon (chrony) has it synchronised and the error bounds it
// maintains. Every daemon's STATUS carries it (docs/time.md), so one look at the STATUS
// messages shows which host of a vehicle has a clock nobody keeps.
#pragma once

#include <cstdint>

namespace ugv::runtime {

struct HostClockState
{
    bool synchronised = false;   // the kernel's clock state is not TIME_ERROR (STA_UNSYNC clear)
    int64_t est_error_us = -1;   // the kernel's estimated error (esterror); -1 when unread
    int64_t max_error_us = -1;   // its maximum error (maxerror; grows 500 ppm while unsynchronised)
    int64_t pps_status = 0;      // 1 when the kernel disciplines the clock from a PPS signal (STA_PPSTIME|STA_PPSFREQ)
    int64_t test_offset_us = 0;  // UGV_CLOCK_OFFSET_S in effect (test aid, io/clock.hpp); 0 in service

    template <class F>
    void visit(F&& f) const
    {
        f("host_clock_synchronised", static_cast<int64_t>(synchronised));
        f("host_clock_est_error_us", est_error_us);
        f("host_clock_max_error_us", max_error_us);
        f("host_clock_pps", pps_status);
        f("host_clock_test_offset_us", test_offset_us);
    }
};

// Reads the kernel's state now (a read-only adjtimex: no privilege needed). A failing call
// leaves the defaults: not synchronised, errors -1.
HostClockState read_host_clock();

}  // namespace ugv::runtime
