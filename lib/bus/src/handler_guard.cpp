#include "handler_guard.hpp"

#include <spdlog/spdlog.h>

namespace ugv::bus::detail {

void call_guarded(const RawHandler& handler, BusCounters& counters, const std::string& channel, const uint8_t* data,
                  std::size_t size, int64_t recv_utime)
{
    try {
        handler(channel, data, size, recv_utime);
    } catch (const std::exception& e) {
        // Only the first few are logged; the counter keeps the total.
        if (++counters.handler_errors <= 10) spdlog::error("handler for {} threw: {}", channel, e.what());
    } catch (...) {
        if (++counters.handler_errors <= 10) spdlog::error("handler for {} threw a non-standard exception", channel);
    }
}

}  // namespace ugv::bus::detail
