#include "foxglove_config.hpp"

#include <cmath>
#include <regex>

#include <asio/ip/address.hpp>

namespace ugv::foxglove_daemon {

namespace {

void check_regex(runtime::Config& cfg, const char* key, const std::string& text)
{
    try {
        std::regex re(text);
    } catch (const std::regex_error& e) {
        cfg.fail(key, std::string("not a valid regex: ") + e.what());
    }
}

}  // namespace

FoxgloveConfig read_config(runtime::Config& cfg)
{
    FoxgloveConfig c;
    c.channels = cfg.get_channel_regex("channels", c.channels);
    c.no_raw = cfg.get_string("no_raw", c.no_raw);
    if (!c.no_raw.empty()) check_regex(cfg, "no_raw", c.no_raw);
    c.address = cfg.get_string("address", c.address);
    std::error_code ec;
    (void)asio::ip::make_address(c.address, ec);
    if (ec) cfg.fail("address", "not an IPv4 or IPv6 address: " + c.address);
    c.port = static_cast<int>(cfg.get_int("port", c.port, 1, 65535));
    c.max_clients = static_cast<int>(cfg.get_int("max_clients", c.max_clients, 1, 256));
    c.client_queue_bytes =
        static_cast<std::size_t>(cfg.get_int("client_queue_kb", static_cast<int64_t>(c.client_queue_bytes >> 10), 64,
                                             1 << 20))
        << 10;
    c.status_channel = cfg.get_channel("status_channel", c.status_channel);
    c.health_timeout_us = static_cast<int64_t>(std::llround(cfg.get_double("health_timeout_s", 5.0, 0.1, 600.0) * 1e6));
    return c;
}

}  // namespace ugv::foxglove_daemon
