#include "ugv/runtime/notify.hpp"

#include <systemd/sd-daemon.h>

namespace ugv::runtime {

Notifier::Notifier()
{
    uint64_t usec = 0;
    // unset_environment = 0: child processes are none of our business, but keep it visible.
    if (sd_watchdog_enabled(0, &usec) > 0) watchdog_interval_us_ = static_cast<int64_t>(usec / 2);
}

void Notifier::ready() { sd_notify(0, "READY=1"); }
void Notifier::status(const std::string& s) { sd_notify(0, ("STATUS=" + s).c_str()); }
void Notifier::watchdog() { sd_notify(0, "WATCHDOG=1"); }
void Notifier::stopping() { sd_notify(0, "STOPPING=1"); }

}  // namespace ugv::runtime
