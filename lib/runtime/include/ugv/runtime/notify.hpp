// systemd notification (sd_notify). Without systemd NOTIFY_SOCKET is unset and every call
// is a no-op; tests bind their own socket and point NOTIFY_SOCKET at it.
#pragma once

#include <cstdint>
#include <string>

namespace ugv::runtime {

class Notifier
{
public:
    Notifier();
    void ready();                       // READY=1
    void status(const std::string& s);  // STATUS=s (one line)
    void watchdog();                    // WATCHDOG=1
    void stopping();                    // STOPPING=1
    // The watchdog period systemd expects pings at (half of WatchdogSec), 0 when disabled.
    int64_t watchdog_interval_us() const { return watchdog_interval_us_; }

private:
    int64_t watchdog_interval_us_ = 0;
};

}  // namespace ugv::runtime
